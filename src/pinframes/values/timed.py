"""The time fields every result on one timeline shares, in one place.

A pose, a stack of poses, a velocity, a Jacobian, a welding process, a clearance and a joint
solution each carry ``times`` (``timedelta64[ns]`` after ``reference_time``; None for a
static result) and ``reference_time`` (a ``datetime64[ns]``, or None: plain offsets), and
offer the same two views of them, :attr:`~Timed.seconds` and :attr:`~Timed.absolute_times`.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["Timed"]


class _HasTimes(Protocol):
    @property
    def times(self) -> NDArray[np.timedelta64] | None: ...

    @property
    def reference_time(self) -> np.datetime64 | None: ...


class Timed:
    """Mixin of a result with ``times`` and ``reference_time``: their views in seconds and
    as timestamps."""

    __slots__ = ()

    @property
    def seconds(self: _HasTimes) -> NDArray[np.float64] | None:
        """:attr:`times` as float seconds after :attr:`reference_time`; None if static."""
        times = self.times
        return None if times is None else times.astype(np.int64) / 1e9

    @property
    def absolute_times(self: _HasTimes) -> NDArray[np.datetime64] | None:
        """``reference_time + times`` as ``datetime64[ns]``; None without a reference time
        or without times."""
        times, reference = self.times, self.reference_time
        if times is None or reference is None:
            return None
        return (reference + times).astype("datetime64[ns]")
