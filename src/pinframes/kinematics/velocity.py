"""``FrameTree.velocity``: how fast a frame moves relative to another, per sample.

Exact derivatives of what ``pose()`` interpolates (the ``rates`` of each moving thing's
interpolation scheme, :mod:`pinframes.values.interpolation`), carried through the compiled
model of the query path (see :mod:`._twists`). The linear velocity is that of the
frame's origin relative to the reference frame (the derivative of
``pose(frame, relative_to).translation``); the angular velocity ``w`` satisfies
``dR/dt = [w]x @ R`` for ``R = pose(frame, relative_to).rotation``. Both are written in the
axes of ``relative_to`` (Pinocchio's ``LOCAL_WORLD_ALIGNED`` when ``relative_to`` is the
model's root) or, rotated, in those of ``frame`` (Pinocchio's ``LOCAL``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values.se3 import IDENTITY
from ..values.timed import Timed
from ._description import TreeDescription
from ._plan import QueryPlan, plan_query
from ._sampled_path import SampledPath, sampled_parts
from ._sampling import MovingFrame
from ._twists import Twist, joint_signs, rotate, velocity_sum
from .pose import planned_transforms

__all__ = ["Velocity", "evaluate_velocity", "planned_velocity", "velocities_in_root"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Velocity(Timed):
    """Velocity of ``frame`` relative to ``relative_to`` per sample.

    Attributes
    ----------
    linear : ndarray, shape (T, 3)
        Velocity of the origin of ``frame`` relative to ``relative_to``, m/s.
    angular : ndarray, shape (T, 3)
        Angular velocity of ``frame`` relative to ``relative_to``, rad/s.
    times : ndarray of timedelta64[ns] or None
        Sample times after :attr:`reference_time`; None for a path on which nothing moves
        queried without times (then ``T`` is 1 and both velocities are zero).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from (the rules of ``pose()``).
    frame, relative_to, expressed_in : str
        The moving frame, the frame it moves relative to, and the frame whose axes the
        vectors are written in.
    """

    linear: FloatArray
    angular: FloatArray
    times: NDArray[np.timedelta64] | None
    reference_time: np.datetime64 | None
    frame: str
    relative_to: str
    expressed_in: str

    def __len__(self) -> int:
        return int(self.linear.shape[0])


def evaluate_velocity(tree: TreeDescription, frame: str, relative_to: str, times: Any,
                      time_ref: Any, extrapolation: str, expressed_in: str) -> Velocity:
    """``tree.velocity(...)``; frame names already checked."""
    plan = plan_query(tree, frame, relative_to, times, time_ref, extrapolation)
    return planned_velocity(tree, plan, expressed_in)


def planned_velocity(tree: TreeDescription, plan: QueryPlan, expressed_in: str) -> Velocity:
    """The velocity of the plan's frame relative to its reference frame at the plan's
    times, in the axes of ``expressed_in``."""
    frame, relative_to = plan.path.frame, plan.path.relative_to
    linear, angular = np.zeros((plan.count, 3)), np.zeros((plan.count, 3))
    if plan.path.static is None:
        for part, path in sampled_parts(plan):
            ((linear_c, angular_c),) = velocities_in_root(path, [(frame, relative_to)])
            axes = path.placements[frame if expressed_in == frame else relative_to][0]
            if axes is not IDENTITY[0]:  # the root's own axes need no turn
                rotation_t = np.swapaxes(axes, -1, -2)
                linear_c, angular_c = rotate(rotation_t, linear_c), rotate(rotation_t, angular_c)
            linear[part], angular[part] = linear_c, angular_c
    # without times a static path has one velocity, zero in any axes
    if expressed_in not in (frame, relative_to) and plan.offsets is not None:
        # the axes at the same times, whatever the policy: the path was checked
        axes_plan = plan.on(tree, expressed_in, relative_to, extrapolation="clamp")
        rotation_t = np.swapaxes(planned_transforms(tree, axes_plan)[0], 1, 2)
        linear, angular = rotate(rotation_t, linear), rotate(rotation_t, angular)
    return Velocity(linear, angular, plan.result_times, plan.reference_time, frame,
                    relative_to, expressed_in)


def velocities_in_root(path: SampledPath, pairs: Sequence[tuple[str, str]]
                       ) -> list[tuple[FloatArray, FloatArray]]:
    """Per pair ``(frame, relative_to)`` of the path's frames, ``(v, w)`` of ``frame``
    relative to ``relative_to`` in the axes of the model's root.

    Each joint that moves one end of a pair gives its twist once for every pair: a moving
    frame's exact rate (its interpolation scheme's), or a robot joint's unit twist times
    its driver's rate and the mimic links' multipliers.
    """
    signs = [joint_signs(path.model, frame, relative_to) for frame, relative_to in pairs]
    moving = set().union(*signs)
    twists: dict[int, Twist] = {}
    for position, sampler in enumerate(path.samplers):
        if position not in moving:
            continue
        if isinstance(sampler, MovingFrame):  # a moving frame's free-flyer
            keyframes = sampler.placed
            segments = path.searches.of_frame(sampler.frame, keyframes.times)
            linear, angular = keyframes.rates(segments.times, segments)
            parent_rotation = path.parent_rotations.get(position)
            if parent_rotation is not None:
                linear = rotate(parent_rotation, linear)
                angular = rotate(parent_rotation, angular)
            twists[position] = (linear, angular)
            continue
        trajectory = sampler.trajectory
        if trajectory is None:  # held at its rest value: no velocity
            continue
        segments = path.searches.of_joints(sampler.time_group, sampler.primary,
                                           trajectory.times)
        rates = sampler.multiplier * trajectory.rates(segments.times, segments)
        sliding, turning = path.unit_twists[position]
        twists[position] = (None if sliding is None else sliding * rates[:, None],
                            None if turning is None else turning * rates[:, None])
    return [velocity_sum(moved, path.origins, twists, path.placements[frame][1])
            for moved, (frame, _) in zip(signs, pairs, strict=True)]
