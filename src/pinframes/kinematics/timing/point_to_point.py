"""Time-optimal joint-space moves from rest to rest, all joints arriving together.

Each joint alone takes its shortest time from rest to rest: without a jerk limit a trapezoid
of acceleration (a triangle when the distance is too short to reach the velocity limit); with
one, the seven phases of an S-curve (jerk +j, 0, -j, cruise, -j, 0, +j, with the phases that
the distance does not allow left out). The move lasts the longest of those times; every other
joint runs its own profile slowed down in time by the ratio of the two durations, so its
velocity, acceleration and jerk shrink by that ratio, its square and its cube and stay within
their limits. A joint that does not move stays still.
"""

from __future__ import annotations

import numpy as np

from ...errors import JointError
from ._phase_profile import PhaseProfile
from .motion_limits import MotionLimits
from .timed_joints import TimedJoints

__all__ = ["PointToPoint", "time_point_to_point"]


class PointToPoint(TimedJoints):
    """A joint-space move from rest at ``start`` to rest at ``goal``, all joints together.

    Attributes
    ----------
    start, goal : numpy.ndarray
        Shape ``(n,)``: the joints at the start and at the end (rad or m).
    duration : float
        Seconds from start to goal: the slowest joint's shortest time.
    joint_durations : numpy.ndarray
        Shape ``(n,)``: each joint's own shortest time (s; 0 for a joint that stays).
    """

    def __init__(self, start: np.ndarray, goal: np.ndarray, profile: PhaseProfile) -> None:
        self.start = start
        self.goal = goal
        self._profile = profile
        self.joint_durations = profile.durations.sum(axis=1)
        self.duration = float(self.joint_durations.max(initial=0.0))
        # each joint's own time runs at joint_duration / duration of the move's time
        self._time_scale = (self.joint_durations / self.duration if self.duration > 0
                            else np.zeros_like(self.joint_durations))

    def sample(self, seconds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and accelerations ``(T, n)`` at ``seconds`` from the start
        (clipped to ``[0, duration]``), exact time derivatives of each other."""
        times = self._clipped(seconds)
        scale = self._time_scale
        own_times = np.minimum(times[:, None] * scale, self.joint_durations)
        position, velocity, acceleration = self._profile.sample(own_times)
        return position, velocity * scale, acceleration * scale**2


def time_point_to_point(start: np.ndarray, goal: np.ndarray,
                        limits: MotionLimits) -> PointToPoint:
    """The time-optimal joint-space move from rest at ``start`` to rest at ``goal``.

    Parameters
    ----------
    start, goal : array_like
        Shape ``(n,)``: joint positions (rad or m), finite.
    limits : MotionLimits
        The joints' velocity, acceleration and, when given, jerk limits.

    Returns
    -------
    PointToPoint
        All joints start and arrive together; its ``duration`` is the largest of the joints'
        shortest times.

    Raises
    ------
    JointError
        ``start`` or ``goal`` not ``n`` finite numbers.
    """
    start_array = _joint_vector("start", start, limits.joint_count)
    goal_array = _joint_vector("goal", goal, limits.joint_count)
    distance = goal_array - start_array
    if limits.jerk is None:
        profile = _trapezoids(start_array, distance, limits.velocity, limits.acceleration)
    else:
        profile = _s_curves(start_array, distance, limits.velocity, limits.acceleration,
                            limits.jerk)
    return PointToPoint(start_array, goal_array, profile)


def _trapezoids(start: np.ndarray, distance: np.ndarray, velocity: np.ndarray,
                acceleration: np.ndarray) -> PhaseProfile:
    """Each joint's shortest rest-to-rest profile without a jerk limit: accelerate, cruise,
    brake (no cruise when the distance is shorter than ``velocity**2 / acceleration``)."""
    length = np.abs(distance)
    sign = np.sign(distance)
    reaches_velocity = length * acceleration >= velocity**2
    ramp = np.where(reaches_velocity, velocity / acceleration, np.sqrt(length / acceleration))
    cruise = np.where(reaches_velocity, length / velocity - velocity / acceleration, 0.0)
    durations = np.stack([ramp, cruise, ramp], axis=1)
    accelerations = sign[:, None] * acceleration[:, None] * np.array([1.0, 0.0, -1.0])
    return PhaseProfile(start, durations, np.zeros_like(durations), accelerations)


def _s_curves(start: np.ndarray, distance: np.ndarray, velocity: np.ndarray,
              acceleration: np.ndarray, jerk: np.ndarray) -> PhaseProfile:
    """Each joint's shortest rest-to-rest profile with a jerk limit: seven phases of jerk
    ``(+j, 0, -j, 0, -j, 0, +j)``, their durations ``(t_j, t_a, t_j, t_v, t_j, t_a, t_j)``.

    Reaching the velocity limit takes ``t_j = a / j`` and ``t_a = v / a - a / j`` when
    ``v j >= a^2``, else ``t_j = sqrt(v / j)``, ``t_a = 0``, over the distance
    ``v (2 t_j + t_a)`` (speeding up and slowing down). A shorter distance ``d`` never cruises:
    with ``t_j = a / j`` it peaks at ``a`` when ``d >= 2 a^3 / j^2`` and then
    ``t_a = (sqrt(t_j^2 + 4 d / a) - 3 t_j) / 2``, else ``t_j = (d / (2 j))^(1/3)``, ``t_a = 0``.
    """
    length = np.abs(distance)
    sign = np.sign(distance)
    full_ramp = velocity * jerk >= acceleration**2
    jerk_time = np.where(full_ramp, acceleration / jerk, np.sqrt(velocity / jerk))
    hold_time = np.where(full_ramp, velocity / acceleration - acceleration / jerk, 0.0)
    speeding = velocity * (2 * jerk_time + hold_time)
    cruises = length >= speeding
    cruise = np.where(cruises, (length - speeding) / np.where(cruises, velocity, 1.0), 0.0)
    peak_time = acceleration / jerk
    peaks = ~cruises & (length * jerk**2 >= 2 * acceleration**3)
    short_hold = (np.sqrt(peak_time**2 + 4 * length / acceleration) - 3 * peak_time) / 2
    jerk_time = np.where(cruises, jerk_time,
                         np.where(peaks, peak_time, np.cbrt(length / (2 * jerk))))
    hold_time = np.where(cruises, hold_time, np.where(peaks, np.maximum(short_hold, 0.0), 0.0))
    durations = np.stack([jerk_time, hold_time, jerk_time, cruise,
                          jerk_time, hold_time, jerk_time], axis=1)
    jerks = sign[:, None] * jerk[:, None] * np.array([1.0, 0, -1, 0, -1, 0, 1])
    peak = sign * jerk * jerk_time
    accelerations = np.stack([0 * peak, peak, peak, 0 * peak, 0 * peak, -peak, -peak], axis=1)
    return PhaseProfile(start, durations, jerks, accelerations)


def _joint_vector(name: str, values: np.ndarray, size: int) -> np.ndarray:
    """``values`` as a read-only ``(size,)`` array of finite floats."""
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise JointError(f"must be numbers, got {values!r}", field=name) from None
    if array.shape != (size,):
        raise JointError(f"must hold one value per joint ({size}), got shape {array.shape}",
                         field=name)
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise JointError(f"must be finite, got {array[bad[0]]!r}", field=f"{name}[{bad[0]}]")
    array.setflags(write=False)
    return array
