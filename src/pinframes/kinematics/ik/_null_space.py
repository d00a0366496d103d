"""Secondary objectives of an inverse-kinematics solve: motions of the solved joints that the
tool does not feel (the null space of its task), taken only where the primary task, the tool
on its target, holds.

An objective asks for a joint motion ``m`` (radians or metres per joint) at a solution; the
solver takes its exact projection into the null space of the task's rows ``A`` (the Newton
system of :mod:`._tool_error` at that solution), ``m - A^+ A m``, then Newton steps on the
primary task alone until the tool is back within its tolerances. When they do not get it
there, the motion is dropped: an objective never costs the primary task anything. An
objective that asks for nothing (None) leaves the solution as it is, so a static target keeps
a static solution.

:class:`AwayFromLimits` is the one ``solve_joints`` passes (``TrackingProblem.objective``);
others (keeping a frame's axis upright, a window of tilt angles) follow the
:class:`NullSpaceObjective` protocol and take its place, or add their motions to its.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from ._bounded_step import JointLimits, LeastSquares

__all__ = ["AwayFromLimits", "NullSpaceObjective", "null_space_motion"]

FloatArray = NDArray[np.float64]


class NullSpaceObjective(Protocol):
    """A wish for the solved joints' values, served in the task's null space.

    Attributes
    ----------
    quiet_margin : float
        A margin inside the joint limits (radians or metres) from which on it asks for
        nothing (``math.inf``: it may ask anywhere); the solver skips asking it there.
    """

    quiet_margin: float

    def motion(self, theta: FloatArray, configuration: FloatArray) -> FloatArray | None:
        """The joint motion (n,) wanted at the solution ``theta`` (n,), radians or metres;
        None when there is nothing to do. ``configuration`` is the sample's Pinocchio ``q``
        (nq,) with ``theta`` in it: an objective about a frame's pose (a torch kept flat)
        runs forward kinematics of it on the model it was made with."""


BAND = 0.1
"""Width of the band along each limit that :class:`AwayFromLimits` keeps the joints out of,
as a fraction of the joint's range (at most :data:`WIDEST_BAND`)."""

WIDEST_BAND = 0.2
"""The widest band along a limit, radians or metres."""

PUSH = 0.2
"""The fraction of its depth in the band by which a joint is asked to leave it, per sample."""


class AwayFromLimits:
    """Joints that come within the band along a limit are asked back out of it.

    Outside the bands nothing is asked (:attr:`quiet_margin`: the widest band), so the
    solution is the smallest motion from the previous sample.
    """

    def __init__(self, limits: JointLimits) -> None:
        bounded = np.isfinite(limits.lower) & np.isfinite(limits.upper)
        span = np.where(bounded, limits.upper - limits.lower, 0.0)
        self._band = np.minimum(BAND * span, WIDEST_BAND)
        self.quiet_margin = float(self._band.max()) if self._band.shape[0] else 0.0
        self._limits = limits

    def motion(self, theta: FloatArray, configuration: FloatArray) -> FloatArray | None:
        """:data:`PUSH` of each joint's depth inside its band, away from the limit."""
        if not self._limits.margin(theta.tolist()) < self.quiet_margin:
            return None
        below = self._band - (theta - self._limits.lower)
        above = self._band - (self._limits.upper - theta)
        wanted = PUSH * (np.maximum(below, 0.0) - np.maximum(above, 0.0))
        return wanted if np.any(wanted) else None


def null_space_motion(solver: LeastSquares, rows: FloatArray, motion: FloatArray
                      ) -> FloatArray:
    """``motion`` (n,) less its part that moves the task: ``motion - A^+ A motion`` for the
    rows ``A`` (m, n) of full row rank, exactly (no damping); zero without redundancy."""
    count, joints = rows.shape
    if joints <= count:
        return np.zeros_like(motion)
    return motion - solver.correction(rows, rows.dot(motion), 0.0)
