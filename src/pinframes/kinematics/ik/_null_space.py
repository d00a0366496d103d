"""Secondary objectives of an inverse-kinematics solve: motions of the solved joints that the
tool does not feel (the null space of its task), taken only where the primary task, the tool
on its target, holds.

An objective asks for a joint motion ``m`` (radians or metres per joint) at a solution, given
the task's rows ``A`` there (the Newton system of :mod:`._tool_error`); the solver takes its
exact projection into their null space, ``m - A^+ A m``, then Newton steps on the primary
task alone until the tool is back within its tolerances. On a sample solved from a start (the
first, or after a gap) rather than from a prediction, this is repeated up to the objective's
``rounds_from_a_start`` times while it asks for something: to convergence. When Newton does
not get the tool back there, the motion is dropped: an objective never costs the primary task
anything. An objective that asks for nothing (None) leaves the solution as it is, so a static
target keeps a static solution.

:class:`AwayFromLimits` is the one ``solve_joints`` passes (``TrackingProblem.objective``);
:class:`._flat.FlatFrame` (a frame's z turned up, ``flat=``) takes its place.
"""

from __future__ import annotations

from collections.abc import Callable
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
    rounds_tracked : int
        How many times at most it is served, one after the other, on a sample solved from a
        prediction (it asks for nothing once it is content: most samples take none).
    rounds_from_a_start : int
        How many times at most it is served, one after the other, on a sample solved from a
        start rather than a prediction (1: once, as on every other sample).
    carries_self_motion : bool
        Whether the prediction of the next sample carries on the whole last step, the
        motion the objective asked for included (a frame kept flat turns on smoothly), or
        only its part that moves the tool (the smallest motion).
    """

    quiet_margin: float
    rounds_tracked: int
    rounds_from_a_start: int
    carries_self_motion: bool

    def motion(self, theta: FloatArray, configuration: FloatArray,
               task_rows: Callable[[], FloatArray], settle: bool) -> FloatArray | None:
        """The joint motion (n,) wanted at the solution ``theta`` (n,), radians or metres;
        None when there is nothing to do. ``configuration`` is the sample's Pinocchio ``q``
        (nq,) with ``theta`` in it: an objective about a frame's pose (a frame kept flat)
        runs forward kinematics of it on the model it was made with. ``task_rows()`` gives
        the task's rows (m, n) at ``theta`` (computed on the first call: an objective with
        a task of its own solves it within their null space); it leaves Pinocchio's data
        with the forward kinematics of ``configuration`` and, when solved joints move the
        reference, every joint's Jacobian (``computeJointJacobians``). ``settle``: the
        sample is solved from a start, served round after round: ask for what is left,
        however little."""


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
        self.rounds_tracked = 1
        self.rounds_from_a_start = 1
        self.carries_self_motion = False
        self._limits = limits

    def motion(self, theta: FloatArray, configuration: FloatArray,
               task_rows: Callable[[], FloatArray], settle: bool) -> FloatArray | None:
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
