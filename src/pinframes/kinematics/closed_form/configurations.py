"""The configuration flags of a recognised arm, from its joint values, and the vendor forms
that follow from them.

- shoulder ``front`` / ``back``: the wrist point (the wrist centre of an OPW arm, where
  axes 5 and 6 meet on a UR-type arm) lies on the :attr:`~.arm_shapes.ArmShape.forward`
  side of axis 1 (turned with joint 1), or behind it;
- elbow ``up`` / ``down``: joint 3 on the side of the stretched-arm angle that puts the
  elbow above the line from axis 2 to the point joints 2 and 3 carry (the wrist centre; a
  UR-type arm's axis 4) while the arm reaches forward, or the other side;
- wrist ``noflip`` / ``flip``: joint 5 above the straight-wrist angle (axis 6 along axis 4,
  or on a UR-type arm along axes 2 to 4; that angle is 0 on every arm we know), or not
  (the straight wrist itself counts as ``flip``, as KUKA's Status does).

A branch is named ``"front,up,noflip"``: its index is ``4 back + 2 down + flip``.

KUKA's Status and Turn are read from the joint values as KUKA's controllers define them,
in the signs of the URDF's joints (ROS-Industrial's KUKA descriptions use the controller's):
Status bit 0 the wrist point behind axis 1, bit 1 joint 3 at or above the stretched-arm
angle (in ``(-pi, pi]``), bit 2 joint 5 at or below 0; Turn bit ``i`` joint ``i + 1``
below 0. ABB's ``cf1``, ``cf4``, ``cf6`` are the quadrants of joints 1, 4 and 6
(``floor(q / (pi / 2))``); ABB's ``cfx`` (6-axis arms) is 4 where the wrist centre is behind
axis 1 (``back``), plus 2 where it is behind the lower arm (the line from axis 2 to axis 3:
``down``), plus 1 where joint 5 is below 0 (at 0: positive, where the flags say ``flip``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentTypeError
from ._subproblems import column, cross, dot, rotated, wrapped
from .arm_shapes import ArmShape

__all__ = ["BRANCH_NAMES", "abb_cfx", "abb_quadrants", "branch_flags", "kuka_status", "kuka_turn",
           "requested_branch", "wrist_flips"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

_WORDS = (("front", "back"), ("up", "down"), ("noflip", "flip"))

ON_AXIS = 1e-12
"""Metres within which the wrist point lies on an axis (which then leaves it in place)."""

BRANCH_NAMES = tuple(f"{shoulder},{elbow},{wrist}" for shoulder in _WORDS[0]
                     for elbow in _WORDS[1] for wrist in _WORDS[2])
"""The eight branches, by index ``4 back + 2 down + flip``."""


def branch_flags(shape: ArmShape, positions: FloatArray) -> IntArray:
    """The branch index ``4 back + 2 down + flip`` (...) of joint values ``positions``
    (..., 6) in the shape's joint order (NaN values count as 0)."""
    def angle(joint: int) -> FloatArray:
        return np.nan_to_num(positions[..., joint] * shape.scales[joint])

    axes, points = shape.axes, shape.points
    extra = positions.ndim - 1
    wrist = column(shape.wrist_point - points[0], extra)
    for joint in (4, 3, 2, 1):  # the wrist point through joints 5 to 2 (6 keeps it)
        off_axis = cross(axes[joint], shape.wrist_point - points[joint])
        if float(off_axis @ off_axis) <= ON_AXIS * ON_AXIS:
            continue  # the axis passes through the wrist point: it stays
        point = column(points[joint] - points[0], extra)
        wrist = rotated(axes[joint], angle(joint), wrist - point) + point
    back = dot(shape.forward, wrist) < 0.0
    stretched, up_sign = shape.elbow
    # (the sign of a sine from the angle wrapped into [-pi, pi]: numpy's sine takes 13 ns)
    down = up_sign * wrapped(angle(2) - stretched) <= 0.0
    return 4 * back.astype(np.int64) + 2 * down + wrist_flips(shape, positions[..., 4])


