"""Which closed form a 6-axis arm has, read from its joints' axes: the ortho-parallel arm with
a spherical wrist (OPW: ABB, KUKA, FANUC, Yaskawa...) or the UR-type arm (Universal Robots
and the cobots built like them).

The arm is described by its six revolute axes at its zero configuration (every solved joint
at 0), in the axes of the tool at that configuration: a unit direction and a point per axis
(the screw a joint turns about), in the order of the chain from the base out. Both families
have axis 1 at right angles to axis 2 and axes 2 and 3 parallel; an OPW arm's axes 4, 5 and 6
meet in one point (the wrist centre) with 5 at right angles to 4 and to 6; a UR-type arm's
axis 4 is parallel to 2 and 3, axis 5 at right angles to it, and axis 6 meets axis 5 at right
angles. Each condition holds to :data:`SHAPE_TOLERANCE` (metres or radians), else the arm is
not recognised and the error names the joints and the first condition that fails per family.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ...errors import JointError
from ._subproblems import rotated

__all__ = ["FAMILIES", "SHAPE_TOLERANCE", "ArmShape", "OpwParameters", "recognise_arm"]

FloatArray = NDArray[np.float64]

SHAPE_TOLERANCE = 1e-9
"""Metres or radians by which an axis may miss a condition of its family."""

FAMILIES = {"opw": "an OPW arm (ortho-parallel base, spherical wrist)",
            "ur": "a UR-type arm (three parallel axes, offset wrist)"}
"""The families, by the name :attr:`ArmShape.family` gives them."""


@dataclass(frozen=True)
class ArmShape:
    """A recognised arm: its axes at the zero configuration, in the tool's axes there.

    Attributes
    ----------
    family : {"opw", "ur"}
        See :data:`FAMILIES`.
    joint_names : tuple of str
        The six joints from the base out.
    axes, points : ndarray, shape (6, 3)
        Per joint, the unit direction its positive value turns about and a point of its
        axis (metres), in the tool's axes at the zero configuration.
    scales : ndarray, shape (6,)
        Radians turned about the axis per radian of the joint's value (1, or a mimic
        multiplier's size).
    wrist_point : ndarray, shape (3,)
        The wrist centre (OPW), or where axes 5 and 6 meet (UR-type), at zero.
    carried_point : ndarray, shape (3,)
        The point axes 2 and 3 carry into place: the wrist centre (OPW), a point of axis 4
        (UR-type).
    forward : ndarray, shape (3,)
        The unit direction across axes 1 and 2 toward which the arm reaches at zero (the
        wrist point's side of axis 1; the shoulder offset's where the wrist point is on it).
    upward : ndarray, shape (3,)
        Axis 1's unit direction that is up: along the z axis of the frame joint 1 turns in
        (its parent link's, as the joint's origin places it).
    """

    family: str
    joint_names: tuple[str, ...]
    axes: FloatArray
    points: FloatArray
    scales: FloatArray
    wrist_point: FloatArray
    carried_point: FloatArray
    forward: FloatArray
    upward: FloatArray

    @property
    def parallel(self) -> FloatArray:
        """The direction of axis 2 (axis 3, and a UR-type arm's axis 4, are parallel to it)."""
        return self.axes[1]

    @cached_property
    def front_sign(self) -> float:
        """+1 where the shoulder angle ``g + h`` of :func:`._subproblems.two_angles` puts the
        wrist point in front of axis 1 (:attr:`forward`), else -1."""
        across = np.cross(self.axes[0], self.parallel)
        return 1.0 if float(np.dot(across, self.forward)) < 0.0 else -1.0

    @cached_property
    def elbow(self) -> tuple[float, float]:
        """``(stretched, up_sign)``: the angle (radians, about axis 3) at which the carried
        point lies furthest from axis 2 (the arm stretched), and the sign of
        ``sin(angle - stretched)`` that puts the elbow above the line from the shoulder
        to the carried point while the arm reaches forward."""
        offset, shoulder_to_elbow = self._planar_arms()
        axis = self.axes[2]
        stretched = math.atan2(float(np.dot(shoulder_to_elbow, np.cross(axis, offset))),
                               float(np.dot(shoulder_to_elbow, offset)))
        above = np.cross(self.forward, self.upward)  # across the arm, forward x up
        quarter = rotated(axis, np.array(stretched + math.pi / 2), offset)
        sign = float(np.dot(np.cross(quarter + shoulder_to_elbow, shoulder_to_elbow), above))
        return stretched, (1.0 if sign > 0.0 else -1.0)

    @cached_property
    def wrist_straight(self) -> float:
        """The angle (radians, about axis 5) at which the wrist is straight: axis 6 along
        axis 4 (OPW), or along axes 2 to 4 (UR-type)."""
        reference = self.axes[3] if self.family == "opw" else self.parallel
        axis5, axis6 = self.axes[4], self.axes[5]
        return math.atan2(float(np.dot(reference, np.cross(axis5, axis6))),
                          float(np.dot(reference, axis6)))

    def _planar_arms(self) -> tuple[FloatArray, FloatArray]:
        """Across the parallel axes: from axis 3 to the carried point, from axis 2 to 3."""
        normal = self.parallel
        offset = self.carried_point - self.points[2]
        between = self.points[2] - self.points[1]
        return (offset - normal * np.dot(offset, normal),
                between - normal * np.dot(between, normal))

    def opw_parameters(self, base_rotation: FloatArray, base_origin: FloatArray
                       ) -> OpwParameters:
        """The OPW parameters of this arm in a base frame (its axes ``base_rotation``
        (3, 3) and origin ``base_origin`` (3,), in the tool's axes at zero) whose z lies
        along axis 1: origin on axis 1 below the base's, x :attr:`forward`."""
        if self.family != "opw":
            raise JointError("OPW parameters are those of an OPW arm; this is "
                             + FAMILIES[self.family], field="joints")
        z = base_rotation[:, 2]
        x = self.forward
        y = np.cross(z, x)
        origin = self.points[0] + self.axes[0] * np.dot(base_origin - self.points[0],
                                                         self.axes[0])
        shoulder = self.points[1] - origin
        offset, upper = self._planar_arms()
        along = self.axes[3] * (1.0 if np.dot(offset, self.axes[3]) >= 0.0 else -1.0)
        c3 = float(np.dot(offset, along))
        tool_axis = self.axes[5] * (1.0 if np.dot(-self.wrist_point, self.axes[5]) >= 0.0
                                    else -1.0)
        return OpwParameters(
            a1=float(np.dot(shoulder, x)), a2=float(np.dot(offset - c3 * along,
                                                           np.cross(y, along))),
            b=float(np.dot(self.wrist_point - origin, y)), c1=float(np.dot(shoulder, z)),
            c2=float(np.linalg.norm(upper)), c3=c3,
            c4=float(np.dot(-self.wrist_point, tool_axis)))


@dataclass(frozen=True)
class OpwParameters:
    """The seven lengths (metres) of an OPW arm, as opw_kinematics names them: ``a1`` the
    shoulder's offset from axis 1, ``a2`` the offset of axis 4 from axis 3, ``b`` the
    sideways offset of the wrist centre, ``c1`` the shoulder's height, ``c2`` and ``c3``
    the upper arm and forearm, ``c4`` the wrist centre to the flange."""

    a1: float
    a2: float
    b: float
    c1: float
    c2: float
    c3: float
    c4: float


def recognise_arm(names: Sequence[str], axes: FloatArray, points: FloatArray,
                  scales: FloatArray, up: FloatArray, frame: str | None = None) -> ArmShape:
    """The :class:`ArmShape` of six joints (``names`` from the base out, ``axes`` and
    ``points`` (6, 3) as :class:`ArmShape` holds them, ``scales`` (6,); ``up`` (3,) the z
    axis of the frame joint 1 turns in, in the same axes).

    Raises :class:`~pinframes.errors.JointError` (naming ``frame``, field ``joints``) when
    the joints fit neither family, with what breaks each.
    """
    names = tuple(names)
    if len(names) != 6:
        raise JointError(f"closed-form inverse kinematics is for six joints in a chain; got "
                         f"{len(names)} ({', '.join(names)})", frame=frame, field="joints")
    checks = _Checks(names, axes, points)
    failures = {}
    for family, conditions in (("opw", checks.opw), ("ur", checks.ur)):
        failure = next((message for message in conditions() if message), None)
        if failure is None:
            return _shape(family, names, axes, points, scales, up)
        failures[family] = failure
    raise JointError(
        f"joints {', '.join(names)} form neither {FAMILIES['opw']}: {failures['opw']}; nor "
        f"{FAMILIES['ur']}: {failures['ur']}", frame=frame, field="joints")


class _Checks:
    """The conditions of each family, each a message when it fails (else None)."""

    def __init__(self, names: tuple[str, ...], axes: FloatArray, points: FloatArray) -> None:
        self.names, self.axes, self.points = names, axes, points

    def _name(self, index: int) -> str:
        return f"joint {index + 1} ({self.names[index]})"

    def at_right_angles(self, first: int, second: int) -> str | None:
        off = math.asin(min(1.0, abs(float(np.dot(self.axes[first], self.axes[second])))))
        return None if off <= SHAPE_TOLERANCE else (
            f"{self._name(second)} axis is not at right angles to {self._name(first)} axis: "
            f"{off:.3g} rad off")

    def parallel(self, first: int, second: int) -> str | None:
        sine = float(np.linalg.norm(np.cross(self.axes[first], self.axes[second])))
        if sine > SHAPE_TOLERANCE:
            return (f"{self._name(second)} axis is not parallel to {self._name(first)} axis: "
                    f"{math.asin(min(1.0, sine)):.3g} rad apart")
        apart = _line_distance(self.axes[first], self.points[first], self.axes[second],
                               self.points[second])
        return None if apart > SHAPE_TOLERANCE else (
            f"{self._name(first)} and {self._name(second)} axes are one line")

    def meet(self, first: int, second: int) -> str | None:
        apart = _line_distance(self.axes[first], self.points[first], self.axes[second],
                               self.points[second])
        return None if apart <= SHAPE_TOLERANCE else (
            f"{self._name(first)} axis does not meet {self._name(second)} axis: {apart:.3g} m "
            "apart")

    def wrist_meets(self) -> str | None:
        centre = _meeting_point(self.axes[3], self.points[3], self.axes[4], self.points[4])
        apart = _point_distance(self.axes[5], self.points[5], centre)
        return None if apart <= SHAPE_TOLERANCE else (
            f"{self._name(5)} axis misses the point where joint 4 and joint 5 axes meet: "
            f"{apart:.3g} m apart")

    def opw(self) -> list[str | None]:
        return [self.at_right_angles(0, 1), self.parallel(1, 2), self.meet(3, 4),
                self.meet(4, 5), self.wrist_meets(), self.at_right_angles(3, 4),
                self.at_right_angles(4, 5)]

    def ur(self) -> list[str | None]:
        return [self.at_right_angles(0, 1), self.parallel(1, 2), self.parallel(2, 3),
                self.at_right_angles(3, 4), self.meet(4, 5), self.at_right_angles(4, 5)]


def _line_distance(axis_a: FloatArray, point_a: FloatArray, axis_b: FloatArray,
                   point_b: FloatArray) -> float:
    """Metres between two lines (unit directions, a point each)."""
    across = np.cross(axis_a, axis_b)
    size = float(np.linalg.norm(across))
    if size <= SHAPE_TOLERANCE:
        return _point_distance(axis_a, point_a, point_b)
    return abs(float(np.dot(point_b - point_a, across))) / size


def _point_distance(axis: FloatArray, point: FloatArray, other: FloatArray) -> float:
    """Metres from ``other`` to the line through ``point`` along ``axis``."""
    return float(np.linalg.norm(np.cross(other - point, axis)))


def _meeting_point(axis_a: FloatArray, point_a: FloatArray, axis_b: FloatArray,
                   point_b: FloatArray) -> FloatArray:
    """The point midway between the closest points of two lines that are not parallel."""
    between = point_b - point_a
    cosine = float(np.dot(axis_a, axis_b))
    denominator = 1.0 - cosine * cosine
    along_a = (np.dot(between, axis_a) - cosine * np.dot(between, axis_b)) / denominator
    along_b = (cosine * np.dot(between, axis_a) - np.dot(between, axis_b)) / denominator
    return 0.5 * (point_a + along_a * axis_a + point_b + along_b * axis_b)


def _shape(family: str, names: tuple[str, ...], axes: FloatArray, points: FloatArray,
           scales: FloatArray, up: FloatArray) -> ArmShape:
    wrist = (_meeting_point(axes[3], points[3], axes[4], points[4]) if family == "opw"
             else _meeting_point(axes[4], points[4], axes[5], points[5]))
    carried = wrist if family == "opw" else points[3]
    across = np.cross(axes[1], axes[0])
    across /= np.linalg.norm(across)
    reach = float(np.dot(wrist - points[0], across))
    if abs(reach) <= 1e-6:
        reach = float(np.dot(points[1] - points[0], across))
    forward = across if reach >= 0.0 else -across
    upward = axes[0] if float(np.dot(up, axes[0])) >= 0.0 else -axes[0]
    return ArmShape(family, names, axes.copy(), points.copy(), scales.copy(), wrist, carried,
                    forward, upward)

