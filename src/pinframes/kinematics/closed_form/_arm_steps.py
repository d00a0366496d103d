"""The steps both closed forms share: joint 1 from the point the plane of axes 2 and 3 must
pass through, and joints 2 and 3 (parallel) from the point they carry into place, in its
two coordinates across the parallel axes. Angles are radians about the unit axes of
:class:`.arm_shapes.ArmShape`, one value per sample (one branch at a time); vectors
``(3, ...)`` as :mod:`._subproblems` holds them."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ._subproblems import (
    TURN,
    Turn,
    applied,
    column,
    cross,
    dot,
    one_of,
    plane_angle,
    rotated,
    turned_along,
    two_angles,
    wrapped,
)
from .arm_shapes import ArmShape

__all__ = ["SINGULAR", "TURN", "Angle", "Arm", "ArmGroup", "Down", "Plane", "arm_plane",
           "branches", "in_arm_plane", "shoulder_angles", "two_link_angles", "wrapped"]

FloatArray = NDArray[np.float64]

SINGULAR = 1e-7
"""Below this sine of the wrist's bend the wrist counts as straight: joint 4 (OPW) or
joint 6 (UR-type) is then taken as given (or 0) and the other wrist joint turns for both.
(Rounding alone bends a straight wrist by about 1e-8 rad, which leaves the two joints'
split to noise; taking the split as given turns the tool by at most pi times this.)"""

Angle = tuple[FloatArray, Turn]
"""An angle (radians, per sample) and its :data:`._subproblems.Turn`."""


Arm = int | NDArray[np.int64] | None
"""The arm branches a closed form solves: a branch index (its shoulder and elbow), one per
sample, or None (all eight)."""

Down = int | NDArray[np.bool_]
"""Elbow down (1) or up (0): at every sample, or per sample."""


@dataclass(frozen=True)
class ArmGroup:
    """Arm branches a closed form solves together: one joint 1 angle per sample.

    Attributes
    ----------
    shoulder : Angle
        Joint 1 (radians about axis 1) and its turn.
    elbows : list of Down
        The elbows asked.
    outs : list of ndarray, shape (T, 2, 6)
        Per elbow, its rows of the result (no flip, flip), joint 1 filled in.
    """

    shoulder: Angle
    elbows: list[Down]
    outs: list[FloatArray]


def branches(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
             arm: Arm) -> tuple[FloatArray, list[ArmGroup], FloatArray]:
    """What a closed form fills for the flange motions ``rotations`` (3, 3, T) and
    ``translations`` (3, T): where they move :attr:`ArmShape.wrist_point` (3, T), the
    groups of arms to solve and the result (T, k, 6) they fill: all eight branches (k = 8),
    or ``arm``'s shoulder and elbow (a branch index, or one per sample: k = 2)."""
    point = applied(rotations, shape.wrist_point) + translations
    front, back = shoulder_angles(shape, point)
    # (held branch by branch, joint by joint, samples last: each joint's values are written
    # in one contiguous pass; the result reads as samples first)
    angles = np.empty((2 if arm is not None else 8, 6, translations.shape[-1])
                      ).transpose(2, 0, 1)
    if arm is None:
        groups = [ArmGroup(side, [0, 1], [angles[:, slot:slot + 2], angles[:, slot + 2:slot + 4]])
                  for side, slot in ((front, 0), (back, 4))]
    elif isinstance(arm, (int, np.integer)):
        groups = [ArmGroup(back if arm & 4 else front, [arm // 2 % 2], [angles])]
    else:
        behind = (arm & 4) > 0
        groups = [ArmGroup((np.where(behind, back[0], front[0]),
                            (np.where(behind, back[1][0], front[1][0]),
                             np.where(behind, back[1][1], front[1][1]))),
                           [(arm & 2) > 0], [angles])]
    for group in groups:
        for out in group.outs:
            out[..., 0] = group.shoulder[0][:, None]
    return point, groups, angles


def shoulder_angles(shape: ArmShape, point: FloatArray) -> list[Angle]:
    """Joint 1's two angles (...), front then back, that put the plane in which axes 2 and
    3 carry :attr:`ArmShape.wrist_point` through ``point`` (3, ...); NaN out of reach."""
    axis, normal = shape.axes[0], shape.parallel
    reach = point - column(shape.points[0], point.ndim - 1)
    wanted = np.array(float(np.dot(normal, shape.wrist_point - shape.points[0])))
    halves = two_angles(dot(normal, reach), dot(cross(axis, normal), reach), wanted)
    return [one_of(halves, shape.front_sign), one_of(halves, -shape.front_sign)]


Plane = tuple[FloatArray, FloatArray]
"""Two directions (3, T) across the parallel axes, turned with joint 1: the arm's
:attr:`ArmShape.forward` and ``parallel x forward`` (see :func:`arm_plane`)."""


def arm_plane(shape: ArmShape, shoulder: Turn) -> Plane:
    """The :data:`Plane` of joint 1's ``shoulder`` angles (...)."""
    forward = shape.forward
    return (rotated(shape.axes[0], shoulder, forward),
            rotated(shape.axes[0], shoulder, cross(shape.parallel, forward)))


def in_arm_plane(shape: ArmShape, plane: Plane, point: FloatArray) -> Plane:
    """Where ``point`` (3, ...) lies from axis 2, across the parallel axes: its coordinates
    along the two directions of ``plane`` (metres, each (...)), joint 1 undone."""
    origin = shape.points[0]
    reach = point - column(origin, point.ndim - 1)
    offset = origin - shape.points[1]
    forward = shape.forward
    return (dot(plane[0], reach) + float(forward @ offset),
            dot(plane[1], reach) + float(cross(shape.parallel, forward) @ offset))


def two_link_angles(shape: ArmShape, point: Plane, elbows: Sequence[Down] = (0, 1)
                    ) -> list[tuple[Angle, Angle]]:
    """Joints 2 and 3 (each (...)) of each of ``elbows`` (0 up, 1 down) that carry
    :attr:`ArmShape.carried_point` to ``point``, given by its coordinates across the
    parallel axes (:func:`in_arm_plane`); NaN where out of reach. (In those two
    coordinates joints 2 and 3 turn about one point: a few products per sample.)"""
    axis3 = shape.axes[2]
    shoulder, elbow = shape.points[1], shape.points[2]
    forward = shape.forward
    sideways = cross(shape.parallel, forward)
    offset = shape.carried_point - elbow
    across = offset - axis3 * np.dot(offset, axis3)
    between = elbow - shoulder
    between = between - axis3 * np.dot(between, axis3)
    along, beside = point
    value = 0.5 * (along * along + beside * beside - across @ across - between @ between)
    halves = two_angles(np.array(between @ across),
                        np.array(between @ cross(axis3, across)), value)
    _, up_sign = shape.elbow  # the centre is the stretched angle
    places = [float(direction @ (elbow - shoulder)) for direction in (forward, sideways)]
    angles = []
    for down in elbows:
        third = one_of(halves, np.where(down, -up_sign, up_sign))
        # the carried point from axis 2: offset turned by joint 3, then the elbow's place
        carried = [part + place for part, place in zip(
            turned_along((forward, sideways), axis3, third[1], offset), places, strict=True)]
        sine_part = carried[0] * beside - carried[1] * along
        cosine_part = carried[0] * along + carried[1] * beside
        angles.append((plane_angle(sine_part, cosine_part), third))
    return angles
