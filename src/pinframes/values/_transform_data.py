"""Applying rigid transforms to measured data: points and direction vectors, per time.

The shape rules, for a transform with ``T`` samples (``Pose.transform_points`` and
``FrameTree.transform_points`` follow them):

=================  ============  ===============================================
data shape         result        meaning
=================  ============  ===============================================
``(3,)``           ``(T, 3)``    one point, at every time
``(M, 3)``         ``(T, M, 3)`` the same ``M`` points at every time, whatever ``M``
``(T, M, 3)``      ``(T, M, 3)`` a profile of ``M`` points per time
``(1, M, 3)``      ``(T, M, 3)`` the same ``M`` points at every time
``(T, 3)``         ``(T, 3)``    with ``per_time=True`` only: row ``i`` at time ``i``
=================  ============  ===============================================

Pairing points with times is asked for explicitly (``per_time=True``), never guessed from a
count that happens to match. A static transform keeps the data's shape. Points move with the
whole transform (``R @ p + t``), directions only rotate (``R @ v``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidDataError
from .numbers import float_array, require_finite_result

__all__ = ["transform_data"]

FloatArray = NDArray[np.float64]


def transform_data(
    rotation: FloatArray, translation: FloatArray | None, data: ArrayLike, field: str,
    per_time: bool = False,
) -> FloatArray:
    """``R @ x + t`` (or ``R @ x`` when ``translation`` is None) under the shape rules above.

    ``rotation`` is ``(3, 3)`` or ``(T, 3, 3)``, ``translation`` ``(3,)`` or ``(T, 3)``;
    ``per_time`` pairs ``(T, 3)`` data row by row with the samples; ``field`` names the
    argument in errors (:class:`~pinframes.errors.InvalidDataError`), also when finite
    data and poses overflow to infinity.
    """
    out = _transformed(rotation, translation, _checked(data, field), field, per_time)
    require_finite_result(out, f"the transformed {field}", InvalidDataError, field=field)
    return out


def _transformed(rotation: FloatArray, translation: FloatArray | None, array: FloatArray,
                 field: str, per_time: bool) -> FloatArray:
    if rotation.ndim == 2:
        out = array @ rotation.T
        return out if translation is None else out + translation
    count = rotation.shape[0]
    if per_time and array.ndim == 2 and array.shape[0] != count:
        raise InvalidDataError(
            f"per_time=True pairs row i with time i, but {array.shape[0]} rows were given "
            f"for {count} times", field=field)
    if array.ndim == 1 or (per_time and array.ndim == 2):
        # one point per time: (T, 3) (a single point broadcast over the times)
        rows = np.broadcast_to(array, (count, 3))
        out = (rotation[:, :, 0] * rows[:, 0, None] + rotation[:, :, 1] * rows[:, 1, None]
               + rotation[:, :, 2] * rows[:, 2, None])
        return out if translation is None else out + translation
    if array.ndim == 3 and array.shape[0] not in (1, count):
        raise InvalidDataError(
            f"has {array.shape[0]} profiles (shape {array.shape}) for {count} times; expected "
            f"({count}, M, 3), or (1, M, 3) for the same points at every time", field=field)
    profiles = array if array.ndim == 3 else array[None]
    out = np.matmul(profiles, np.swapaxes(rotation, 1, 2))
    return out if translation is None else out + translation[:, None, :]


def _checked(data: ArrayLike, field: str) -> FloatArray:
    array = float_array(data, field, InvalidDataError)
    if array.ndim not in (1, 2, 3) or array.shape[-1] != 3:
        raise InvalidDataError(
            f"expected shape (3,), (N, 3) or (T, M, 3), got {array.shape}", field=field)
    return array
