"""Frames along a curve: the axes of a seam frame at each point of a polyline.

At point ``i`` of a polyline ``points`` (N, 3), metres: x is the travel direction (the
central difference ``points[i + 1] - points[i - 1]``; at the two ends the one-sided
difference of the same (second) order, the direction of the parabola through the first or
last three points; the chord when there are only two), z is the given normal made
perpendicular to x, and y = z x x. :meth:`pinframes.Pose.along_curve`
turns these axes and the points into a moving pose.

Bad input is an :class:`~pinframes.errors.InvalidPoseError` whose field names the point
(``points[3]``, ``normals[3]``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidPoseError

__all__ = ["MIN_NORMAL_ANGLE_RAD", "curve_rotations", "length_along_polyline"]

FloatArray = NDArray[np.float64]

MIN_NORMAL_ANGLE_RAD = 1e-6
"""A normal closer than this to the travel direction (radians) leaves z undefined."""


def curve_rotations(points: FloatArray, normals: FloatArray) -> FloatArray:
    """Rotation matrices (N, 3, 3) of the frames along ``points`` (N, 3), metres.

    Columns: x the unit travel direction, y = z x x, z the unit part of ``normals`` (N, 3),
    or one (3,) normal for every point, perpendicular to x. Both arrays must be finite.
    """
    _check_points(points)
    normal_stack = _normal_stack(normals, points.shape[0])
    travel = np.empty_like(points)
    travel[1:-1] = points[2:] - points[:-2]
    if points.shape[0] == 2:
        travel[:] = points[1] - points[0]
    else:
        travel[0] = _one_sided(points[0], points[1], points[2])
        travel[-1] = -_one_sided(points[-1], points[-2], points[-3])
    travel_norms = np.linalg.norm(travel, axis=1)
    if np.any(travel_norms == 0.0):
        index = int(np.argmax(travel_norms == 0.0))
        raise InvalidPoseError(f"the curve turns back at point {index}: its neighbours "
                               "coincide, so it has no travel direction there",
                               field=f"points[{index}]")
    x_axes = travel / travel_norms[:, None]
    normal_norms = np.linalg.norm(normal_stack, axis=1)
    if np.any(normal_norms == 0.0):
        index = int(np.argmax(normal_norms == 0.0))
        raise InvalidPoseError(f"the normal of point {index} is zero",
                               field=f"normals[{index}]")
    across = normal_stack - np.sum(normal_stack * x_axes, axis=1, keepdims=True) * x_axes
    across_norms = np.linalg.norm(across, axis=1)
    parallel = across_norms <= np.sin(MIN_NORMAL_ANGLE_RAD) * normal_norms
    if np.any(parallel):
        index = int(np.argmax(parallel))
        raise InvalidPoseError(f"the normal of point {index} is parallel to the travel "
                               f"direction {np.round(x_axes[index], 6).tolist()}",
                               field=f"normals[{index}]")
    z_axes = across / across_norms[:, None]
    return np.stack([x_axes, np.cross(z_axes, x_axes), z_axes], axis=-1)


def _one_sided(first: FloatArray, second: FloatArray, third: FloatArray) -> FloatArray:
    """The direction at ``first`` of the parabola through three points, parametrised by
    the length along their chords (second order, as the central differences inside; for
    equal chords ``4 second - 3 first - third``)."""
    near = float(np.linalg.norm(second - first))
    far = float(np.linalg.norm(third - second))
    return ((near + far) / (near * far) * (second - first)
            - near / (far * (near + far)) * (third - first))


def length_along_polyline(points: FloatArray) -> FloatArray:
    """Length along ``points`` (N, 3) from the first point to each point, metres (N,)."""
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
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
