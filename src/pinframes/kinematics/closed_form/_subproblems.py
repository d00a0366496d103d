"""The three small problems both closed forms are made of, vectorised over samples: turning
a vector about a unit axis, the angle that turns one vector onto another about an axis, and
the two angles where ``A cos + B sin`` takes a value.

Vectors are ``(3, ...)`` arrays, components first (a constant one is ``(3,)``), so that
every product is an element-wise pass over contiguous rows; rotations are ``(3, 3, T)``,
samples last, as :mod:`pinframes.values.se3` holds them. An angle travels with its cosine
and sine (a :data:`Turn`), taken from the ratios that give it and from sums of angles:
numpy's ``cos`` and ``sin`` of float64 take 13 ns a number, ``arctan2`` and ``arccos`` 2.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = ["AT_LIMIT", "TURN", "Halves", "Turn", "added", "applied", "backwards", "column",
           "cross", "dot", "one_of", "plane_angle", "rotated", "turn_angle", "turn_of",
           "turned_along", "turning", "two_angles", "wrapped"]

FloatArray = NDArray[np.float64]

TURN = 2.0 * math.pi
"""One turn, radians."""

AT_LIMIT = 1e-9
"""How far past +-1 a cosine may fall (rounding at a stretched arm or a straight wrist) and
still be taken as +-1; further past, the pose is out of reach and the angles are NaN."""


def column(vector: FloatArray, dimensions: int) -> FloatArray:
    """A constant ``vector`` (3,) shaped to broadcast against vectors ``(3,)`` followed by
    ``dimensions`` more axes."""
    return vector.reshape((3,) + (1,) * dimensions)


def dot(first: FloatArray, second: FloatArray) -> FloatArray:
    """The dot product of two vectors (components first, broadcast)."""
    return first[0] * second[0] + first[1] * second[1] + first[2] * second[2]


def cross(first: FloatArray, second: FloatArray) -> FloatArray:
    """The cross product of two vectors (components first, broadcast)."""
    return _stacked(first[1] * second[2] - first[2] * second[1],
                    first[2] * second[0] - first[0] * second[2],
                    first[0] * second[1] - first[1] * second[0])


def _stacked(x: FloatArray, y: FloatArray, z: FloatArray) -> FloatArray:
    """Three components (broadcast) as one vector array."""
    shape = np.shape(x)
    if np.shape(y) != shape or np.shape(z) != shape:
        shape = np.broadcast_shapes(shape, np.shape(y), np.shape(z))
    out = np.empty((3, *shape))
    out[0], out[1], out[2] = x, y, z
    return out


def applied(rotations: FloatArray, vector: FloatArray) -> FloatArray:
    """``rotations`` (3, 3, T) applied to ``vector`` (3,) or (3, T, ...)."""
    extra = vector.ndim - 2 if vector.ndim > 1 else 0
    rows = rotations.reshape(rotations.shape[:3] + (1,) * extra)
    return _stacked(*(rows[row, 0] * vector[0] + rows[row, 1] * vector[1]
                      + rows[row, 2] * vector[2] for row in range(3)))


Turn = tuple[FloatArray, FloatArray]
"""An angle as its cosine and sine (computed once for the several vectors it turns)."""


def turn_of(angle: FloatArray) -> Turn:
    """``angle`` (...) radians as a :data:`Turn` (numpy's ``cos`` and ``sin`` of float64
    take a number at a time, 13 ns each: the closed forms take their turns from the
    products of :func:`added` instead, where they can)."""
    return np.cos(angle), np.sin(angle)


def added(first: Turn, second: Turn) -> Turn:
    """The :data:`Turn` of the sum of two angles."""
    return (first[0] * second[0] - first[1] * second[1],
            first[1] * second[0] + first[0] * second[1])


def backwards(turn: Turn) -> Turn:
    """The opposite :data:`Turn`."""
    return turn[0], -turn[1]


def rotated(axis: FloatArray, angle: FloatArray | Turn, vector: FloatArray) -> FloatArray:
    """``vector`` (3, ...) turned by ``angle`` (...) radians (or a :data:`Turn`) about the
    unit ``axis`` (3,) (Rodrigues' formula)."""
    cosine, sine = angle if isinstance(angle, tuple) else turn_of(angle)
    along = dot(axis, vector) * (1.0 - cosine)
    x, y, z = vector[0], vector[1], vector[2]
    a, b, c = axis
    return _stacked(x * cosine + (b * z - c * y) * sine + a * along,
                    y * cosine + (c * x - a * z) * sine + b * along,
                    z * cosine + (a * y - b * x) * sine + c * along)


def turned_along(directions: Sequence[FloatArray], axis: FloatArray, turn: Turn,
                 vector: FloatArray) -> list[FloatArray]:
    """The components (...) along each constant direction (3,) of the constant ``vector``
    (3,) turned by ``turn`` about the unit ``axis`` (3,): Rodrigues' formula dotted with the
    direction beforehand, three products per sample."""
    cosine, sine = turn
    parts = []
    for direction in directions:
        fixed = float(direction @ axis) * float(axis @ vector)
        parts.append(fixed + cosine * (float(direction @ vector) - fixed)
                     + sine * float(direction @ cross(axis, vector)))
    return parts


def turn_angle(axis: FloatArray, start: FloatArray, end: FloatArray) -> FloatArray:
    """The angle (...) in ``(-pi, pi]`` about the unit ``axis`` (3,) that turns ``start``
    onto ``end`` (3, ...), their parts across the axis compared (0 where either has none)."""
    return np.arctan2(*_turn_parts(axis, start, end))


def turning(axis: FloatArray, start: FloatArray, end: FloatArray
            ) -> tuple[FloatArray, Turn]:
    """:func:`turn_angle` and its :data:`Turn`."""
    return plane_angle(*_turn_parts(axis, start, end))


def plane_angle(sine: FloatArray, cosine: FloatArray) -> tuple[FloatArray, Turn]:
    """The angle (...) whose sine and cosine are ``sine`` and ``cosine`` times one size
    (0 where both are 0), and its :data:`Turn`."""
    size = np.hypot(sine, cosine)
    none = size == 0.0
    if none.any():
        sine, cosine, size = (np.where(none, fill, part) for fill, part in
                              ((0.0, sine), (1.0, cosine), (1.0, size)))
    return np.arctan2(sine, cosine), (cosine / size, sine / size)


def _turn_parts(axis: FloatArray, start: FloatArray, end: FloatArray
                ) -> tuple[FloatArray, FloatArray]:
    """``size^2`` times the sine and the cosine of :func:`turn_angle`."""
    return (dot(axis, cross(start, end)),
            dot(start, end) - dot(axis, start) * dot(axis, end))


Halves = tuple[FloatArray, FloatArray, Turn, Turn]
"""The centre ``g`` and half-width ``h`` of two angles ``g + h`` and ``g - h`` (radians),
and their :data:`Turn` s."""


def two_angles(cos_part: FloatArray, sin_part: FloatArray, value: FloatArray) -> Halves:
    """The :data:`Halves` of the two angles at which ``cos_part cos(x) + sin_part sin(x)``
    equals ``value`` (arrays broadcast); ``h`` is NaN where no angle does
    (:data:`AT_LIMIT`)."""
    size = np.hypot(cos_part, sin_part)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = value / size
        centre_turn = (cos_part / size, sin_part / size)
    ratio = np.where(np.abs(ratio) <= 1.0 + AT_LIMIT, np.clip(ratio, -1.0, 1.0), np.nan)
    return (np.arctan2(sin_part, cos_part), np.arccos(ratio), centre_turn,
            (ratio, np.sqrt((1.0 - ratio) * (1.0 + ratio))))


def one_of(halves: Halves, sign: float | FloatArray) -> tuple[FloatArray, Turn]:
    """The angle ``g + sign h`` of ``halves`` (wrapped into ``[-pi, pi]``) and its
    :data:`Turn`."""
    centre, half, centre_turn, (cosine, sine) = halves
    return wrapped(centre + sign * half), added(centre_turn, (cosine, sign * sine))


def wrapped(angle: FloatArray) -> FloatArray:
    """``angle`` into ``[-pi, pi]`` (whole turns taken off: faster than a modulo)."""
    return angle - TURN * np.rint(angle * (1.0 / TURN))
