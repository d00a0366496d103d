"""`JointTrack`: samples of one joint value over time, interpolated linearly and held outside."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._interpolation import segment_positions
from ._readonly import readonly_copy

__all__ = ["JointTrack"]


@dataclass(frozen=True)
class JointTrack:
    """Values of one joint at strictly increasing times.

    Attributes
    ----------
    times : ndarray of int64, shape (T,)
        Nanoseconds after ``reference`` (or plain offsets when it is None).
    reference : numpy.datetime64 or None
        What ``times`` count from.
    values : ndarray, shape (T,)
        Radians or metres. Continuous joints are stored unwrapped, so that linear
        interpolation takes the short way round.

    Immutable: ``times`` and ``values`` are read-only copies of the arrays given.
    """

    times: NDArray[np.int64]
    reference: np.datetime64 | None
    values: NDArray[np.float64]

    def __post_init__(self) -> None:
        object.__setattr__(self, "times", readonly_copy(self.times))
        object.__setattr__(self, "values", readonly_copy(self.values))

    def sample(self, times: NDArray[np.int64]) -> NDArray[np.float64]:
        """Values at ``times`` (ns on this track's own basis), held outside the samples."""
        index, fraction = segment_positions(self.times, times)
        if self.values.shape[0] == 1:
            return np.full(times.shape, self.values[0])
        return (1.0 - fraction) * self.values[index] + fraction * self.values[index + 1]
