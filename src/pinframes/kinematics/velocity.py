"""``FrameTree.velocity``: how fast a frame moves relative to another, per sample.

Exact derivatives of what ``pose()`` interpolates (see :mod:`._rates`), carried through the
compiled model of the query path (see :mod:`._twists`). The linear velocity is that of the
frame's origin relative to the reference frame (the derivative of
``pose(frame, relative_to).translation``); the angular velocity ``w`` satisfies
``dR/dt = [w]x @ R`` for ``R = pose(frame, relative_to).rotation``. Both are written in the
axes of ``relative_to`` (Pinocchio's ``LOCAL_WORLD_ALIGNED`` when ``relative_to`` is the
model's root) or, rotated, in those of ``frame`` (Pinocchio's ``LOCAL``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values.joint import Joint, mimic_primary
from ..values.se3 import IDENTITY
from ._description import TreeDescription
from ._path import PreparedPath
from ._rates import keyframe_rates, segment_rates, track_rates
from ._sampled_path import PlannedQuery, SampledPath, plan_query
from ._twists import Twist, rotate, velocity_sum
from .pose import evaluate_pose

__all__ = ["Velocity", "evaluate_velocity", "joint_rates"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Velocity:
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
    planned = plan_query(tree, frame, relative_to, times, time_ref, extrapolation)
    linear, angular = np.zeros((planned.count, 3)), np.zeros((planned.count, 3))
    if planned.prepared.static is None:
        for part, path in planned.chunks(tree):
            linear_c, angular_c = _velocity_in_root(tree, planned.prepared, path)
            axes = (path.frame if expressed_in == frame else path.relative_to)[0]
            if axes is not IDENTITY[0]:  # the root's own axes need no turn
                rotation_t = np.swapaxes(axes, -1, -2)
                linear_c, angular_c = rotate(rotation_t, linear_c), rotate(rotation_t, angular_c)
            linear[part], angular[part] = linear_c, angular_c
    if expressed_in not in (frame, relative_to):
        rotation_t = np.swapaxes(_orientation(tree, expressed_in, relative_to, planned), 1, 2)
        linear, angular = rotate(rotation_t, linear), rotate(rotation_t, angular)
    return Velocity(linear, angular, planned.times, planned.reference_time, frame,
                    relative_to, expressed_in)


def _orientation(tree: TreeDescription, other: str, relative_to: str, planned: PlannedQuery
                 ) -> FloatArray:
    """Rotations ``(T, 3, 3)`` of ``other`` in ``relative_to`` at the result's times."""
    offsets, reference = planned.offsets, planned.reference_time
    if offsets is None:
        static = evaluate_pose(tree, other, relative_to, None, None, "clamp")
        return np.broadcast_to(static.rotation, (1, 3, 3))
    times = offsets.astype("timedelta64[ns]")
    if reference is not None:
        return evaluate_pose(tree, other, relative_to, reference + times, reference,
                             "clamp").rotation
    return evaluate_pose(tree, other, relative_to, times, None, "clamp").rotation


def _velocity_in_root(tree: TreeDescription, prepared: PreparedPath, path: SampledPath
                      ) -> tuple[FloatArray, FloatArray]:
    """``(v, w)`` of the frame relative to the reference frame, in the root's axes."""
    twists: dict[int, Twist] = {}
    segments: dict[tuple[str, int], tuple[NDArray[np.intp], FloatArray]] = {}
    for position, joint in enumerate(path.model.joints):
        keyframes = prepared.placed_keyframes[position]
        if position not in path.signs:
            continue
        if keyframes is not None:  # a moving frame's free-flyer
            linear, angular = keyframe_rates(keyframes, path.times - path.shifts[joint.frame])
            parent_rotation = path.parent_rotations.get(position)
            if parent_rotation is not None:
                linear = rotate(parent_rotation, linear)
                angular = rotate(parent_rotation, angular)
            twists[position] = (linear, angular)
            continue
        rates = None if joint.joint is None else joint_rates(
            tree, joint.joint, path.times, path.shifts, segments)
        if rates is not None:
            sliding, turning = path.unit_twists[position]
            twists[position] = (None if sliding is None else sliding * rates[:, None],
                                None if turning is None else turning * rates[:, None])
    return velocity_sum(path.signs, path.origins, twists, path.frame[1])


def joint_rates(
    tree: TreeDescription, joint: Joint, times: NDArray[np.int64], shifts: dict[str, int],
    segments: dict[tuple[str, int], tuple[NDArray[np.intp], FloatArray]] | None = None,
) -> FloatArray | None:
    """Velocities (N,) of ``joint`` at ``times`` (timeline basis), rad/s or m/s: its
    trajectory's, or its mimic primary's times the product of the multipliers; None when
    no trajectory drives it. ``segments`` keeps the segment lookups of one set of times
    for the joints of one time group (:meth:`TreeDescription.time_group`)."""
    primary, multiplier = mimic_primary(joint, tree.joints_by_name)
    track = tree.joint_trajectories.get(primary.name)
    if track is None:
        return None
    own_times = times - shifts[primary.name]
    found = None
    if segments is not None:
        key = (tree.time_group(primary.name), shifts[primary.name])
        found = segments.get(key)
        if found is None:
            found = segments[key] = segment_rates(track.times, own_times)
    return multiplier * track_rates(track, own_times, found)
