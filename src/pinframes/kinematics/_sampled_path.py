"""A compiled query path sampled at times: every joint's frame and both ends in the root.

Shared by velocities and Jacobians: both need, per sample, where each joint of the path is
(``oMi``), where the frame and the reference frame are (``oMf``), and which joints move
which end.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values.se3 import Transform
from ..values.timeline import QueryTimeline
from ._description import TreeDescription
from ._model import CompiledModel
from ._path import PreparedPath, prepare_path
from ._sampling import CHUNK, SegmentSearches, sample_joints
from ._times import basis_shifts, checked_timeline
from ._twists import Twist, joint_signs, robot_joint_axes

__all__ = ["PlannedQuery", "SampledPath", "plan_query", "sample_path"]


@dataclass(frozen=True)
class SampledPath:
    """What velocities and Jacobians need of a query path at ``N`` samples, in its model's
    root ``C``; arrays samples first (``(N, 3)``, ``(N, 3, 3)``) or static.

    Attributes
    ----------
    model : CompiledModel
        The compiled path.
    origins : dict of int to array
        Per joint that moves an end (a key of ``signs``), its origin ``p_j`` in ``C``, metres.
    parent_rotations : dict of int to array
        Per such free-flyer below another joint, that joint's rotation in ``C``.
    unit_twists : dict of int to Twist
        Per such robot joint, its twist per unit of joint velocity in ``C``'s axes.
    frame, relative_to : Transform
        The query frame and the reference frame in ``C``.
    signs : dict of int to float
        +1 for the joints moving the frame, -1 for those moving the reference frame.
    times : ndarray of int64
        The sample times on the timeline's basis.
    searches : SegmentSearches
        Where they fall among each moving thing's samples (for their rates).
    """

    model: CompiledModel
    origins: dict[int, NDArray[np.float64]]
    parent_rotations: dict[int, NDArray[np.float64]]
    unit_twists: dict[int, Twist]
    frame: Transform
    relative_to: Transform
    signs: dict[int, float]
    times: NDArray[np.int64]
    searches: SegmentSearches


@dataclass(frozen=True)
class PlannedQuery:
    """A query's compiled path, its timeline and the result's times."""

    prepared: PreparedPath
    timeline: QueryTimeline
    count: int
    offsets: NDArray[np.int64] | None

    @property
    def times(self) -> NDArray[np.timedelta64] | None:
        """Result times after :attr:`reference_time`, ``timedelta64[ns]``; None if static."""
        return None if self.offsets is None else self.offsets.astype("timedelta64[ns]")

    @property
    def reference_time(self) -> np.datetime64 | None:
        return self.timeline.reference

    def chunks(self, tree: TreeDescription) -> Iterator[tuple[slice, SampledPath]]:
        """The path sampled in slices of at most ``CHUNK`` times (moving paths only)."""
        prepared, timeline = self.prepared, self.timeline
        assert prepared.model is not None, "a static path has no model to sample"
        shifts = basis_shifts(list(prepared.sources), timeline)
        signs = joint_signs(prepared.model, prepared.frame, prepared.relative_to)
        times = timeline.evaluation_times
        if times is None:
            times = np.zeros(1, dtype=np.int64)
        for start in range(0, self.count, CHUNK):
            part = slice(start, start + CHUNK)
            yield part, sample_path(tree, prepared, signs, shifts, times[part])


def plan_query(tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
               extrapolation: str) -> PlannedQuery:
    """Compile (or reuse) the path and plan its timeline by the rules of ``pose()``."""
    prepared = prepare_path(tree, frame, relative_to)
    timeline = checked_timeline(tree, prepared, times, time_ref, extrapolation)
    offsets = timeline.result_offsets
    return PlannedQuery(prepared, timeline, 1 if offsets is None else offsets.shape[0],
                        offsets)


def sample_path(tree: TreeDescription, prepared: PreparedPath, signs: dict[int, float],
                shifts: dict[str, int], times: NDArray[np.int64]) -> SampledPath:
    """The path of ``prepared`` (a moving one) at ``times`` (timeline basis).

    Keeps of each joint's frame only what the twists need (its origin, its axis, a
    free-flyer's parent rotation), so that the forward kinematics can let the frames go
    (see :meth:`CompiledModel.joint_frames`).
    """
    model = prepared.model
    assert model is not None, "a static path has no model to sample"
    searches = SegmentSearches(tree, times, shifts)
    samples = sample_joints(tree, model, prepared.placed_keyframes, times, shifts, searches)
    ends = model.frame_parents([prepared.frame, prepared.relative_to])
    # the moving frames' free-flyers below another joint: their twists turn by its rotation
    flyer_parents = {index: joint.parent for index, joint in enumerate(model.joints)
                     if index in signs and joint.joint is None and joint.parent >= 0}
    kept: dict[int, Transform] = {}
    origins: dict[int, NDArray[np.float64]] = {}
    unit_twists: dict[int, Twist] = {}
    for index, (rotation, translation) in model.joint_frames(samples):
        if index in ends or index in flyer_parents.values():
            kept[index] = (rotation, translation)
        if index not in signs:
            continue
        origins[index] = _vectors_first(translation)
        robot_joint = model.joints[index].joint
        if robot_joint is not None:  # copies: a column view would hold the whole rotation
            unit_twists[index] = _copied(robot_joint_axes(robot_joint, _rotations_first(rotation)))
    parent_rotations = {index: _rotations_first(kept[parent][0])
                        for index, parent in flyer_parents.items()}
    frame, relative_to = model.frame_placements_in_root(
        kept, [prepared.frame, prepared.relative_to])
    return SampledPath(model, origins, parent_rotations, unit_twists,
                       (_rotations_first(frame[0]), _vectors_first(frame[1])),
                       (_rotations_first(relative_to[0]), _vectors_first(relative_to[1])),
                       signs, times, searches)


def _rotations_first(rotation: NDArray[np.float64]) -> NDArray[np.float64]:
    """A ``(N, 3, 3)`` view of ``(3, 3, N)`` rotations; a static one stays the same object
    (the shared identity is still recognised)."""
    return np.moveaxis(rotation, -1, 0) if rotation.ndim == 3 else rotation


def _vectors_first(vector: NDArray[np.float64]) -> NDArray[np.float64]:
    """A ``(N, 3)`` view of ``(3, N)`` vectors; a static one stays as it is."""
    return vector.T if vector.ndim == 2 else vector


def _copied(twist: Twist) -> Twist:
    linear, angular = twist
    return (None if linear is None else np.ascontiguousarray(linear),
            None if angular is None else np.ascontiguousarray(angular))
