"""``FrameTree.pose``: the pose of one frame in another at times, and the times it takes
when given none.

The query is planned once (:func:`._plan.plan_query`: the path, prepared once per tree
version, and the timeline); then a query at one or a few times takes Pinocchio's own forward
kinematics time by time (:mod:`._one_time`), a longer one samples every joint
(:mod:`._sampling`) and composes the path in chunks of :data:`~._sampling.KERNEL_CHUNK` samples
with the sample axis last (:meth:`CompiledModel.forward_kinematics`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..values.numbers import require_finite_pose
from ..values.pose import Pose, trusted_pose
from ..values.se3 import Transform, compose, inverse, to_stacks
from ..values.timeconv import TimeAxis
from ._description import TreeDescription
from ._one_time import one_time_plan, takes_few_times
from ._plan import QueryPlan, plan_query
from ._sampling import KERNEL_CHUNK, sample_joints

__all__ = ["default_times", "evaluate_pose", "planned_pose", "planned_transforms"]


def evaluate_pose(
    tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
    extrapolation: str,
) -> Pose:
    """``tree.pose(frame, relative_to, times, time_ref)``; arguments already checked."""
    plan = plan_query(tree, frame, relative_to, times, time_ref, extrapolation)
    return planned_pose(tree, plan)


def planned_pose(tree: TreeDescription, plan: QueryPlan) -> Pose:
    """The pose of the plan's frame in its reference frame at the plan's times."""
    path, offsets = plan.path, plan.offsets
    if offsets is None and path.static is not None:
        rotation, translation = path.static
    else:
        rotation, translation = planned_transforms(tree, plan)
        if offsets is None:
            rotation, translation = rotation[0], translation[0]
    return trusted_pose(rotation, translation, offsets, plan.timeline.reference)


def planned_transforms(tree: TreeDescription, plan: QueryPlan) -> Transform:
    """The pose of the plan's frame in its reference frame at the plan's times as
    ``(N, 3, 3)`` rotations and ``(N, 3)`` translations (metres); ``N`` is 1 for a static
    result."""
    path = plan.path
    model = path.model
    if model is None:  # a static path, checked once when it was prepared
        assert path.static is not None
        return to_stacks(path.static, plan.count)
    if takes_few_times(plan.times, model):  # Pinocchio's own kinematics, time by time
        rotation, translation = one_time_plan(path).poses(plan.times, plan.shifts)
    else:  # the numpy kernels, samples last, a chunk at a time
        ends = [path.frame, path.relative_to]
        rotation, translation = np.empty((plan.count, 3, 3)), np.empty((plan.count, 3))
        for part, piece in plan.parts(KERNEL_CHUNK):
            samples = sample_joints(path.samplers, piece.times, piece.shifts)
            frame_pose, reference_pose = model.forward_kinematics(samples, ends)
            rotation[part], translation[part] = to_stacks(
                compose(inverse(reference_pose), frame_pose), part.stop - part.start)
    require_finite_pose(translation, path.frame, path.relative_to)
    return rotation, translation


def default_times(tree: TreeDescription, frame: str, relative_to: str) -> TimeAxis | None:
    """The times ``tree.pose(frame, relative_to)`` evaluates at when given none (a copy: the
    plan they come from is kept with the path, and the caller may write the copy)."""
    plan = plan_query(tree, frame, relative_to, None, None, "clamp")
    return None if plan.offsets is None else TimeAxis(plan.offsets.copy(), plan.reference_time)
