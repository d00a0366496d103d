"""A compiled query path sampled at times: every joint's frame and every frame of the model
in the root.

Shared by velocities, Jacobians and the welding process: they need, per sample, where each
joint of the path is (``oMi``) and where the frames are (``oMf``); which joints move which
frame relative to which the caller asks :func:`._twists.joint_signs`. A model that holds
more frames than the path's two ends (``prepare_path(..., also=...)``) is sampled once for
every pair of them.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..values.interpolation import SegmentSearches
from ..values.se3 import Transform, rotations_first, vectors_first
from ._model import CompiledModel
from ._plan import QueryPlan
from ._sampling import KERNEL_CHUNK, JointSampler, sample_joints
from ._twists import Twist, robot_joint_axes

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
        Per joint, its origin ``p_j`` in ``C``, metres.
    parent_rotations : dict of int to array
        Per free-flyer below another joint, that joint's rotation in ``C``.
    unit_twists : dict of int to Twist
        Per robot joint, its twist per unit of joint velocity in ``C``'s axes.
    placements : dict of str to Transform
        Every frame of the model (the query frame, the reference frame and any other it
        holds) in ``C``.
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
    placements: dict[str, Transform]
    times: NDArray[np.int64]
    searches: SegmentSearches


def sampled_parts(plan: QueryPlan) -> Iterator[tuple[slice, SampledPath]]:
    """The plan's path (a compiled one) sampled in slices of at most ``KERNEL_CHUNK``
    times, with where each goes in the result.

    Keeps of each joint's frame only what the twists need (its origin, its axis, a
    free-flyer's parent rotation), so that the forward kinematics can let the frames go
    (see :meth:`CompiledModel.joint_frames`).
    """
    prepared = plan.path
    model = prepared.model
    assert model is not None, "a static path has no model to sample"
    frames = list(model.frame_ids)
    parents = model.frame_parents(frames)
    # the moving frames' free-flyers below another joint: their twists turn by its rotation
    flyer_parents = {index: joint.parent for index, joint in enumerate(model.joints)
                     if joint.joint is None and joint.parent >= 0}
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
            origins[index] = vectors_first(translation)
            robot_joint = model.joints[index].joint
            if robot_joint is not None:
                unit_twists[index] = robot_joint_axes(robot_joint, rotations_first(rotation))
        parent_rotations = {index: rotations_first(kept[parent][0])
                            for index, parent in flyer_parents.items()}
        placements = {name: (rotations_first(rotation), vectors_first(translation))
                      for name, (rotation, translation)
                      in zip(frames, model.frame_placements_in_root(kept, frames), strict=True)}
        yield part, SampledPath(model, prepared.samplers, origins, parent_rotations,
                                unit_twists, placements, times, searches)
