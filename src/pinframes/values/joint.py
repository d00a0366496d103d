"""`Joint`: a robot joint that moves a child link relative to its parent link.

The pose of the child link in the parent link is ``origin @ motion(q)``, where ``origin`` is
the URDF ``<origin>`` and ``motion`` rotates about (revolute, continuous) or slides along
(prismatic) the unit ``axis``, written in the joint frame. Angles in radians, lengths in
metres.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ..errors import JointError
from ._trigonometry import cos_sin
from .se3 import rotated_vector, rotation_product, turned

__all__ = ["JOINT_KINDS", "Drive", "Joint", "Mimic", "mimic_chain", "mimic_drive", "mimic_drives"]

JOINT_KINDS = ("revolute", "continuous", "prismatic")
"""Joint kinds driven by one value each."""

MIMIC_BOUND = 1e6
"""Largest mimic multiplier and offset: a coupling beyond it is no mechanism, and its
products overflow to infinite or NaN poses long before floats run out."""


@dataclass(frozen=True)
class Mimic:
    """A joint whose value is ``multiplier * value(joint) + offset``."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        for field in ("multiplier", "offset"):
            value = getattr(self, field)
            try:
                number = float(value) if not isinstance(value, (str, bytes)) else None
            except (TypeError, ValueError, OverflowError):
                number = None
            if number is None or not abs(number) <= MIMIC_BOUND:
                raise JointError(f"a mimic {field} must be a number of magnitude at most "
                                 f"{MIMIC_BOUND:g}, got {value!r} (mimic of joint {self.joint!r})",
                                 field=f"mimic.{field}")
            object.__setattr__(self, field, number)


@dataclass(frozen=True)
class Joint:
    """A one-degree-of-freedom robot joint.

    Attributes
    ----------
    name : str
        Joint name as held by the tree (with the robot's prefix).
    kind : str
        ``"revolute"``, ``"continuous"`` or ``"prismatic"``.
    axis : tuple of float
        Unit axis in the joint frame.
    lower, upper : float or None
        Position limits, radians or metres (None: unlimited).
    velocity, effort : float or None
        Limits as written in the URDF (kept for export).
    mimic : Mimic or None
        Set when this joint follows another one.
    """

    name: str
    kind: str
    axis: tuple[float, float, float] = (1.0, 0.0, 0.0)
    lower: float | None = None
    upper: float | None = None
    velocity: float | None = None
    effort: float | None = None
    mimic: Mimic | None = None

    def __post_init__(self) -> None:
        if self.kind not in JOINT_KINDS:
            raise JointError(f"unknown joint kind {self.kind!r}; expected one of {JOINT_KINDS}",
                             joint=self.name, field="type")
        try:
            axis = np.asarray(self.axis, dtype=float)
        except (TypeError, ValueError):
            axis = np.zeros(0)
        norm = float(np.linalg.norm(axis))
        if axis.shape != (3,) or not np.isfinite(norm) or norm < 1e-9:
            raise JointError(f"axis must be a non-zero 3-vector, got {self.axis!r}",
                             joint=self.name, field="axis")
        object.__setattr__(self, "axis", tuple(float(v) for v in axis / norm))
        if (self.kind != "continuous" and self.lower is not None and self.upper is not None
                and self.lower > self.upper):
            raise JointError(f"the lower limit {self.lower:g} is above the upper limit "
                             f"{self.upper:g}", joint=self.name, field="limit")

    @property
    def rest_value(self) -> float:
        """The value the joint holds while it has no samples, radians or metres: 0, or the
        limit nearest to 0 when its limits exclude 0."""
        value = 0.0 if self.lower is None else max(0.0, self.lower)
        return value if self.upper is None else min(value, self.upper)

    @property
    def is_actuated(self) -> bool:
        """True for joints driven by their own value (not mimic joints)."""
        return self.mimic is None

    def moved(
        self, frame: tuple[NDArray[np.float64], NDArray[np.float64]],
        values: NDArray[np.float64] | float,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """``frame @ motion(values)``: the child link's frame from the joint frame ``frame``.

        ``frame`` is static (``(3, 3)``, ``(3,)``) or batched, samples last (``(3, 3, N)``,
        ``(3, N)``); ``values`` one float or ``(N,)``, radians or metres. A turn about an
        axis along x, y or z mixes two columns of the rotation (the joints of most robots);
        any other axis takes Rodrigues' formula ``R(q) = I + sin q K + (1 - cos q) K^2``
        (``K`` the cross-product matrix of the axis), two static products and three passes.
        """
        rotation, translation = frame
        if self.kind == "prismatic":
            slide = rotated_vector(rotation, np.asarray(self.axis))
            return rotation, _batched_sum(translation, slide, values)
        cosine, sine = cos_sin(values)
        aligned = self._signed_axis
        if aligned is not None:
            index, sign = aligned
            return turned(rotation, index, cosine, sign * sine), translation
        axis = self.axis
        cross = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]],
                          [-axis[1], axis[0], 0.0]])
        along_sine = rotation_product(rotation, cross)
        along_versine = rotation_product(rotation, cross @ cross)
        if rotation.ndim == 2 and np.ndim(values):
            rotation, along_sine, along_versine = (
                part[:, :, None] for part in (rotation, along_sine, along_versine))
        turned_rotation = along_sine * sine
        turned_rotation += along_versine * (1.0 - cosine)
        turned_rotation += rotation
        return turned_rotation, translation

    def pinocchio_joint_model(self) -> pin.JointModel:
        """The Pinocchio joint model of this joint (aligned axes get the specialised ones).

        A continuous joint about an unaligned axis becomes a revolute one, which moves the
        same: pin 4.1's Python bindings build ``JointModelRevoluteUnboundedUnaligned`` only
        about the x axis.
        """
        axis = np.asarray(self.axis)
        aligned = self._aligned_axis()
        if aligned is not None:
            prefix = {"revolute": "R", "continuous": "RUB", "prismatic": "P"}[self.kind]
            return getattr(pin, f"JointModel{prefix}{aligned}")()
        if self.kind == "prismatic":
            return pin.JointModelPrismaticUnaligned(axis)
        return pin.JointModelRevoluteUnaligned(axis)

    def configuration(self, values: NDArray[np.float64]) -> NDArray[np.float64]:
        """Pinocchio configuration entries ``(N, nq)`` of this joint for ``values``."""
        if self.kind == "continuous" and self._aligned_axis() is not None:
            return np.stack([np.cos(values), np.sin(values)], axis=1)
        return values[:, None]

    @cached_property
    def _signed_axis(self) -> tuple[int, float] | None:
        """``(index, sign)`` when the axis is exactly +-x, +-y or +-z (index 0, 1, 2), else
        None. Exactly: URDF axes such as ``0 -1 -4.37114e-08`` (romeo) turn 4e-8 off y."""
        index = int(np.argmax(np.abs(self.axis)))
        if sum(abs(value) for value in self.axis) == abs(self.axis[index]):
            return index, float(np.sign(self.axis[index]))
        return None

    def _aligned_axis(self) -> str | None:
        """``"X"``, ``"Y"`` or ``"Z"`` when the axis is that unit axis, else None."""
        signed = self._signed_axis
        return "XYZ"[signed[0]] if signed is not None and signed[1] > 0 else None


