"""Every solution of a UR-type arm (axes 2, 3 and 4 parallel, axis 6 meeting axis 5) for
many flange motions at once.

Axis 5 lies in a plane across the parallel axes that joints 2 to 4 only slide within, and
the point where axes 5 and 6 meet stays on it: joint 1 turns that plane through the point
(front or back). Joints 2 to 4 keep the tool's component along the parallel axes, so axis
6's gives joint 5 (either side of the wrist singularity: no flip or flip), the rest of the
rotation joint 6 and the sum of joints 2 to 4; joints 2 and 3 then carry axis 4 into place
(elbow up or down) and joint 4 takes the remainder. Up to 8 solutions.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ._arm_steps import SINGULAR, into_arm_plane, shoulder_angles, two_link_angles, wrapped
from ._subproblems import (
    applied,
    backwards,
    column,
    dot,
    rotated,
    turn_angle,
    turn_of,
    two_angles,
)
from .arm_shapes import ArmShape

__all__ = ["ur_solutions"]

FloatArray = NDArray[np.float64]


def ur_solutions(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                 arm: int | None = None, free: FloatArray | None = None) -> FloatArray:
    """As :func:`.opw.opw_solutions`, for a UR-type shape: angles (T, 8, 6), branch
    ``4 back + 2 down + flip``, NaN where out of reach; with ``arm``, (T, 2, 6). At the
    wrist singularity (axis 6 along axes 2 to 4) joint 6 takes ``free`` (else 0)."""
    axes, points = shape.axes, shape.points
    normal, forward = shape.parallel, shape.forward
    axis5, axis6 = axes[4], axes[5]
    meeting = applied(rotations, shape.wrist_point) + translations  # (3, T)
    first = shoulder_angles(shape, meeting)  # (T, 2)
    if arm is not None:
        first = first[:, arm // 4:arm // 4 + 1]
    turn1 = turn_of(first)
    tool_axis = rotated(axes[0], backwards(turn1), applied(rotations, axis6)[:, :, None])
    centre5, half5 = two_angles(np.array(normal @ axis6),
                                np.array(normal @ np.cross(axis5, axis6)),
                                dot(normal, tool_axis))
    fifth = wrapped(np.stack([centre5 + half5, centre5 - half5], axis=-1))  # (T, 2, 2)
    normal_in_tool = applied(rotations.swapaxes(0, 1), rotated(axes[0], turn1, normal))
    back5 = backwards(turn_of(fifth))
    sixth = -turn_angle(axis6, rotated(axis5, back5, normal), normal_in_tool[..., None])
    sixth = wrapped(np.where(np.abs(np.sin(half5))[..., None] < SINGULAR,
                             0.0 if free is None else free[:, None, None], sixth))
    # (the rotation of joints 2 to 4 about the parallel axes)
    back6 = backwards(turn_of(sixth))
    forward_back = rotated(axis6, back6, rotated(axis5, back5, forward))
    back1 = backwards((turn1[0][:, :, None], turn1[1][:, :, None]))
    in_arm = rotated(axes[0], back1, applied(rotations, forward_back))
    middle = turn_angle(normal, forward, in_arm)  # (T, 2, 2)
    # where joints 2 and 3 carry axis 4: its point with joints 5 and 6 undone, the flange's
    # motion, joint 1 undone
    moved = rotated(axis5, back5, shape.carried_point - points[4]) + column(points[4], 3)
    moved = rotated(axis6, back6, moved - column(points[5], 3)) + column(points[5], 3)
    moved = applied(rotations, moved) + translations[:, :, None, None]
    in_plane = into_arm_plane(shape, first[:, :, None], moved)  # (3, T, 2, 2)
    second, third = two_link_angles(shape, in_plane)  # (T, 2, 2, 2): shoulder, wrist, elbow
    if arm is not None:
        elbow = (arm // 2) % 2
        second, third = second[..., elbow:elbow + 1], third[..., elbow:elbow + 1]
    sign3, sign4 = float(normal @ axes[2]), float(normal @ axes[3])
    fourth = wrapped(sign4 * (middle[..., None] - second - sign3 * third))
    count = first.shape[0]
    angles = [np.broadcast_to(first[:, :, None, None], second.shape), second, third, fourth,
              np.broadcast_to(fifth[..., None], second.shape),
              np.broadcast_to(sixth[..., None], second.shape)]
    # (T, shoulder, wrist, elbow) to (T, shoulder, elbow, wrist)
    return np.stack(angles, axis=-1).swapaxes(2, 3).reshape(count, -1, 6)
