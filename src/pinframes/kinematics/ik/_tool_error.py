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

- process windows (``tilt=``, :class:`WindowMatch`): the origin, and the tool's z within
  windows of tilt about the target's x and y; the rows of the tilt angles enter only past
  their windows (and the spin's, unless it is free).

:meth:`PoseMatch.measure` gives the position error (m, the distance between the origins) and
the orientation error (rad: the angle of the rotation between the frames, or between the two
axes), which the tolerances are checked against.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

__all__ = ["AXES", "AxisMatch", "PoseMatch", "ToolMatch", "WindowMatch", "tilts_of"]

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


class WindowMatch:
    """What must match: the tool's origin, and its z within windows of tilt about the
    target's x and y (process windows: work and travel angles); with ``free_spin`` its
    rotation about z is free, else it is the target's carried by the tilt.

    The tilt is the tool's orientation in the target written ``Rx(a) Ry(b) Rz(c)`` (x, then
    the new y, then the new z; radians): ``(a, b)`` turn the target's z onto the tool's,
    ``z = (sin b, -sin a cos b, cos a cos b)`` in the target's axes, and ``c`` is the spin.
    Within the windows, ``|a| <= about_x`` and ``|b| <= about_y``, the tilt is free: its rows
    leave the Newton system (the solver spends it on the smallest motion and on reach); past
    a window, the row of that angle asks for the excess back. The orientation error is the
    Euclidean norm of the excesses (and of the spin without ``free_spin``), radians.
    """

    def __init__(self, about_x: float, about_y: float, free_spin: bool) -> None:
        self.windows = (about_x, about_y)
        self.free_spin = free_spin
        self._active = [0, 1, 2]  # rows kept at the latest measure: position, then angles
        self._rates = np.eye(3)  # Euler rates per local angular velocity there

    def measure(self, tool_in_target: pin.SE3) -> tuple[float, float, FloatArray]:
        """Position error (m), orientation error (rad) and the error vector (the position
        in the tool's axes, then the excess of each angle past its window)."""
        rotation = tool_in_target.rotation
        offset = tool_in_target.translation
        about_x, about_y = self.windows
        tilt_x, tilt_y, spin = _euler_xyz(rotation)
        excesses = [_excess(tilt_x, about_x), _excess(tilt_y, about_y),
                    0.0 if self.free_spin else spin]
        active = [0, 1, 2] + [3 + index for index, excess in enumerate(excesses)
                              if excess or (index == 2 and not self.free_spin)]
        self._active = active
        self._rates = _euler_rates(tilt_y, spin)
        error = np.empty(len(active))
        error[:3] = rotation.T.dot(offset)
        error[3:] = [excesses[index - 3] for index in active[3:]]
        return (math.hypot(*offset.tolist()), math.hypot(*excesses), error)

    def rows(self, jacobian: FloatArray) -> FloatArray:
        """The rows of the Newton system from the tool's ``LOCAL`` Jacobian (6, n), for the
        rows kept at the latest :meth:`measure`."""
        angles = self._rates.dot(jacobian[3:])
        return np.concatenate([jacobian[:3], angles[[index - 3 for index in self._active[3:]]]])

    def nearest_match(self, tool_in_target: pin.SE3) -> pin.SE3:
        """The pose in the target's axes nearest to the tool that matches: its tilt within
        the windows, its spin (when free)."""
        tilt_x, tilt_y, spin = _euler_xyz(tool_in_target.rotation)
        about_x, about_y = self.windows
        rotation = (pin.utils.rotate("x", tilt_x - _excess(tilt_x, about_x))
                    @ pin.utils.rotate("y", tilt_y - _excess(tilt_y, about_y))
                    @ pin.utils.rotate("z", spin if self.free_spin else 0.0))
        return pin.SE3(rotation, np.zeros(3))

    def errors(self, rotations: FloatArray, translations: FloatArray
               ) -> tuple[FloatArray, FloatArray]:
        """Position errors (m) and orientation errors (rad), shape (N,), of many tool poses
        in their targets (``(N, 3, 3)`` rotations, ``(N, 3)`` translations)."""
        tilts = tilts_of(rotations)
        about_x, about_y = self.windows
        excess_x = np.abs(tilts[:, 0]) - np.minimum(np.abs(tilts[:, 0]), about_x)
        excess_y = np.abs(tilts[:, 1]) - np.minimum(np.abs(tilts[:, 1]), about_y)
        spins = (np.zeros(rotations.shape[0]) if self.free_spin
                 else np.arctan2(-rotations[:, 0, 1], rotations[:, 0, 0]))
        return (np.linalg.norm(translations, axis=1),
                np.sqrt(excess_x ** 2 + excess_y ** 2 + spins ** 2))


def tilts_of(rotations: FloatArray) -> FloatArray:
    """The tilt ``(a, b)`` (N, 2), radians, of tool orientations in their targets
    ``(N, 3, 3)``: the tool's z is ``Rx(a) Ry(b)`` the target's (see :class:`WindowMatch`)."""
    axes = rotations[:, :, 2]
    return np.stack([np.arctan2(-axes[:, 1], axes[:, 2]),
                     np.arctan2(axes[:, 0], np.hypot(axes[:, 1], axes[:, 2]))], axis=1)


def _euler_xyz(rotation: FloatArray) -> tuple[float, float, float]:
    """``(a, b, c)`` of ``rotation = Rx(a) Ry(b) Rz(c)``, radians (b within +-pi/2)."""
    (r00, r01, r02), (_, _, r12), (_, _, r22) = rotation.tolist()
    return (math.atan2(-r12, r22), math.atan2(r02, math.hypot(r12, r22)),
            math.atan2(-r01, r00))


def _euler_rates(tilt_y: float, spin: float) -> FloatArray:
    """The rates of ``(a, b, c)`` (3, 3) per angular velocity in the tool's axes: the inverse
    of ``[Rz(-c) Ry(-b) x, Rz(-c) y, z]`` (each angle's axis in the tool's axes), in closed
    form. At ``b = +-pi/2`` (the tool's z along the target's x, far past any window) the
    angles are singular: ``cos b`` is kept at least :data:`_SMALLEST_COSINE`."""
    cos_b = max(math.cos(tilt_y), _SMALLEST_COSINE)
    tan_b = math.sin(tilt_y) / cos_b
    cos_c, sin_c = math.cos(spin), math.sin(spin)
    return np.array([[cos_c / cos_b, -sin_c / cos_b, 0.0], [sin_c, cos_c, 0.0],
                     [-tan_b * cos_c, tan_b * sin_c, 1.0]])


_SMALLEST_COSINE = 1e-6
"""The smallest cosine of the tilt about y in the Euler rates (their singularity at 90°)."""


def _excess(angle: float, window: float) -> float:
    """How far ``angle`` lies past ``[-window, window]`` (signed; 0 within), radians."""
    if angle > window:
        return angle - window
    if angle < -window:
        return angle + window
    return 0.0


ToolMatch = PoseMatch | AxisMatch | WindowMatch
"""What a solve makes match between the tool and its target."""
