"""Time-optimal timing along a geometric joint path, from rest to rest.

The path is the joints at increasing values of a path parameter (the tool's arc length, say);
between samples it is a C1 cubic curve (:class:`._path_spline.PathSpline`). The squared path
speed at every sample comes from the reachability passes of :mod:`._reachability`, within the
joints' velocity and acceleration limits and an optional bound on the path speed; each
segment is then crossed at a constant path acceleration.
"""

from __future__ import annotations

import numpy as np

from ...errors import JointError
from ._path_spline import PathSpline
from ._reachability import squared_path_speeds
from ._timing_grid import TimingGrid
from .motion_limits import MotionLimits
from .timed_joints import TimedJoints

__all__ = ["PathTiming", "time_along_path"]


class PathTiming(TimedJoints):
    """A joint path timed from rest to rest.

    Attributes
    ----------
    duration : float
        Seconds from the path's start to its end.
    passing_times : numpy.ndarray
        Shape ``(N,)``: the seconds at which the path passes each of its samples.
    parameter_speeds : numpy.ndarray
        Shape ``(N,)``: ``ds/dt`` there (path parameter per s; 0 at both ends).
    """

    def __init__(self, grid: TimingGrid, squared_speeds: np.ndarray) -> None:
        self._grid = grid
        speeds = np.sqrt(squared_speeds)
        lengths = grid.lengths
        self._speeds = speeds
        self._accelerations = np.diff(squared_speeds) / (2 * lengths)
        self._times = np.concatenate([[0.0], np.cumsum(2 * lengths / (speeds[:-1] + speeds[1:]))])
        self.passing_times = self._times[grid.samples]
        self.parameter_speeds = speeds[grid.samples]
        self.duration = float(self._times[-1])

    def parameter(self, seconds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The path parameter ``s`` and ``ds/dt``, each ``(T,)``, at ``seconds`` from the start
        (clipped to ``[0, duration]``)."""
        segments, offsets, speeds, _ = self._on_segments(self._clipped(seconds))
        return self._grid.parameters[segments] + offsets, speeds

    def sample(self, seconds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and accelerations ``(T, n)`` at ``seconds`` from the start
        (clipped to ``[0, duration]``): ``q(s)``, ``q'(s) ds/dt`` and
        ``q''(s) (ds/dt)^2 + q'(s) d2s/dt2``."""
        segments, offsets, speeds, accelerations = self._on_segments(self._clipped(seconds))
        position, first, second = self._grid.on_spline(segments, offsets)
        velocity = first * speeds[:, None]
        acceleration = second * speeds[:, None] ** 2 + first * accelerations[:, None]
        return position, velocity, acceleration

    def _on_segments(self, times: np.ndarray,
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Per time: its grid segment, how far into it (path parameter), ``ds/dt`` and
        ``d2s/dt2``."""
        last = self._accelerations.size - 1
        segments = np.clip(np.searchsorted(self._times, times, side="right") - 1, 0, last)
        elapsed = times - self._times[segments]
        start_speeds = self._speeds[segments]
        accelerations = self._accelerations[segments]
        offsets = np.clip(start_speeds * elapsed + accelerations * elapsed**2 / 2,
                          0.0, self._grid.lengths[segments])
        speeds = np.maximum(start_speeds + accelerations * elapsed, 0.0)
        return segments, offsets, speeds, accelerations


def time_along_path(positions: np.ndarray, path_parameter: np.ndarray, limits: MotionLimits,
                    *, max_parameter_speed: float | None = None) -> PathTiming:
    """The time-optimal motion along a joint path, from rest to rest.

    Parameters
    ----------
    positions : array_like
        Shape ``(N, n)``, ``N >= 2``: the joints (rad or m) at each path-parameter value.
    path_parameter : array_like
        Shape ``(N,)``: strictly increasing values of the path parameter (the tool's arc
        length in metres, for instance).
    limits : MotionLimits
        The joints' velocity and acceleration limits (a jerk limit is not used along a path).
    max_parameter_speed : float or None
        The largest ``|ds/dt|`` (path parameter per second: a travel speed in m/s along an
        arc length), or None for none.

    Returns
    -------
    PathTiming
        Between samples the joints follow a C1 cubic curve in ``s``: positions and velocities
        are continuous, accelerations jump at the samples. The path is timed on its samples,
        with points added between them when it has fewer than 200 segments; the joints'
        velocities and accelerations are bounded at those points and the middle of each
        segment, and measured at its quarters (a segment where a joint goes over by more than
        0.1 % is timed again with that joint's limits tightened there).

    Raises
    ------
    JointError
        Positions or parameters of the wrong shape, not finite or not increasing; a joint
        count other than the limits'; a ``max_parameter_speed`` that is not a number > 0; a
        stretch on which no joint moves when ``max_parameter_speed`` is None.
    """
    joints, parameters = _path_arrays(positions, path_parameter, limits.joint_count)
    if max_parameter_speed is not None and not (
            np.isfinite(max_parameter_speed) and max_parameter_speed > 0):
        raise JointError(f"must be a finite number > 0, got {max_parameter_speed!r}",
                         field="max_parameter_speed")
    grid = TimingGrid(PathSpline(joints, parameters))
    squared = squared_path_speeds(grid, limits.velocity, limits.acceleration,
                                  None if max_parameter_speed is None
                                  else float(max_parameter_speed))
    return PathTiming(grid, squared)


def _path_arrays(positions: np.ndarray, path_parameter: np.ndarray,
                 joint_count: int) -> tuple[np.ndarray, np.ndarray]:
    """The path's positions ``(N, n)`` and parameters ``(N,)`` as checked float arrays."""
    try:
        joints = np.array(positions, dtype=float)
        parameters = np.array(path_parameter, dtype=float)
    except (TypeError, ValueError):
        raise JointError("must be numbers", field="positions") from None
    if joints.ndim != 2 or joints.shape[1] != joint_count or joints.shape[0] < 2:
        raise JointError(f"must have shape (N >= 2, {joint_count}), got {joints.shape}",
                         field="positions")
    if parameters.shape != (joints.shape[0],):
        raise JointError(f"must have shape ({joints.shape[0]},), got {parameters.shape}",
                         field="path_parameter")
    for name, values in (("positions", joints), ("path_parameter", parameters)):
        if not np.all(np.isfinite(values)):
            index = int(np.flatnonzero((~np.isfinite(values.reshape(len(values), -1))).any(1))[0])
            raise JointError("must be finite", field=f"{name}[{index}]")
    steps = np.diff(parameters)
    if np.any(steps <= 0):
        index = int(np.flatnonzero(steps <= 0)[0]) + 1
        raise JointError(f"must increase, but {parameters[index]!r} follows "
                         f"{parameters[index - 1]!r}", field=f"path_parameter[{index}]")
    joints.setflags(write=False)
    parameters.setflags(write=False)
    return joints, parameters
