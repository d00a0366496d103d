"""The steps both closed forms share: joint 1 from the point the plane of axes 2 and 3 must
pass through, and joints 2 and 3 (parallel) from the point they carry into place. Angles
are radians about the unit axes of :class:`.arm_shapes.ArmShape`, samples first; vectors
``(3, ...)`` as :mod:`._subproblems` holds them."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ._subproblems import column, dot, rotated, turn_angle, two_angles
from .arm_shapes import ArmShape

__all__ = ["SINGULAR", "TURN", "into_arm_plane", "shoulder_angles", "two_link_angles", "wrapped"]

FloatArray = NDArray[np.float64]

SINGULAR = 1e-7
"""Below this sine of the wrist's bend the wrist counts as straight: joint 4 (OPW) or
joint 6 (UR-type) is then taken as given (or 0) and the other wrist joint turns for both.
(Rounding alone bends a straight wrist by about 1e-8 rad, which leaves the two joints'
split to noise; taking the split as given turns the tool by at most pi times this.)"""


TURN = 2.0 * math.pi
"""One turn, radians."""


def wrapped(angle: FloatArray) -> FloatArray:
    """``angle`` into ``[-pi, pi]`` (whole turns taken off: faster than a modulo)."""
    return angle - TURN * np.rint(angle * (1.0 / TURN))


def shoulder_angles(shape: ArmShape, point: FloatArray) -> FloatArray:
    """Joint 1's two angles (..., 2), front then back, that put the plane in which axes 2 and
    3 carry :attr:`ArmShape.wrist_point` through ``point`` (3, ...); NaN out of reach."""
    axis, normal = shape.axes[0], shape.parallel
    reach = point - column(shape.points[0], point.ndim - 1)
    wanted = np.array(float(np.dot(normal, shape.wrist_point - shape.points[0])))
    centre, half = two_angles(dot(normal, reach), dot(np.cross(axis, normal), reach), wanted)
    side = shape.front_sign * half
    return wrapped(np.stack([centre + side, centre - side], axis=-1))


def into_arm_plane(shape: ArmShape, shoulder: FloatArray, point: FloatArray) -> FloatArray:
    """``point`` (3, ...) turned back by joint 1's ``shoulder`` angles (...)."""
    origin = column(shape.points[0], point.ndim - 1)
    return rotated(shape.axes[0], -shoulder, point - origin) + origin


def two_link_angles(shape: ArmShape, point: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Joints 2 and 3 (each (..., 2), elbow up then down) that carry
    :attr:`ArmShape.carried_point` to ``point`` (3, ...), given in the arm's plane at joint
    1 zero (:func:`into_arm_plane`); NaN where out of reach."""
    axis2, axis3 = shape.axes[1], shape.axes[2]
    shoulder, elbow = shape.points[1], shape.points[2]
    offset = shape.carried_point - elbow
    across = offset - axis3 * np.dot(offset, axis3)
    between = elbow - shoulder
    between = between - axis3 * np.dot(between, axis3)
    to_point = point - column(shoulder, point.ndim - 1)
    distance_squared = dot(to_point, to_point) - dot(axis2, to_point) ** 2
    value = 0.5 * (distance_squared - across @ across - between @ between)
    centre, half = two_angles(np.array(between @ across),
                              np.array(between @ np.cross(axis3, across)), value)
    _, up_sign = shape.elbow  # the centre is the stretched angle
    elbow_angles = wrapped(np.stack([centre + up_sign * half, centre - up_sign * half],
                                    axis=-1))
    carried = rotated(axis3, elbow_angles, offset) + column(elbow - shoulder, point.ndim)
    upper_arm = turn_angle(axis2, carried, to_point[..., None])
    return upper_arm, elbow_angles
