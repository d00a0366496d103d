"""The time fields every result on one timeline shares, in one place.

A pose, a stack of poses, a velocity, a Jacobian, a welding process, a clearance and a joint
solution each carry ``times`` (``timedelta64[ns]`` after ``reference_time``; None for a
static result) and ``reference_time`` (a ``datetime64[ns]``, or None: plain offsets), and
offer the same two views of them, :attr:`~Timed.seconds` and :attr:`~Timed.absolute_times`.
A value that holds its own samples (a pose, data attached to a frame) keeps its times as
:class:`SampledInTime` does.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["SampledInTime", "Timed"]


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


class SampledInTime(Timed):
    """Mixin of a value that holds its own samples: ``_times`` (int64 nanoseconds after
    ``_reference``; None when static) and ``_reference`` (``datetime64[ns]`` or None), and
    the properties that read them."""

    __slots__ = ("_reference", "_times")

    _times: NDArray[np.int64] | None
    _reference: np.datetime64 | None

    @property
    def times(self) -> NDArray[np.timedelta64] | None:
        """Sample times after :attr:`reference_time`, ``timedelta64[ns]``; None if static."""
        return None if self._times is None else self._times.astype("timedelta64[ns]")

    @property
    def reference_time(self) -> np.datetime64 | None:
        """The timestamp :attr:`times` count from, ``datetime64[ns]``, or None."""
        return self._reference

    @property
    def is_time_dependent(self) -> bool:
        """True when sampled in time (a pose per time, a point set per time)."""
        return self._times is not None
