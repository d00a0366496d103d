"""A move once planned: how long it lasts and its joints at any time of it, from rest to
rest; stretched onto the program's step.

Each move's duration is rounded up to a whole number of steps by slowing it uniformly (its
velocities scaled by ``c <= 1``, its accelerations by ``c^2``), so that every move starts
and ends on a sample, at rest, and the limits still hold.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..kinematics.timing import PathTiming, TimedJoints
from ..values.motion import MoveRecord
from .cartesian_paths import TargetPath

__all__ = ["PlannedMove", "steps_of"]

FloatArray = NDArray[np.float64]


def steps_of(duration: float, step: float) -> int:
    """Samples' steps a move of ``duration`` seconds takes: rounded up (a nanosecond of
    float error forgiven)."""
    return max(0, math.ceil(duration / step - 1e-6))


@dataclass(frozen=True)
class PlannedMove:
    """One planned move.

    Attributes
    ----------
    name, kind : str
        As in :class:`~pinframes.values.motion.MoveRecord`.
    start : ndarray, shape (n,)
        The joints where the move starts (and stays, for a wait).
    timing : TimedJoints or PathTiming or None
        The move's timing (None: a wait).
    duration : float
        Its own duration, seconds (a wait's seconds).
    path : TargetPath or None
        For linear and seam moves, the tool's target path.
    node_reached : ndarray of bool, shape (N,), or None
        For linear and seam moves, whether each node of the path was reached; for a
        point-to-point move to a pose, one value: whether that pose was.
    """

    name: str
    kind: str
    start: FloatArray
    timing: TimedJoints | PathTiming | None
    duration: float
    path: TargetPath | None = None
    node_reached: NDArray[np.bool_] | None = None

    @property
    def end(self) -> FloatArray:
        """The joints where the move ends, at rest."""
        if self.timing is None:
            return self.start
        return np.asarray(self.timing.sample(np.array([self.duration]))[0][0], dtype=float)

    def sampled(self, local: FloatArray, stretched: float) -> tuple[
            FloatArray, FloatArray, FloatArray, NDArray[np.bool_], float | None]:
        """Positions, velocities, accelerations (T, n) and reached (T,) at ``local`` seconds
        of the move stretched to last ``stretched`` seconds; and for a linear or seam move
        the tool's highest speed along its path then (m/s), else None."""
        count = local.shape[0]
        if self.timing is None or self.duration <= 0.0:
            zeros = np.zeros((count, self.start.shape[0]))
            return (np.broadcast_to(self.start, zeros.shape).copy(), zeros, zeros.copy(),
                    np.ones(count, bool), None)
        scale = self.duration / stretched
        own = np.minimum(local * scale, self.duration)
        positions, velocities, accelerations = self.timing.sample(own)
        reached, speed = self._on_path(own, scale)
        return (np.asarray(positions, float), np.asarray(velocities, float) * scale,
                np.asarray(accelerations, float) * scale**2, reached, speed)

    def record(self, start_s: float, end_s: float, reached_speed: float | None
               ) -> MoveRecord:
        """This move's record, started at ``start_s`` and ended at ``end_s`` seconds."""
        if self.path is None:
            return MoveRecord(self.name, self.kind, start_s, end_s)
        return MoveRecord(self.name, self.kind, start_s, end_s, self.path.requested_speed,
                          reached_speed)

    def _on_path(self, own: FloatArray, scale: float
                 ) -> tuple[NDArray[np.bool_], float | None]:
        """Whether the tool is on its target at ``own`` seconds of the move, and its highest
        speed along the path then (m/s; None for a point-to-point move)."""
        count = own.shape[0]
        reached = np.ones(count, bool)
        if self.path is None or not isinstance(self.timing, PathTiming):
            if self.node_reached is not None:
                reached[own >= self.duration] = bool(self.node_reached.all())
            return reached, None
        parameter, rate = self.timing.parameter(own)
        per_parameter = np.interp(parameter, self.path.parameter,
                                  self.path.tool_speed_per_parameter)
        speed = float(np.max(np.abs(rate) * per_parameter)) * scale
        if self.node_reached is not None:
            nodes = self.path.parameter
            after = np.clip(np.searchsorted(nodes, parameter), 0, nodes.shape[0] - 1)
            before = np.clip(after - 1, 0, nodes.shape[0] - 1)
            reached = self.node_reached[before] & self.node_reached[after]
        return reached, speed
