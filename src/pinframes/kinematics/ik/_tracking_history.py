"""What the next sample of a tracked path starts from (:class:`TrackingHistory`): the seed,
the last solution, and the step between the last two carried on as a prediction, bent by the
change from the step before when the last three solutions reached their targets (the
quadratic through them: near a singular configuration the path's two branches lie closer
than the linear prediction's error, a hundredth of a radian on a 10 Hz path, and only the
quadratic's, ten times smaller, keeps the side of the singular configuration the path
keeps or crosses to)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["LONGEST_PREDICTION", "SMOOTH", "StepBack", "TrackingHistory"]

FloatArray = NDArray[np.float64]

StepBack = tuple[FloatArray, float]
"""The step from a solution back to the one before (n,) and the sum of its joint changes
(radians or metres): the correction of the Newton step that took the solver from the one
to the other (see :class:`TrackingHistory`)."""

LONGEST_PREDICTION = 2.0
"""The largest ratio of a time step to the one before by which the last step is carried on:
after a longer gap the sample starts from the last solution (and is bridged)."""

SMOOTH = 0.25
"""The largest change of the step from one sample to the next, over the step (Euclidean
norms, radians or metres), for which the quadratic through the last three solutions is
carried on: past it the samples do not resolve the path's bend, or the steps wander along a
singular configuration's self-motion, and the line through the last two is."""

_SMOOTH_SQUARED = SMOOTH**2


class TrackingHistory:
    """What the next sample starts from: the seed, the last three solutions when they reached
    their targets, and the last solution that did. The step between the last two is the
    solver's own correction when one Newton step from the one gave the other (the same
    numbers as their difference but rounding, with the sum of its joint changes: a
    subtraction and a sum less per sample), else their difference; the step before is
    taken the same way.

    Parameters
    ----------
    seed : ndarray, shape (n,)
        Where the first sample starts.

    Attributes
    ----------
    last : ndarray, shape (n,)
        The latest solution (the seed before the first).
    last_on_target : ndarray, shape (n,)
        The latest solution that reached its target (the seed before the first).
    after_a_miss : bool
        Whether the latest sample did not reach its target.
    """

    def __init__(self, seed: FloatArray) -> None:
        self.last = self.last_on_target = seed
        self.after_a_miss = False
        self._last_reached = False  # the seed is no solution
        self._last_margin = 0.0  # a lower bound of how far ``last`` lies inside the limits
        self._previous: FloatArray | None = None  # before ``last``, when both reached
        self._back: StepBack | None = None  # from ``last`` to ``_previous``, when given
        # ``_previous``'s own previous and step back, when the three reached their targets
        self._before: tuple[FloatArray, StepBack | None] | None = None
        self._ratio = math.nan  # the time step ratio of the latest sample

    def start(self, ratio: float) -> tuple[FloatArray, FloatArray | None, float, float]:
        """The last solution; the step from it to the prediction reversed (the sign in
        which the solver's corrections come: the last solution less the prediction) when
        the last two reached their targets and ``ratio`` (this time step over the last) is
        at most :data:`LONGEST_PREDICTION`, else None; a lower bound of how far the last
        solution lies inside the limits (0: not known); and the sum of that step's joint
        changes, or a bound above it (NaN: not known).

        The prediction lies on the line through the last two solutions, times ``ratio``
        past the last; on the quadratic through the last three (at their times) when the
        one before also reached its target, the last time step was within
        :data:`LONGEST_PREDICTION` of the one before and the step changed by at most
        :data:`SMOOTH` of itself."""
        before, before_ratio, self._ratio = self._before, self._ratio, ratio
        if self._previous is None or not ratio <= LONGEST_PREDICTION:
            return self.last, None, self._last_margin, math.nan
        if self._back is None:  # (kept: the next sample's step before)
            self._back = self._previous - self.last, math.nan
        back, changes = self._back
        if before is not None and 0.0 < before_ratio <= LONGEST_PREDICTION:
            earlier, earlier_back = before
            back_before = earlier - self._previous if earlier_back is None else earlier_back[0]
            # the steps' change, in the last step's time
            change = (back - back_before if before_ratio == 1.0
                      else back - before_ratio * back_before)
            # |change| <= SMOOTH |back|; where the sum of back's joint changes is known,
            # against that sum over sqrt(n) (at most |back|: one dot product less)
            squared, joints = change.dot(change), back.shape[0]
            if (squared * joints <= _SMOOTH_SQUARED * changes * changes if changes >= 0.0
                    else squared <= _SMOOTH_SQUARED * back.dot(back)):
                # q + r d1 + r (r + 1) r1 / (r1 + 1) (d1 - r1 d0), d = -back: the quadratic
                # through the last three at times 0, -h, -h - h / r1, at r h
                bend = ratio * (ratio + 1.0) * before_ratio / (before_ratio + 1.0)
                # (its joint changes sum to at most r changes + bend sqrt(n) |change|)
                return self.last, (back + change if ratio == 1.0 and bend == 1.0
                                   else ratio * back + bend * change), self._last_margin, (
                    ratio * changes + bend * math.sqrt(squared * joints))
        if ratio != 1.0:
            back, changes = back * ratio, changes * ratio
        return self.last, back, self._last_margin, changes

    def add(self, theta: FloatArray, reached: bool, margin: float,
            back: StepBack | None = None, jumped: bool = False) -> None:
        """Record the solution of the sample just solved, with a lower bound of how far it
        lies inside the limits (0: not known) and, when the solver knows it, the step from
        it back to the last solution (the same numbers as ``last - theta`` but rounding).
        ``jumped``: it was reached along another self-motion than the last (see
        :mod:`._self_motion_escape`), a step not to carry on."""
        previous = self.last if reached and self._last_reached and not jumped else None
        self._before = None if previous is None or self._previous is None else (
            self._previous, self._back)
        self._previous = previous
        self.last, self._last_reached, self.after_a_miss = theta, reached, not reached
        self._last_margin, self._back = margin, back
        if reached:
            self.last_on_target = theta