def _batched_sum(
    translation: NDArray[np.float64], direction: NDArray[np.float64],
    values: NDArray[np.float64] | float,
) -> NDArray[np.float64]:
    """``translation + direction * values`` for static or samples-last parts."""
    if np.ndim(values) and direction.ndim == 1:
        direction = direction[:, None]
    step = direction * values
    if translation.ndim < step.ndim:
        translation = translation[:, None]
    return translation + step


def mimic_chain(joint: Joint, joints: Mapping[str, Joint]) -> list[Joint]:
    """``joint``, the joint it mimics, and so on up to a joint that mimics none.

    Raises :class:`~pinframes.errors.JointError` when a joint in the chain mimics one that is
    not in ``joints`` (by name) or the chain closes on itself.
    """
    chain = [joint]
    seen = {joint.name}  # constant-time cycle test: a long chain costs its length, not its square
    while chain[-1].mimic is not None:
        target = chain[-1].mimic.joint
        if target not in joints:
            raise JointError(f"mimics joint {target!r}, which is not in the tree",
                             joint=chain[-1].name, field="mimic")
        if target in seen:
            names = [link.name for link in chain]
            raise JointError(f"mimic joints form a cycle: {' -> '.join([*names, target])}",
                             joint=chain[-1].name, field="mimic")
        chain.append(joints[target])
        seen.add(target)
    return chain


@dataclass(frozen=True)
class Drive:
    """How a joint follows the actuated joint that finally drives it through a chain of
    mimics: ``value = multiplier * value(primary) + offset`` (radians or metres)."""

    primary: str
    multiplier: float = 1.0
    offset: float = 0.0


def mimic_drive(joint: Joint, joints: Mapping[str, Joint]) -> Drive:
    """How ``joint`` follows the actuated joint at the end of its mimic chain: through
    ``v2 = m2 (m1 v0 + o1) + o2 = (m2 m1) v0 + (m2 o1 + o2)`` down the chain (itself,
    multiplier 1, offset 0, for a joint that mimics none).

    Raises :class:`~pinframes.errors.JointError` as :func:`mimic_chain` does.
    """
    chain = mimic_chain(joint, joints)
    multiplier, offset = 1.0, 0.0
    for link in reversed(chain[:-1]):  # from the primary out to the joint
        assert link.mimic is not None  # every joint but the chain's last mimics the next
        multiplier, offset = (link.mimic.multiplier * multiplier,
                              link.mimic.multiplier * offset + link.mimic.offset)
    return Drive(chain[-1].name, multiplier, offset)


def mimic_drives(joints: Mapping[str, Joint]) -> dict[str, Drive]:
    """Per joint of ``joints`` (by name), its :func:`mimic_drive`."""
    return {joint.name: mimic_drive(joint, joints) for joint in joints.values()}
