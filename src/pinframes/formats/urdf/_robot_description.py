"""A robot as a URDF describes it (:class:`RobotDescription`), before it is mounted on a tree."""

from __future__ import annotations

from dataclasses import dataclass, field

from ...values.geometry import FrameGeometry
from ...values.pose import Pose
from ...values.robot_semantics import RobotSemantics

__all__ = ["JointDescription", "RobotDescription"]


@dataclass(frozen=True)
class JointDescription:
    """One ``<joint>`` of a URDF, names not yet prefixed.

    ``origin`` is the child link's pose in the parent link at joint value 0; ``extra_xml``
    keeps the elements pinframes does not interpret (``<dynamics>``, ``<calibration>``,
    ``<safety_controller>``) as written, for export.
    """

    name: str
    type: str
    parent: str
    child: str
    origin: Pose
    axis: tuple[float, float, float]
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    mimic: tuple[str, float, float] | None = None
    extra_xml: tuple[str, ...] = ()


@dataclass(frozen=True)
class RobotDescription:
    """A parsed URDF: its links (with their XML kept as written) and joints, root first,
    the collision and visual geometry of every link, and what its SRDF says (None: no
    SRDF given)."""

    name: str
    source: str
    root_link: str
    links: dict[str, tuple[str, ...]]
    joints: tuple[JointDescription, ...]
    extra_xml: tuple[str, ...] = field(default=())
    geometry: dict[str, FrameGeometry] = field(default_factory=dict)
    semantics: RobotSemantics | None = None
