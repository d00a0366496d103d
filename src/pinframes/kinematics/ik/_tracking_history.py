"""What the next sample of a tracked path starts from (:class:`TrackingHistory`): the seed,
the last solution, and the step between the last two carried on as a prediction."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

__all__ = ["LONGEST_PREDICTION", "StepBack", "TrackingHistory"]

FloatArray = NDArray[np.float64]

StepBack = tuple[FloatArray, float]
"""The step from a solution back to the one before (n,) and the sum of its joint changes
(radians or metres): the correction of the Newton step that took the solver from the one
to the other (see :class:`TrackingHistory`)."""

LONGEST_PREDICTION = 2.0
"""The largest ratio of a time step to the one before by which the last step is carried on:
after a longer gap the sample starts from the last solution (and is bridged)."""


class TrackingHistory:
    """What the next sample starts from: the seed, the last two solutions when both reached
    their targets, and the last solution that did. The step between the last two is the
    solver's own correction when one Newton step from the one gave the other (the same
    numbers as their difference but rounding, with the sum of its joint changes: a
    subtraction and a sum less per sample), else their difference.

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

    def start(self, ratio: float) -> tuple[FloatArray, FloatArray | None, float, float]:
        """The last solution; the last step reversed (the solution before less the last:
        the sign in which the solver's corrections come) times ``ratio`` (the ratio of the
        time steps) when both reached their targets and ``ratio`` is at most
        :data:`LONGEST_PREDICTION`, else None; a lower bound of how far the last solution
        lies inside the limits (0: not known); and the sum of that step's joint changes
        (NaN: not known)."""
        if self._previous is None or not ratio <= LONGEST_PREDICTION:
            return self.last, None, self._last_margin, math.nan
        back, changes = (self._previous - self.last, math.nan) if self._back is None else (
            self._back)
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
        self._previous = self.last if reached and self._last_reached and not jumped else None
        self.last, self._last_reached, self.after_a_miss = theta, reached, not reached
        self._last_margin, self._back = margin, back
        if reached:
            self.last_on_target = theta
