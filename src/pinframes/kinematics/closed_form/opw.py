"""Every solution of an OPW arm (ortho-parallel base, spherical wrist) for many flange
motions at once.

The wrist centre does not move with joints 4 to 6, so joints 1 to 3 place it: joint 1 turns
the plane of the parallel axes 2 and 3 through it (front or back), joints 2 and 3 reach it
in that plane (elbow up or down). Joints 4 to 6 then turn the tool's axes as the rest of the
rotation asks, an axis-5 angle either side of the straight wrist (no flip or flip). Up to 8
solutions, about a hundred array operations whatever the number of samples.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ._arm_steps import SINGULAR, into_arm_plane, shoulder_angles, two_link_angles, wrapped
from ._subproblems import applied, backwards, dot, rotated, turn_angle, turn_of, two_angles
from .arm_shapes import ArmShape

__all__ = ["opw_solutions"]

FloatArray = NDArray[np.float64]


def opw_solutions(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                  arm: int | None = None, free: FloatArray | None = None) -> FloatArray:
    """Angles (T, 8, 6), radians about the shape's axes, that move the tool from its zero
    configuration by each of ``rotations`` (3, 3, T) and ``translations`` (3, T) (in the
    tool's axes at zero); branch ``4 back + 2 down + flip``; NaN where out of reach. With
    ``arm`` (a branch index), only its shoulder and elbow: (T, 2, 6), no flip then flip.
    Where the wrist is straight, joint 4 takes ``free`` (T,) (radians about its axis; else
    0) and joint 6 the rest."""
    axes = shape.axes
    centre = applied(rotations, shape.wrist_point) + translations  # (3, T)
    first = shoulder_angles(shape, centre)  # (T, 2)
    if arm is not None:
        first = first[:, arm // 4:arm // 4 + 1]
    in_plane = into_arm_plane(shape, first, centre[:, :, None])  # (3, T, 2)
    second, third = two_link_angles(shape, in_plane)  # (T, 2, 2)
    if arm is not None:
        elbow = (arm // 2) % 2
        second, third = second[..., elbow:elbow + 1], third[..., elbow:elbow + 1]
    # the wrist's rotation: the flange's, turned back by joints 1 to 3 (2 and 3 parallel)
    first = np.broadcast_to(first[:, :, None], second.shape)
    back1 = backwards(turn_of(first))
    back23 = backwards(turn_of(second + float(axes[1] @ axes[2]) * third))
    axis4, axis5, axis6 = axes[3], axes[4], axes[5]

    def wrist_turned(vector: FloatArray) -> FloatArray:
        turned = rotated(axes[0], back1, applied(rotations, vector)[:, :, None, None])
        return rotated(axes[1], back23, turned)

    tool_axis = wrist_turned(axis6)  # (3, T, 2, 2)
    centre5, half5 = two_angles(np.array(axis4 @ axis6),
                                np.array(axis4 @ np.cross(axis5, axis6)),
                                dot(axis4, tool_axis))
    fifth = wrapped(np.stack([centre5 + half5, centre5 - half5], axis=-1))  # (T, 2, 2, 2)
    turn5 = turn_of(fifth)
    fourth = turn_angle(axis4, rotated(axis5, turn5, axis6), tool_axis[..., None])
    fourth = np.where(np.abs(np.sin(half5))[..., None] < SINGULAR,
                      0.0 if free is None else free[:, None, None, None], fourth)
    across = rotated(axis4, -fourth, wrist_turned(axis5)[..., None])
    sixth = turn_angle(axis6, axis5, rotated(axis5, backwards(turn5), across))
    count = first.shape[0]
    angles = [np.broadcast_to(angle[..., None], fifth.shape) for angle in
              (first, second, third)] + [fourth, fifth, sixth]
    return np.stack(angles, axis=-1).reshape(count, -1, 6)
