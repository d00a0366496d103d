"""The moves of a program as it is written, before planning: one frozen record per move.

Targets are kept as the caller gave them (frame names, :class:`~pinframes.Pose` values,
joint values or an SRDF group state's name) and resolved when the program is planned, where
the program then stands.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..values.pose import Pose
from ..values.weave import Weave

__all__ = ["JointMove", "LinearMove", "Move", "WaitMove", "WeldMove"]


@dataclass(frozen=True)
class JointMove:
    """A point-to-point move in joint space: ``target`` is joint values by name (radians or
    metres), one value per program joint, an SRDF group state's name, or a frame / ``Pose``
    the tool is put on (inverse kinematics from where the program stands)."""

    name: str
    target: Any


@dataclass(frozen=True)
class LinearMove:
    """The tool's origin on the straight line to ``target`` (a frame or a ``Pose`` in the
    root), its orientation slerped, at ``speed`` m/s where the joints allow it."""

    name: str
    target: str | Pose
    speed: float


@dataclass(frozen=True)
class WeldMove:
    """A seam welded: to the approach point (point to point), approach (linear), the seam
    (the target frame's own times, or ``speed`` m/s along it), retract (linear).

    ``seam`` is the frame that travels along the seam, ``torch`` the frame the tool must
    match on it (default: ``seam``); ``approach`` and ``retract`` are metres back along the
    torch target's -z from the seam's start and end, run at ``approach_speed`` m/s."""

    name: str
    seam: str
    torch: str | None
    speed: float | None
    approach: float
    retract: float
    approach_speed: float
    weave: Weave | None
    tilt: tuple[float, float] | None
    free_axis: str | None


@dataclass(frozen=True)
class WaitMove:
    """The joints held for ``seconds``."""

    name: str
    seconds: float


Move = JointMove | LinearMove | WeldMove | WaitMove
"""Any move of a program."""
