"""Weaving: the torch's periodic motion across a seam, as offsets in the seam's axes.

A weave of ``amplitude`` A (metres) at ``frequency`` f (Hz) has the phase ``s = f t`` (t in
seconds after the weave's first time, ``φ = s mod 1`` its fraction of a period) and moves
across its parent's y axis, starting on the centre line (y = 0) toward +y:

- ``"triangle"``: y = A tri(φ), tri rising 4 φ to 1 at φ = 1/4, falling to -1 at 3/4 and
  back to 0 at 1 (constant speed 4 A f across);
- ``"sine"``: y = A sin(2 pi s);
- ``"trapezoid"``: y = A clip(tri(φ) / (1 - dwell), -1, 1): a triangle that holds at each
  edge for ``dwell / 2`` of the period (``dwell`` in (0, 1));
- ``"circle"``: x = A cos(2 pi s), y = A sin(2 pi s): a circle of radius A about the
  centre point, counter-clockwise seen from the parent's +z, starting A ahead on x.

``amplitude`` is the largest offset from the centre line.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidPoseError

__all__ = ["WEAVE_PATTERNS", "Weave"]

FloatArray = NDArray[np.float64]

WEAVE_PATTERNS = ("triangle", "sine", "trapezoid", "circle")
"""The weave patterns :class:`Weave` knows."""

_ON_A_HALF_PERIOD = 1e-6
"""How close to a whole number of half periods (in half periods) a sample time counts as
on one: times are whole nanoseconds, a period is far longer."""


@dataclass(frozen=True)
class Weave:
    """A weave pattern: what :meth:`pinframes.Pose.weave` samples.

    Attributes
    ----------
    amplitude : float
        The largest offset from the centre line, metres (> 0).
    frequency : float
        Periods per second, Hz (> 0).
    pattern : str
        One of :data:`WEAVE_PATTERNS`.
    dwell : float or None
        For ``"trapezoid"`` the fraction of each period spent at the two edges, in (0, 1);
        None for the other patterns.
    """

    amplitude: float
    frequency: float
    pattern: str = "triangle"
    dwell: float | None = None

    def __post_init__(self) -> None:
        for name in ("amplitude", "frequency"):
            value = getattr(self, name)
            if (isinstance(value, bool) or not isinstance(value, (int, float, np.number))
                    or not (np.isfinite(value) and value > 0)):
                raise InvalidPoseError(f"expected a positive finite number, got {value!r}",
                                       field=name)
        if self.pattern not in WEAVE_PATTERNS:
            raise InvalidPoseError(f"expected one of {', '.join(WEAVE_PATTERNS)}, got "
                                   f"{self.pattern!r}", field="pattern")
        if self.pattern != "trapezoid":
            if self.dwell is not None:
                raise InvalidPoseError(f"only a trapezoid weave dwells, not a {self.pattern}",
                                       field="dwell")
        elif (isinstance(self.dwell, bool) or not isinstance(self.dwell, (int, float, np.number))
              or not 0.0 < self.dwell < 1.0):
            raise InvalidPoseError("a trapezoid weave needs a dwell fraction in (0, 1), got "
                                   f"{self.dwell!r}", field="dwell")

    def check_sample_times(self, seconds: FloatArray) -> None:
        """Refuse sample times (``seconds`` after the start) that all fall on whole half
        periods: there every pattern is on its centre line (the circle at the two ends of
        its x diameter), so the samples draw a straight line, not the weave. Two samples
        are a line whatever their times, and are let be."""
        half_periods = 2.0 * self.frequency * seconds
        off = np.abs(half_periods - np.round(half_periods))
        if seconds.shape[0] > 2 and np.all(off <= _ON_A_HALF_PERIOD):
            step = float(np.min(np.diff(seconds)))
            raise InvalidPoseError(
                f"the weave of {self.frequency:g} Hz is sampled only at whole half periods "
                f"({1 / (2 * self.frequency):g} s; every {step:g} s here), where it crosses "
                "its centre line: the samples draw a straight line. Sample it at least four "
                f"times per period (a step of {1 / (4 * self.frequency):g} s or less)",
                field="times")

    def offsets(self, seconds: ArrayLike) -> FloatArray:
        """Offsets (T, 3) in metres from the centre point, in the parent's axes, at
        ``seconds`` (T,) after the weave's start."""
        phase = self.frequency * np.asarray(seconds, dtype=float)
        offsets = np.zeros((phase.shape[0], 3))
        if self.pattern == "sine":
            offsets[:, 1] = np.sin(2 * np.pi * phase)
        elif self.pattern == "circle":
            offsets[:, 0] = np.cos(2 * np.pi * phase)
            offsets[:, 1] = np.sin(2 * np.pi * phase)
        else:
            triangle = _triangle(phase - np.floor(phase))
            if self.dwell is not None:
                triangle = np.clip(triangle / (1.0 - self.dwell), -1.0, 1.0)
            offsets[:, 1] = triangle
        return self.amplitude * offsets


def _triangle(fraction: FloatArray) -> FloatArray:
    """The unit triangle wave at ``fraction`` of its period in [0, 1): 0, up to 1 at 1/4,
    down to -1 at 3/4, back to 0."""
    return np.where(fraction < 0.25, 4.0 * fraction,
                    np.where(fraction < 0.75, 2.0 - 4.0 * fraction, 4.0 * fraction - 4.0))
