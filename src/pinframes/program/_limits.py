"""The program's joints and their motion limits: velocities from the URDF (or ``limits=``),
accelerations and jerks from ``limits=`` only.

``limits=`` maps joint names to records with ``velocity``, ``acceleration`` and ``jerk``
(what :func:`pinframes.read_joint_limits` reads from a MoveIt ``joint_limits.yaml``), or to
mappings with those keys; a name is the tree's (``robot/joint_1``) or the URDF's
(``joint_1``, the robot's prefix left off). A value given replaces the URDF's velocity, as
MoveIt's does. A joint without an acceleration limit is an error naming it: no default is
invented.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from typing import Any

import numpy as np

from ..errors import ArgumentTypeError, InvalidDataError, JointError
from ..kinematics.timing import MotionLimits

__all__ = ["LIMIT_FIELDS", "motion_limits", "named_joint_values", "program_joint"]

LIMIT_FIELDS = ("velocity", "acceleration", "jerk")
"""The fields of one joint's limits: per second, per second squared and per second cubed."""


def motion_limits(joint_names: tuple[str, ...], urdf_velocities: np.ndarray,
                  limits: Mapping[str, Any] | None) -> MotionLimits:
    """The :class:`MotionLimits` of ``joint_names`` (radians or metres per s, s^2, s^3):
    ``urdf_velocities`` (inf where the URDF gives none) overridden by ``limits``."""
    given = _by_joint(joint_names, limits or {})
    velocity = np.array(urdf_velocities, dtype=float)
    acceleration = np.full(len(joint_names), np.nan)
    jerk = np.full(len(joint_names), np.inf)
    for column, name in enumerate(joint_names):
        record = given.get(name, {})
        if record.get("velocity") is not None:
            velocity[column] = record["velocity"]
        if record.get("acceleration") is not None:
            acceleration[column] = record["acceleration"]
        if record.get("jerk") is not None:
            jerk[column] = record["jerk"]
        if not np.isfinite(velocity[column]):
            raise JointError("has no velocity limit (none in the URDF, none in limits=)",
                             joint=name, field="velocity")
        if not np.isfinite(acceleration[column]):
            raise JointError("has no acceleration limit: give one in limits= (joint name to "
                             "velocity, acceleration, jerk) or read a MoveIt joint_limits.yaml "
                             "with pinframes.read_joint_limits", joint=name,
                             field="acceleration")
    return MotionLimits(velocity=velocity, acceleration=acceleration,
                        jerk=jerk if np.isfinite(jerk).all() else None)


def _by_joint(joint_names: tuple[str, ...], limits: Mapping[str, Any]
              ) -> dict[str, dict[str, float | None]]:
    """``limits`` by the program's joint names, each a dict of the three fields."""
    if not isinstance(limits, Mapping):
        raise ArgumentTypeError("expected a mapping of joint names to limits, got "
                                f"{type(limits).__name__}", field="limits")
    found: dict[str, dict[str, float | None]] = {}
    for key, record in limits.items():
        name = program_joint(str(key), joint_names)
        if name is None:
            continue  # limits of other joints (a MoveIt file lists every joint of the robot)
        found[name] = {field: _limit(record, field, name) for field in LIMIT_FIELDS}
    return found


def program_joint(key: str, joint_names: tuple[str, ...]) -> str | None:
    """The program joint ``key`` names: itself, or the one whose name it ends after a
    prefix (``joint_1`` for ``robot/joint_1``); None when none or several."""
    if key in joint_names:
        return key
    matches = [name for name in joint_names
               if name.endswith(key) and len(name) > len(key)
               and not name[-len(key) - 1].isalnum()]
    return matches[0] if len(matches) == 1 else None


def _limit(record: Any, field: str, joint: str) -> float | None:
    value = record.get(field) if isinstance(record, Mapping) else getattr(record, field, None)
    if value is None:
        return None
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, bool) or not number > 0 or math.isnan(number):
        raise JointError(f"expected a positive number, got {value!r}", joint=joint,
                         field=f"limits.{field}")
    return number


def named_joint_values(values: Mapping[Any, Any], base: np.ndarray,
                       joint_names: tuple[str, ...], tree_joints: Collection[str],
                       field: str) -> np.ndarray:
    """``base`` (one value per program joint) with the joints ``values`` names (tree or
    URDF names) set; joints of the tree the program does not move are left out (a group
    state names them), other names are a :class:`JointError` naming them."""
    result = np.array(base, dtype=float)
    for key, value in values.items():
        name = program_joint(str(key), joint_names)
        if name is None:
            if key in tree_joints:
                continue
            raise JointError(f"is not a joint of the program (its joints: "
                             f"{', '.join(joint_names)})", joint=str(key), field=field)
        try:
            result[joint_names.index(name)] = float(value)
        except (TypeError, ValueError):
            raise InvalidDataError(f"expected a number, got {value!r}", joint=name,
                                   field=field) from None
    return result
