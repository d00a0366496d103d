"""Placing a parsed robot into a frame tree: links become frames, joints stay joints."""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

from ...errors import ArgumentTypeError, FrameExistsError, FrameNotFoundError, near_misses
from ...tree.urdf_names import URDF_METADATA_KEY
from ...values.geometry import GEOMETRY_METADATA_KEY
from ...values.joint import Joint, Mimic
from ...values.pose import Pose
from ...values.robot_semantics import SEMANTICS_METADATA_KEY, LinkSemantics
from ..limits import Limits
from ._parse import parse_urdf
from ._robot_description import RobotDescription

if TYPE_CHECKING:
    from ...tree import FrameTree

__all__ = ["DRIVEN_JOINT_TYPES", "mount_robot", "mount_urdf"]

DRIVEN_JOINT_TYPES = ("revolute", "continuous", "prismatic")
"""URDF joint types that stay joints (the others become frames at their origin)."""


def mount_urdf(
    tree: FrameTree, urdf: str | os.PathLike[str], parent: str, pose: Pose | None, prefix: str,
    *, strict: bool = False, limits: Limits | None = None,
    package_dirs: Iterable[str | os.PathLike[str]] = (),
    xacro_args: Mapping[str, Any] | None = None, srdf: str | os.PathLike[str] | None = None,
    xacro: bool | None = None,
) -> list[str]:
    """Parse ``urdf`` (a path or the XML text) and mount it: ``FrameTree.attach_urdf``."""
    robot = parse_urdf(urdf, strict=strict, limits=limits, package_dirs=package_dirs,
                       xacro_args=xacro_args, srdf=srdf, xacro=xacro)
    return mount_robot(tree, robot, parent, pose, prefix)


def mount_robot(
    tree: FrameTree, robot: RobotDescription, parent: str | None, pose: Pose | None,
    prefix: str,
) -> list[str]:
    """Add every link of ``robot`` as frame ``prefix + link`` below ``parent``.

    With ``parent=None`` the root link must already be the tree's root (``read_urdf``).
    Everything is checked before the tree changes, and a failure midway is rolled back, so
    the tree is left as it was.
    """
    if not isinstance(prefix, str):
        raise ArgumentTypeError(f"expected a string, got {type(prefix).__name__}",
                                file=robot.source, field="prefix")
    root_frame = prefix + robot.root_link
    names = [root_frame] + [prefix + joint.child for joint in robot.joints]
    if parent is not None:
        if parent not in tree:
            raise FrameNotFoundError(f"parent frame {parent!r} is not in the tree"
                                     + near_misses(parent, tree.frames),
                                     file=robot.source, field="parent")
        clash = [name for name in names if name in tree]
        if clash:
            raise FrameExistsError(
                f"the tree already has frames {', '.join(clash[:5])}"
                + (" ..." if len(clash) > 5 else "") + "; mount with another prefix",
                file=robot.source, frame=clash[0])
    taken = [prefix + j.name for j in robot.joints if prefix + j.name in tree.joints]
    if taken:
        raise FrameExistsError(f"the tree already has joints {', '.join(taken[:5])}; mount "
                               "with another prefix", file=robot.source, frame=taken[0],
                               field="joint")
    added: list[str] = []
    try:
        if parent is not None:
            tree.add(root_frame, parent, pose)
            added.append(root_frame)
        _keep_link(tree, root_frame, robot, robot.root_link, None, prefix)
        for joint in robot.joints:
            child = prefix + joint.child
            if joint.type in DRIVEN_JOINT_TYPES:
                mimic = None if joint.mimic is None else Mimic(prefix + joint.mimic[0],
                                                               joint.mimic[1], joint.mimic[2])
                driven = Joint(prefix + joint.name, joint.type, joint.axis, joint.lower,
                               joint.upper, joint.velocity, joint.effort, mimic)
                tree.attach_joint(child, prefix + joint.parent, driven, joint.origin)
            else:
                tree.add(child, prefix + joint.parent, joint.origin)
            added.append(child)
            _keep_link(tree, child, robot, joint.child, joint, prefix)
    except Exception:
        if added:
            tree.remove(added[0], recursive=True)
        raise
    robots = tree.metadata.setdefault(URDF_METADATA_KEY, {})
    robots[root_frame] = {"name": robot.name, "prefix": prefix, "extra_xml": robot.extra_xml,
                          "source": _absolute(robot.source)}
    return names


def _absolute(source: str) -> str:
    """The URDF file as an absolute path (its folder resolves relative mesh names)."""
    return source if source == "<urdf string>" else os.path.abspath(source)


def _keep_link(tree: FrameTree, frame: str, robot: RobotDescription, link: str, joint,
               prefix: str) -> None:
    """Remember what export needs and pinframes does not interpret, and the link's geometry
    (for clearance queries and the 3-D page)."""
    kept: dict[str, Any] = {"robot": prefix + robot.root_link, "link": link,
                            "link_xml": robot.links[link]}
    if joint is not None:
        kept["joint"] = {"name": prefix + joint.name, "type": joint.type,
                         "extra_xml": joint.extra_xml, "axis": joint.axis}
    metadata = tree.frame_metadata(frame)
    metadata[URDF_METADATA_KEY] = kept
    metadata[GEOMETRY_METADATA_KEY] = robot.geometry[link]
    if robot.semantics is not None:
        metadata[SEMANTICS_METADATA_KEY] = LinkSemantics(link, robot.semantics)