def wrist_flips(shape: ArmShape, fifth: FloatArray) -> IntArray:
    """1 where joint 5's values ``fifth`` (...) flip the wrist, else 0 (NaN counts as 0)."""
    return (wrapped(np.nan_to_num(fifth * shape.scales[4]) - shape.wrist_straight)
            <= 0.0).astype(np.int64)


def requested_branch(configuration: Any, field: str = "configuration",
                     frame: str | None = None) -> tuple[str, int]:
    """``("flags", index)`` for words such as ``"front,up,noflip"`` (any order, one of each
    pair), ``("kuka_status", value)`` for a KUKA Status 0..7 (an int or its digits)."""
    if isinstance(configuration, (int, np.integer)) and not isinstance(configuration, bool):
        status = int(configuration)
    elif isinstance(configuration, str) and configuration.strip().isdigit():
        status = int(configuration.strip())
    elif isinstance(configuration, str):
        words = [word.strip().lower() for word in configuration.split(",") if word.strip()]
        index = 0
        for weight, pair in zip((4, 2, 1), _WORDS, strict=True):
            chosen = [word for word in words if word in pair]
            if len(chosen) != 1:
                raise ArgumentTypeError(
                    f"expected one of {' / '.join(pair)} in {configuration!r} (a "
                    "configuration is e.g. 'front,up,noflip', or a KUKA Status 0..7)",
                    frame=frame, field=field)
            index += weight * pair.index(chosen[0])
        unknown = [word for word in words if not any(word in pair for pair in _WORDS)]
        if unknown:
            raise ArgumentTypeError(f"unknown configuration word {unknown[0]!r} (known: "
                                    f"{', '.join(w for pair in _WORDS for w in pair)})",
                                    frame=frame, field=field)
        return "flags", index
    else:
        raise ArgumentTypeError(f"expected configuration words such as 'front,up,noflip' or "
                                f"a KUKA Status 0..7, got {configuration!r}", frame=frame,
                                field=field)
    if not 0 <= status <= 7:
        raise ArgumentTypeError(f"a KUKA Status is 0..7 (three bits), got {status}",
                                frame=frame, field=field)
    return "kuka_status", status


def kuka_status(shape: ArmShape, positions: FloatArray) -> IntArray:
    """KUKA's Status (...) of joint values ``positions`` (..., 6) in the shape's order."""
    stretched = shape.elbow[0] / shape.scales[2]
    period = 2.0 * math.pi / shape.scales[2]
    stretched = stretched - period * math.floor((stretched + 0.5 * period) / period)
    back = branch_flags(shape, positions) >= 4
    return (back + 2 * (positions[..., 2] >= stretched)
            + 4 * (positions[..., 4] <= 0.0)).astype(np.int64)


def kuka_turn(positions: FloatArray) -> IntArray:
    """KUKA's Turn (...): bit ``i`` set where joint ``i + 1`` of ``positions`` (..., 6) is
    below 0."""
    return np.sum((positions < 0.0) << np.arange(positions.shape[-1]), axis=-1)


def abb_quadrants(positions: FloatArray) -> IntArray:
    """ABB's ``cf1``, ``cf4``, ``cf6`` (..., 3): the quadrants ``floor(q / (pi / 2))`` of
    joints 1, 4 and 6 of ``positions`` (..., 6)."""
    return np.floor(positions[..., [0, 3, 5]] / (0.5 * math.pi)).astype(np.int64)


def abb_cfx(shape: ArmShape, positions: FloatArray) -> IntArray:
    """ABB's ``cfx`` (...) of joint values ``positions`` (..., 6) in the shape's order: the
    branch index with joint 5 at 0 counted as positive (``noflip``), not as ``flip``."""
    index = branch_flags(shape, positions)
    return (index - index % 2 + (positions[..., 4] < 0.0)).astype(np.int64)
