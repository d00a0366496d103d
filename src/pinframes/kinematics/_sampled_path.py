"""A compiled query path sampled at times: every joint's frame and both ends in the root.

Shared by velocities and Jacobians: both need, per sample, where each joint of the path is
(``oMi``), where the frame and the reference frame are (``oMf``), and which joints move
which end.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..values.interpolation import SegmentSearches
from ..values.se3 import Transform, rotations_first, vectors_first
from ._description import TreeDescription
from ._model import CompiledModel
from ._plan import QueryPlan
from ._sampling import KERNEL_CHUNK, JointSampler, sample_joints
from ._twists import Twist, joint_signs, robot_joint_axes

__all__ = ["SampledPath", "sampled_parts"]


@dataclass(frozen=True)
class SampledPath:
    """What velocities and Jacobians need of a query path at ``N`` samples, in its model's
    root ``C``; arrays samples first (``(N, 3)``, ``(N, 3, 3)``) or static.

    Attributes
    ----------
    model : CompiledModel
        The compiled path.
    samplers : tuple of JointSampler
        How each of its joints is sampled (:mod:`._sampling`).
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
    samplers: tuple[JointSampler, ...]
    origins: dict[int, NDArray[np.float64]]
    parent_rotations: dict[int, NDArray[np.float64]]
    unit_twists: dict[int, Twist]
    frame: Transform
    relative_to: Transform
    signs: dict[int, float]
    times: NDArray[np.int64]
    searches: SegmentSearches


def sampled_parts(tree: TreeDescription, plan: QueryPlan
                  ) -> Iterator[tuple[slice, SampledPath]]:
    """The plan's path (a moving one) sampled in slices of at most ``KERNEL_CHUNK`` times,
    with where each goes in the result.

    Keeps of each joint's frame only what the twists need (its origin, its axis, a
    free-flyer's parent rotation), so that the forward kinematics can let the frames go
    (see :meth:`CompiledModel.joint_frames`).
    """
    prepared = plan.path
    model = prepared.model
    assert model is not None, "a static path has no model to sample"
    ends = [prepared.frame, prepared.relative_to]
    signs = joint_signs(model, *ends)
    parents = model.frame_parents(ends)
    # the moving frames' free-flyers below another joint: their twists turn by its rotation
    flyer_parents = {index: joint.parent for index, joint in enumerate(model.joints)
                     if index in signs and joint.joint is None and joint.parent >= 0}
    for part, piece in plan.parts(KERNEL_CHUNK):
        times = piece.sample_times
        searches = SegmentSearches(times, piece.shifts)
        samples = sample_joints(prepared.samplers, times, piece.shifts, searches)
        kept: dict[int, Transform] = {}
        origins: dict[int, NDArray[np.float64]] = {}
        unit_twists: dict[int, Twist] = {}
        for index, (rotation, translation) in model.joint_frames(samples):
            if index in parents or index in flyer_parents.values():
                kept[index] = (rotation, translation)
            if index not in signs:
                continue
            origins[index] = vectors_first(translation)
            robot_joint = model.joints[index].joint
            if robot_joint is not None:
                unit_twists[index] = robot_joint_axes(robot_joint, rotations_first(rotation))
        parent_rotations = {index: rotations_first(kept[parent][0])
                            for index, parent in flyer_parents.items()}
        frame, relative_to = model.frame_placements_in_root(kept, ends)
        yield part, SampledPath(
            model, prepared.samplers, origins, parent_rotations, unit_twists,
            (rotations_first(frame[0]), vectors_first(frame[1])),
            (rotations_first(relative_to[0]), vectors_first(relative_to[1])),
            signs, times, searches)
