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

from ._arm_steps import (
    SINGULAR,
    Arm,
    Down,
    arm_plane,
    branches,
    in_arm_plane,
    two_link_angles,
)
from ._subproblems import (
    Turn,
    applied,
    backwards,
    column,
    cross,
    dot,
    one_of,
    plane_angle,
    rotated,
    turn_of,
    turned_along,
    two_angles,
    wrapped,
)
from .arm_shapes import ArmShape

__all__ = ["ur_solutions"]

FloatArray = NDArray[np.float64]


def ur_solutions(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                 arm: Arm = None, free: FloatArray | None = None) -> FloatArray:
    """As :func:`.opw.opw_solutions`, for a UR-type shape: angles (T, 8, 6), branch
    ``4 back + 2 down + flip``, NaN where out of reach; with ``arm``, (T, 2, 6). At the
    wrist singularity (axis 6 along axes 2 to 4) joint 6 takes ``free`` (else 0). One
    branch at a time, as there."""
    _, groups, angles = branches(shape, rotations, translations, arm)
    for group in groups:
        _wrists_and_links(shape, rotations, translations, group.shoulder[1], group.elbows,
                          free, [out[..., 1:] for out in group.outs])
    return angles


def _wrists_and_links(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                      turn1: Turn, elbows: list[Down], free: FloatArray | None,
                      outs: list[FloatArray]) -> None:
    """Joints 2 to 6 (T, 2, 5) into ``outs`` (one per elbow of ``elbows``), no flip then
    flip, of the arm whose joint 1 turns by ``turn1``."""
    axes, points = shape.axes, shape.points
    normal, forward = shape.parallel, shape.forward
    axis5, axis6 = axes[4], axes[5]
    into_tool = rotations.swapaxes(0, 1)  # (the flange's motion undone)

    def in_tool(vector: FloatArray) -> FloatArray:
        """A constant ``vector`` turned with joint 1, in the tool's axes at zero."""
        return applied(into_tool, rotated(axes[0], turn1, vector))

    normal_in_tool = in_tool(normal)
    halves = two_angles(np.array(normal @ axis6), np.array(normal @ cross(axis5, axis6)),
                        dot(normal_in_tool, axis6))
    # the rotation of joints 2 to 4 about the parallel axes: the angle from forward to what
    # the flange's motion makes of forward with joints 5 and 6 undone
    forward_in_tool, across_in_tool = in_tool(forward), in_tool(cross(normal, forward))
    plane = arm_plane(shape, turn1)
    first6 = axis5 - axis6 * float(axis6 @ axis5)  # two directions across axis 6
    across6 = (first6 / np.linalg.norm(first6), cross(axis6, first6 / np.linalg.norm(first6)))
    starts = [dot(direction, normal_in_tool) for direction in across6]
    straight = np.flatnonzero(halves[3][1] < SINGULAR)
    sign3, sign4 = float(normal @ axes[2]), float(normal @ axes[3])
    for wrist in (0, 1):
        fifth, turn5 = one_of(halves, -1.0 if wrist else 1.0)
        back5 = backwards(turn5)
        # joint 6: from the normal in the tool to the normal with joint 5 undone, across axis 6
        ends = turned_along(across6, axis5, back5, normal)
        sixth, turn6 = plane_angle(starts[0] * ends[1] - starts[1] * ends[0],
                                   starts[0] * ends[0] + starts[1] * ends[1])
        if straight.shape[0]:
            sixth[straight] = 0.0 if free is None else wrapped(free[straight])
            for part, value in zip(turn6, turn_of(sixth[straight]), strict=True):
                part[straight] = value
        back6 = backwards(turn6)
        forward_back = rotated(axis6, back6, rotated(axis5, back5, forward))
        middle = np.arctan2(dot(across_in_tool, forward_back),
                            dot(forward_in_tool, forward_back))
        # where joints 2 and 3 carry axis 4: its point with joints 5 and 6 undone, the
        # flange's motion, joint 1 undone
        moved = rotated(axis5, back5, shape.carried_point - points[4]) + column(points[4], 1)
        moved = rotated(axis6, back6, moved - column(points[5], 1)) + column(points[5], 1)
        moved = applied(rotations, moved) + translations
        links = two_link_angles(shape, in_arm_plane(shape, plane, moved), elbows)
        for out, ((second, _), (third, _)) in zip(outs, links, strict=True):
            out[:, wrist, 0], out[:, wrist, 1] = second, third
            out[:, wrist, 2] = wrapped(sign4 * (middle - second - sign3 * third))
            out[:, wrist, 3], out[:, wrist, 4] = fifth, sixth
