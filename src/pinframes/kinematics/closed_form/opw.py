"""Every solution of an OPW arm (ortho-parallel base, spherical wrist) for many flange
motions at once.

The wrist centre does not move with joints 4 to 6, so joints 1 to 3 place it: joint 1 turns
the plane of the parallel axes 2 and 3 through it (front or back), joints 2 and 3 reach it
in that plane (elbow up or down). Joints 4 to 6 then turn the tool's axes as the rest of the
rotation asks, an axis-5 angle either side of the straight wrist (no flip or flip; the flip
is the same rotation about the wrist centre with joints 4 and 6 half a turn on). Up to 8
solutions, about a hundred array operations per arm whatever the number of samples.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ._arm_steps import (
    SINGULAR,
    Angle,
    Arm,
    arm_plane,
    branches,
    in_arm_plane,
    two_link_angles,
)
from ._subproblems import (
    Turn,
    added,
    applied,
    backwards,
    cross,
    dot,
    one_of,
    rotated,
    turn_angle,
    turn_of,
    turning,
    two_angles,
    wrapped,
)
from .arm_shapes import ArmShape

__all__ = ["opw_solutions"]

FloatArray = NDArray[np.float64]


def opw_solutions(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                  arm: Arm = None, free: FloatArray | None = None) -> FloatArray:
    """Angles (T, 8, 6), radians about the shape's axes, that move the tool from its zero
    configuration by each of ``rotations`` (3, 3, T) and ``translations`` (3, T) (in the
    tool's axes at zero); branch ``4 back + 2 down + flip``; NaN where out of reach. With
    ``arm`` (a branch index), only its shoulder and elbow: (T, 2, 6), no flip then flip.
    Where the wrist is straight, joint 4 takes ``free`` (T,) (radians about its axis; else
    0) and joint 6 the rest.

    Each array holds one value per sample (a branch at a time: numpy broadcasting a few
    branches against the samples runs inner loops a few elements long, several times
    slower), and each angle's cosine and sine come from products of those it is made of."""
    point, groups, angles = branches(shape, rotations, translations, arm)
    for group in groups:
        turn1 = group.shoulder[1]
        links = two_link_angles(shape, in_arm_plane(shape, arm_plane(shape, turn1), point),
                                group.elbows)
        for out, (second, third) in zip(group.outs, links, strict=True):
            out[..., 1], out[..., 2] = second[0][:, None], third[0][:, None]
            _wrists(shape, rotations, backwards(turn1), second, third, free, out[..., 3:])
    return angles


def _wrists(shape: ArmShape, rotations: FloatArray, back1: Turn, second: Angle,
            third: Angle, free: FloatArray | None, out: FloatArray) -> None:
    """Joints 4 to 6 (T, 2, 3) into ``out``, no flip then flip, of the arm that joint 1
    (turned back by ``back1``) and joints 2 and 3 place."""
    axes = shape.axes
    # the wrist's rotation: the flange's, turned back by joints 1 to 3 (2 and 3 parallel)
    back23 = backwards(added(second[1], third[1] if float(axes[1] @ axes[2]) > 0.0
                             else backwards(third[1])))
    axis4, axis5, axis6 = axes[3], axes[4], axes[5]

    def wrist_turned(vector: FloatArray) -> FloatArray:
        return rotated(axes[1], back23, rotated(axes[0], back1, applied(rotations, vector)))

    tool_axis = wrist_turned(axis6)  # (3, T)
    halves = two_angles(np.array(axis4 @ axis6), np.array(axis4 @ cross(axis5, axis6)),
                        dot(axis4, tool_axis))
    fifth, turn5 = one_of(halves, 1.0)  # no flip
    fourth, turn4 = turning(axis4, rotated(axis5, turn5, axis6), tool_axis)
    straight = np.flatnonzero(halves[3][1] < SINGULAR)
    if straight.shape[0]:
        fourth[straight] = 0.0 if free is None else free[straight]
        for part, value in zip(turn4, turn_of(fourth[straight]), strict=True):
            part[straight] = value
    across = rotated(axis4, backwards(turn4), wrist_turned(axis5))
    sixth = turn_angle(axis6, axis5, rotated(axis5, backwards(turn5), across))
    out[:, 0, 0], out[:, 0, 1], out[:, 0, 2] = fourth, fifth, sixth
    # the flip: joints 4 and 6 half a turn on, joint 5 mirrored about the straight wrist
    # (the same rotation about the wrist centre); a straight wrist keeps its one solution
    for column, angle, shift in ((0, fourth, np.pi), (1, -fifth, 2.0 * shape.wrist_straight),
                                 (2, sixth, np.pi)):
        out[:, 1, column] = wrapped(angle + shift)
    out[straight, 1] = out[straight, 0]
