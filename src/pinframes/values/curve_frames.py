"""Frames along a curve: the axes of a seam frame at each point of a polyline.

At point ``i`` of a polyline ``points`` (N, 3), metres: x is the travel direction, the
direction at the point of the parabola through it and its two neighbours, parametrised by
the length along the chords (the three-point non-uniform difference: with unit chords
``d1`` before and ``d2`` after the point and their lengths ``h1``, ``h2``, the direction of
``h2 d1 + h1 d2``; for equal chords the central difference). At the two ends it is the
same parabola's direction through the first or last three points (``(2 h1 + h2) d1 - h1 d2``
at the start), the chord when there are only two. z is the given normal made
perpendicular to x, and y = z x x. :meth:`pinframes.Pose.along_curve` turns these axes and
the points into a moving pose.

Bad input is an :class:`~pinframes.errors.InvalidPoseError` whose field names the point
(``points[3]``, ``normals[3]``): a point repeating the one before it, a turn within
:data:`MIN_REVERSAL_ANGLE_RAD` of going straight back. Chord lengths are computed without
squaring, so points 1e-170 m apart keep their directions.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidPoseError

__all__ = ["MIN_NORMAL_ANGLE_RAD", "MIN_REVERSAL_ANGLE_RAD", "curve_rotations",
           "length_along_polyline"]

FloatArray = NDArray[np.float64]

MIN_NORMAL_ANGLE_RAD = 1e-6
"""A normal closer than this to the travel direction (radians) leaves z undefined."""

MIN_REVERSAL_ANGLE_RAD = float(np.radians(0.01))
"""A turn closer than this (radians) to going straight back is a reversal: the curve has
no travel direction there."""


def curve_rotations(points: FloatArray, normals: FloatArray) -> FloatArray:
    """Rotation matrices (N, 3, 3) of the frames along ``points`` (N, 3), metres.

    Columns: x the unit travel direction, y = z x x, z the unit part of ``normals`` (N, 3),
    or one (3,) normal for every point, perpendicular to x. Both arrays must be finite.
    """
    _check_points(points)
    normal_stack = _normal_stack(normals, points.shape[0])
    x_axes = _travel_directions(points)
    normal_norms = _lengths(normal_stack)
    if np.any(normal_norms == 0.0):
        index = int(np.argmax(normal_norms == 0.0))
        raise InvalidPoseError(f"the normal of point {index} is zero",
                               field=f"normals[{index}]")
    across = normal_stack - np.sum(normal_stack * x_axes, axis=1, keepdims=True) * x_axes
    across_norms = _lengths(across)
    parallel = across_norms <= np.sin(MIN_NORMAL_ANGLE_RAD) * normal_norms
    if np.any(parallel):
        index = int(np.argmax(parallel))
        raise InvalidPoseError(f"the normal of point {index} is parallel to the travel "
                               f"direction {np.round(x_axes[index], 6).tolist()}",
                               field=f"normals[{index}]")
    z_axes = across / across_norms[:, None]
    return np.stack([x_axes, np.cross(z_axes, x_axes), z_axes], axis=-1)


def _travel_directions(points: FloatArray) -> FloatArray:
    """Unit travel directions (N, 3) along ``points`` (N, 3) with no repeated point."""
    with np.errstate(over="ignore"):
        chords = np.diff(points, axis=0)
    lengths = _lengths(chords)
    overflowing = ~np.isfinite(lengths)
    if np.any(overflowing):
        index = int(np.argmax(overflowing)) + 1
        raise InvalidPoseError(f"point {index} is too far from point {index - 1}: their "
                               "distance overflows", field=f"points[{index}]")
    units = chords / lengths[:, None]
    if points.shape[0] == 2:
        return np.repeat(units, 2, axis=0)
    before, after = units[:-1], units[1:]
    reversed_turn = np.einsum("ij,ij->i", before, after) <= -np.cos(MIN_REVERSAL_ANGLE_RAD)
    if np.any(reversed_turn):
        index = int(np.argmax(reversed_turn)) + 1
        raise InvalidPoseError(f"the curve turns back at point {index} (within "
                               f"{np.degrees(MIN_REVERSAL_ANGLE_RAD):g} degrees of straight "
                               "back), so it has no travel direction there",
                               field=f"points[{index}]")
    # weights as fractions of the two chords' sum: no product of two lengths, which
    # would underflow for points 1e-170 m apart
    near, far = lengths[:-1], lengths[1:]
    first_share = near / (near + far)
    travel = np.empty_like(points)
    travel[1:-1] = (1.0 - first_share)[:, None] * before + first_share[:, None] * after
    travel[0] = (1.0 + first_share[0]) * units[0] - first_share[0] * units[1]
    last_share = far[-1] / (near[-1] + far[-1])
    travel[-1] = (1.0 + last_share) * units[-1] - last_share * units[-2]
    return travel / _lengths(travel)[:, None]


def _lengths(vectors: FloatArray) -> FloatArray:
    """Euclidean lengths of rows (M, 3), without squaring (no underflow or overflow)."""
    return np.hypot(np.hypot(vectors[:, 0], vectors[:, 1]), vectors[:, 2])


def length_along_polyline(points: FloatArray) -> FloatArray:
    """Length along ``points`` (N, 3) from the first point to each point, metres (N,)."""
    steps = _lengths(np.diff(points, axis=0))
    return np.concatenate([[0.0], np.cumsum(steps)])


def _check_points(points: FloatArray) -> None:
    if points.ndim != 2 or points.shape[1] != 3:
        raise InvalidPoseError(f"expected shape (N, 3), got {points.shape}", field="points")
    if points.shape[0] < 2:
        raise InvalidPoseError(f"a curve needs at least 2 points, got {points.shape[0]}",
                               field="points")
    repeated = np.all(points[1:] == points[:-1], axis=1)
    if np.any(repeated):
        index = int(np.argmax(repeated)) + 1
        raise InvalidPoseError(f"point {index} repeats point {index - 1}",
                               field=f"points[{index}]")


def _normal_stack(normals: FloatArray, count: int) -> FloatArray:
    if normals.shape == (3,):
        return np.broadcast_to(normals, (count, 3))
    if normals.shape != (count, 3):
        raise InvalidPoseError(f"expected one normal (3,) or one per point ({count}, 3), got "
                               f"shape {normals.shape}", field="normals")
    return normals
