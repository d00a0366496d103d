"""Numbers given by users as float arrays: real, and finite unless told otherwise.

numpy turns complex numbers into floats by dropping their imaginary parts (with only a
``ComplexWarning``); pinframes refuses them instead, as it refuses text, NaN and infinity.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidDataError, InvalidPoseError, PinframesError

__all__ = ["float_array", "require_finite_pose", "require_finite_result", "unit_direction"]


def float_array(values: ArrayLike, field: str, error: type[PinframesError], *,
                finite: bool = True, copy: bool = False) -> NDArray[np.float64]:
    """``values`` as a float64 array (a new one with ``copy``, else possibly ``values``).

    Raises ``error`` at ``field`` for values that are not real numbers (text, complex
    numbers, ragged nesting, integers beyond float range) and, with ``finite``, for NaN and
    infinity (naming the first such index).
    """
    try:
        array = np.asarray(values)
        complex_numbers = array.dtype.kind == "c"
        if not complex_numbers:
            array = array.astype(float, copy=copy)
    except (TypeError, ValueError, OverflowError) as exc:
        raise error(f"expected numbers: {exc}", field=field) from None
    if complex_numbers:
        raise error("expected real numbers, got complex ones (pinframes never drops an "
                    "imaginary part)", field=field)
    if finite and not np.isfinite(array).all():
        where = tuple(int(i) for i in np.argwhere(~np.isfinite(array))[0])
        raise error(f"non-finite value (NaN or infinity) at index {where}", field=field)
    return array


def unit_direction(values: ArrayLike, field: str, *, frame: str | None = None
                   ) -> NDArray[np.float64]:
    """``values``, three real numbers, as a unit vector; an :class:`InvalidDataError` at
    ``field`` (and ``frame``) for anything else: not three finite numbers, or a vector whose
    squared length is zero or overflows (coordinates below about 1e-162 or above 1e154),
    which no computation keeps as a direction."""
    try:
        vector = float_array(values, field, InvalidDataError)
    except PinframesError as exc:
        raise exc.located(frame=frame) from None
    with np.errstate(over="ignore"):  # an overflow is refused below
        squared = float(vector @ vector) if vector.shape == (3,) else math.nan
    if not 0.0 < squared < math.inf:
        shown = vector.tolist() if vector.size <= 6 else f"an array of shape {vector.shape}"
        raise InvalidDataError(
            f"expected a direction: 3 numbers whose squared length is a finite, non-zero "
            f"number (coordinates between about 1e-162 and 1e154), got {shown}",
            frame=frame, field=field)
    return vector / math.sqrt(squared)


def require_finite_result(array: NDArray[np.float64], what: str,
                          error: type[PinframesError], *, frame: str | None = None,
                          field: str | None = None) -> None:
    """Raise ``error`` when ``array``, computed from finite inputs, overflowed to infinity
    or NaN (two translations of 1e308 m add up to more than a float holds)."""
    if not _all_finite(array):
        raise error(f"{what} overflows double precision (beyond about 1.8e308): the values "
                    "combined are finite but too large", frame=frame, field=field)


def require_finite_pose(translation: NDArray[np.float64], frame: str, relative_to: str
                        ) -> None:
    """An :class:`~pinframes.errors.InvalidPoseError` naming the frame when the pose of
    ``frame`` in ``relative_to``, composed from finite poses, overflowed to infinity or NaN
    (two translations of 1e308 m)."""
    if not _all_finite(translation):  # the message is made only then (a query's hot path)
        require_finite_result(translation, f"the pose of {frame!r} in {relative_to!r}",
                              InvalidPoseError, frame=frame, field="translation")


_FEW = 64
"""Up to this many values Python's own ``math.isfinite`` is the faster check: numpy's
``isfinite(...).all()`` costs a few microseconds whatever the size, as much as a cached
static query (benchmarks/bench_queries.py, case c)."""


def _all_finite(array: NDArray[np.float64]) -> bool:
    if array.size <= _FEW:
        return all(map(math.isfinite, array.ravel().tolist()))
    return bool(np.isfinite(array).all())
