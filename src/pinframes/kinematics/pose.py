"""``FrameTree.pose``: the pose of one frame in another at times, and the times it takes
when given none.

The path is prepared once per tree version (:mod:`._path`), the times planned
(:mod:`._times`); then a query at one or a few times takes Pinocchio's own forward
kinematics time by time (:mod:`._one_time`), a longer one samples every joint
(:mod:`._sampling`) and composes the path in chunks of :data:`~._sampling.CHUNK` samples
with the sample axis last (:meth:`CompiledModel.forward_kinematics`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values.pose import Pose, trusted_pose
from ..values.se3 import Transform, compose, inverse, to_stacks
from ..values.timeconv import TimeAxis
from ..values.timeline import QueryTimeline, TimedSource
from ._description import TreeDescription
from ._one_time import one_time_plan, takes_few_times
from ._path import PreparedPath, prepare_path, require_finite_pose
from ._sampling import CHUNK, sample_joints, warn_joints_without_samples
from ._times import basis_shifts, checked_timeline, plan_timeline

__all__ = ["default_times", "evaluate_pose"]


def evaluate_pose(
    tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
    extrapolation: str,
) -> Pose:
    """``tree.pose(frame, relative_to, times, time_ref)``; arguments already checked."""
    path = prepare_path(tree, frame, relative_to)
    sources = list(path.sources)
    timeline = checked_timeline(tree, path, times, time_ref, extrapolation)
    offsets = timeline.result_offsets
    if path.static is not None:
        if offsets is None:
            return trusted_pose(*path.static)
        rotation, translation = to_stacks(path.static, offsets.shape[0])
    elif path.model is not None and takes_few_times(timeline, path.model):
        # Pinocchio's own kinematics, time by time
        plan = one_time_plan(tree, path)
        if plan.holds_rest_values:
            warn_joints_without_samples(tree)
        rotation, translation = plan.poses(timeline.evaluation_times,
                                           basis_shifts(sources, timeline))
    else:
        rotation, translation = _evaluate_in_chunks(tree, path, sources, timeline)
    if path.static is None:  # a static path was checked once, when it was prepared
        require_finite_pose(translation, frame, relative_to)
    if offsets is None:
        return trusted_pose(rotation[0], translation[0])
    return trusted_pose(rotation, translation, offsets, timeline.reference)


def default_times(tree: TreeDescription, frame: str, relative_to: str) -> TimeAxis | None:
    """The times ``tree.pose(frame, relative_to)`` evaluates at when given none."""
    path = prepare_path(tree, frame, relative_to)
    timeline = plan_timeline(tree, list(path.sources), None, None)
    offsets = timeline.result_offsets
    if offsets is None:
        return None
    return TimeAxis(offsets, timeline.reference)


def _evaluate_in_chunks(
    tree: TreeDescription, path: PreparedPath, sources: list[TimedSource],
    timeline: QueryTimeline,
) -> Transform:
    """:func:`_evaluate_model` over slices of the timeline, so that the temporary arrays of
    a long query stay small (and cache-friendly); the result, ``(N, 3, 3)`` rotations and
    ``(N, 3)`` translations, is filled in place."""
    times = timeline.evaluation_times
    if times is None:  # nothing on the path is sampled: one static pose
        return to_stacks(_evaluate_model(tree, path, sources, times, timeline), 1)
    count = times.shape[0]
    rotation, translation = np.empty((count, 3, 3)), np.empty((count, 3))
    for start in range(0, count, CHUNK):
        part = slice(start, start + CHUNK)
        rotation[part], translation[part] = to_stacks(
            _evaluate_model(tree, path, sources, times[part], timeline),
            min(count, start + CHUNK) - start)
    return rotation, translation


def _evaluate_model(
    tree: TreeDescription, path: PreparedPath, sources: list[TimedSource],
    times: NDArray[np.int64] | None, timeline: QueryTimeline,
) -> Transform:
    """The pose of the query frame in the reference frame at ``times`` (timeline basis),
    samples last (see :mod:`pinframes.values.se3`)."""
    model = path.model
    assert model is not None
    samples = sample_joints(tree, model, path.placed_keyframes, times,
                            basis_shifts(sources, timeline))
    frame_pose, reference_pose = model.forward_kinematics(
        samples, [path.frame, path.relative_to])
    return compose(inverse(reference_pose), frame_pose)
