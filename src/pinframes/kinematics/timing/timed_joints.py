"""A timed joint motion from rest to rest: its duration and its samples with exact rates."""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from ...errors import InvalidTimeError

__all__ = ["TimedJoints"]


class TimedJoints(ABC):
    """A joint motion from rest to rest, timed within its limits.

    Attributes
    ----------
    duration : float
        How long the motion lasts, in seconds.
    """

    duration: float

    @abstractmethod
    def sample(self, seconds: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities and accelerations, each shape ``(T, n)``, at ``seconds``.

        ``seconds`` (shape ``(T,)``, or a number) count from the motion's start and are
        clipped to ``[0, duration]`` (a NaN is an ``InvalidTimeError``); the velocities and
        accelerations are the exact time derivatives of the positions (rad or m, per s and
        s^2).
        """

    def _clipped(self, seconds: np.ndarray) -> np.ndarray:
        """``seconds`` as a 1-D float array within ``[0, duration]``.

        Raises
        ------
        InvalidTimeError
            A time that is not a number (NaN).
        """
        times = np.asarray(seconds, dtype=float).reshape(-1)
        if np.isnan(times).any():
            raise InvalidTimeError("seconds must be numbers, got NaN", field="seconds")
        return np.clip(times, 0.0, self.duration)
