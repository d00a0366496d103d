"""How far a tool frame is from its target, and the rows of the Newton system that closes it.

``X`` is the pose of the tool in the target (a ``pinocchio.SE3``: the tool's axes and origin
written in the target's). The solver moves the joints by ``d`` with ``rows @ d = -error``
where ``rows`` is the tool's Jacobian in its own axes (Pinocchio's ``LOCAL``: the origin's
velocity, then the angular velocity, in the tool's axes) per unit rate of each joint:

- the whole pose: ``error = log6(X)``, the twist that carries the target onto the tool. Its
  derivative is ``Jlog6(X) @ J`` and ``Jlog6(X)^-1 @ log6(X) = log6(X)``, so this is Newton's
  step on the SE(3) logarithm without ``Jlog6``.
- ``free_axis`` (``"x"``, ``"y"`` or ``"z"`` of the tool): the origin, and the direction of
  that axis. Rotation about it is free: the rows are the three linear ones
  (``error = R^T p``) and the two angular ones across the axis (``error`` the rotation
  carrying the target's axis onto the tool's, written in the tool's axes).

:meth:`PoseMatch.measure` gives the position error (m, the distance between the origins) and
the orientation error (rad: the angle of the rotation between the frames, or between the two
axes), which the tolerances are checked against.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

__all__ = ["AXES", "AxisMatch", "PoseMatch", "ToolMatch"]

FloatArray = NDArray[np.float64]

AXES = ("x", "y", "z")
"""The tool axes that ``free_axis`` may name."""

_IDENTITY = pin.SE3.Identity()


class PoseMatch:
    """What must match: the whole pose of the tool and the target's."""

    def measure(self, tool_in_target: pin.SE3) -> tuple[float, float, FloatArray]:
        """Position error (m), orientation error (rad) and the error vector (6,)."""
        error = pin.log6(tool_in_target).vector
        _, _, _, turn_x, turn_y, turn_z = error.tolist()
        return (math.hypot(*tool_in_target.translation.tolist()),
                math.hypot(turn_x, turn_y, turn_z), error)

    def rows(self, jacobian: FloatArray) -> FloatArray:
        """The rows of the Newton system from the tool's ``LOCAL`` Jacobian (6, n)."""
        return jacobian

    def nearest_match(self, tool_in_target: pin.SE3) -> pin.SE3:
        """The pose in the target's axes nearest to the tool that matches: the target."""
        return _IDENTITY

    def errors(self, rotations: FloatArray, translations: FloatArray
               ) -> tuple[FloatArray, FloatArray]:
        """Position errors (m) and orientation errors (rad), shape (N,), of many tool poses
        in their targets (``(N, 3, 3)`` rotations, ``(N, 3)`` translations)."""
        sines = 0.5 * np.sqrt(
            (rotations[:, 2, 1] - rotations[:, 1, 2]) ** 2
            + (rotations[:, 0, 2] - rotations[:, 2, 0]) ** 2
            + (rotations[:, 1, 0] - rotations[:, 0, 1]) ** 2)
        cosines = 0.5 * (np.trace(rotations, axis1=1, axis2=2) - 1.0)
        return np.linalg.norm(translations, axis=1), np.arctan2(sines, cosines)


class AxisMatch:
    """What must match: the tool's origin and one of its axes and the target's; rotation
    about that axis is free."""

    def __init__(self, axis: str) -> None:
        self.axis = AXES.index(axis)
        # the two axes across it, in cyclic order: axis x next = after
        self._next, self._after = (self.axis + 1) % 3, (self.axis + 2) % 3
        self._kept_rows = [0, 1, 2, 3 + self._next, 3 + self._after]

    def measure(self, tool_in_target: pin.SE3) -> tuple[float, float, FloatArray]:
        """Position error (m), the angle between the two axes (rad) and the error vector
        (5,)."""
        rotation = tool_in_target.rotation
        offset = tool_in_target.translation
        target_axis = rotation[self.axis].tolist()  # the target's axis in the tool's axes
        ahead, behind = target_axis[self._next], target_axis[self._after]
        sine = math.hypot(ahead, behind)
        angle = math.atan2(sine, target_axis[self.axis])
        error = np.empty(5)
        error[:3] = rotation.T.dot(offset)
        if sine > 0.0:
            # the rotation carrying the target's axis onto the tool's: (target x tool) / sine
            # * angle, whose components across the tool axis are (behind, -ahead) / sine * angle
            scale = angle / sine
            error[3] = scale * behind
            error[4] = -scale * ahead
        else:  # aligned (angle 0), or opposite: half a turn about any axis across, the next
            error[3] = angle
            error[4] = 0.0
        return math.hypot(*offset.tolist()), angle, error

    def rows(self, jacobian: FloatArray) -> FloatArray:
        """The rows of the Newton system from the tool's ``LOCAL`` Jacobian (6, n)."""
        return jacobian[self._kept_rows]

    def nearest_match(self, tool_in_target: pin.SE3) -> pin.SE3:
        """The pose in the target's axes nearest to the tool that matches: the target turned
        about its axis as far as the tool's next axis is, seen along that axis."""
        next_axis = tool_in_target.rotation[:, self._next]
        turn = math.atan2(next_axis[self._after], next_axis[self._next])
        rotation = np.zeros(3)
        rotation[self.axis] = turn
        return pin.SE3(pin.exp3(rotation), np.zeros(3))

    def errors(self, rotations: FloatArray, translations: FloatArray
               ) -> tuple[FloatArray, FloatArray]:
        """Position errors (m) and angles between the axes (rad), shape (N,), of many tool
        poses in their targets (``(N, 3, 3)`` rotations, ``(N, 3)`` translations)."""
        tool_axes = rotations[:, :, self.axis]
        sines = np.hypot(tool_axes[:, self._next], tool_axes[:, self._after])
        return (np.linalg.norm(translations, axis=1),
                np.arctan2(sines, tool_axes[:, self.axis]))


ToolMatch = PoseMatch | AxisMatch
"""What a solve makes match between the tool and its target."""
