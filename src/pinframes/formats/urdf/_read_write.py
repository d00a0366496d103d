"""``read_urdf`` and ``write_urdf``: a robot file as a tree, and a whole tree as one URDF."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from typing import Any

import numpy as np

from ...tree import FrameTree
from ...values.joint import Joint, mimic_chain
from ...values.rotations import rpy_from_matrix
from .._atomic import atomic_write
from ._mount import URDF_METADATA_KEY, mount_robot
from ._parse import parse_urdf

__all__ = ["read_urdf", "write_urdf"]


def read_urdf(path: str | os.PathLike[str], *, strict: bool = False) -> FrameTree:
    """A robot alone: the tree's root is the robot's root link, named after the robot.

    ``strict`` refuses a mimic of a joint the file does not have (by default such a joint
    stays independent, with a :class:`~pinframes.urdf.BrokenMimicWarning`).
    """
    robot = parse_urdf(path, strict=strict)
    tree = FrameTree(root=robot.root_link, name=robot.name)
    mount_robot(tree, robot, None, None, "")
    return tree


def write_urdf(tree: FrameTree, path: str | os.PathLike[str], time: Any = None) -> None:
    """Write the whole tree as one URDF, atomically.

    Every frame is a link. Robot joints keep their type, axis, limits and mimic; static
    frames are fixed joints; moving frames are fixed joints frozen at ``time`` (default:
    their first keyframe; ``time`` follows the rules of :meth:`FrameTree.pose`). Link
    contents (visuals, inertials, ``package://`` URIs) and unread joint elements are
    written back as they were read.
    """
    robot = ET.Element("robot", name=tree.name or tree.root)
    for kept in tree.metadata.get(URDF_METADATA_KEY, {}).values():
        for text in kept.get("extra_xml", ()):
            robot.append(ET.fromstring(text))
    used_joint_names = {name for name in tree.joints}
    for frame in tree.frames:
        robot.append(_link(tree, frame))
        if frame != tree.root:
            robot.append(_joint(tree, frame, time, used_joint_names))
    ET.indent(robot, "  ")
    text = ET.tostring(robot, encoding="unicode", xml_declaration=False)
    with atomic_write(path, "w") as handle:
        handle.write('<?xml version="1.0" encoding="utf-8"?>\n' + text + "\n")


def _link(tree: FrameTree, frame: str) -> ET.Element:
    link = ET.Element("link", name=frame)
    kept = tree.frame_metadata(frame).get(URDF_METADATA_KEY, {})
    for text in kept.get("link_xml", ()):
        link.append(ET.fromstring(text))
    return link


def _joint(tree: FrameTree, frame: str, time: Any, used: set[str]) -> ET.Element:
    parent = tree.parent(frame)
    driven = tree.joint_of(frame)
    kept = tree.frame_metadata(frame).get(URDF_METADATA_KEY, {}).get("joint", {})
    if driven is not None:
        name, joint_type = driven.name, driven.kind
    else:
        joint_type = kept.get("type", "fixed")
        name = kept.get("name") or _free_name(f"{parent}_to_{frame}", used)
    joint = ET.Element("joint", name=name, type=joint_type)
    ET.SubElement(joint, "parent", link=parent)
    ET.SubElement(joint, "child", link=frame)
    translation, rotation = _origin(tree, frame, parent, time)
    ET.SubElement(joint, "origin", xyz=_numbers(translation),
                  rpy=_numbers(rpy_from_matrix(rotation)))
    if driven is not None:
        _driven_elements(joint, driven, tree.joints)
    elif joint_type == "planar":
        ET.SubElement(joint, "axis", xyz=_numbers(kept.get("axis", (0.0, 0.0, 1.0))))
    for text in kept.get("extra_xml", ()):
        joint.append(ET.fromstring(text))
    return joint


def _origin(tree: FrameTree, frame: str, parent: str, time: Any
            ) -> tuple[np.ndarray, np.ndarray]:
    local = tree.local_pose(frame)
    if not local.is_time_dependent:
        return local.translation, local.rotation
    if time is None:
        return local.translation[0], local.rotation[0]
    frozen = tree.pose(frame, parent, times=[time])
    return frozen.translation[0], frozen.rotation[0]


def _driven_elements(element: ET.Element, joint: Joint, joints: dict[str, Joint]) -> None:
    ET.SubElement(element, "axis", xyz=_numbers(joint.axis))
    limits = {"lower": joint.lower, "upper": joint.upper, "effort": joint.effort,
              "velocity": joint.velocity}
    if joint.kind != "continuous":
        # URDF requires effort and velocity on the limits of revolute and prismatic joints.
        limits["effort"] = limits["effort"] or 0.0
        limits["velocity"] = limits["velocity"] or 0.0
    written = {key: repr(float(value)) for key, value in limits.items() if value is not None}
    if written:
        ET.SubElement(element, "limit", **written)
    if joint.mimic is not None:
        primary, multiplier, offset = _mimic_of_driven_joint(joint, joints)
        ET.SubElement(element, "mimic", joint=primary, multiplier=repr(multiplier),
                      offset=repr(offset))


def _mimic_of_driven_joint(joint: Joint, joints: dict[str, Joint]) -> tuple[str, float, float]:
    """The joint at the end of ``joint``'s mimic chain, and the multiplier and offset that
    give ``joint``'s value from it.

    URDF readers such as Pinocchio's refuse a mimic of a mimic, so a chain is written as one
    mimic of the driven joint: ``v2 = m2 (m1 v0 + o1) + o2 = (m2 m1) v0 + (m2 o1 + o2)``.
    """
    chain = mimic_chain(joint, joints)
    multiplier, offset = 1.0, 0.0
    for link in reversed(chain[:-1]):
        multiplier, offset = (link.mimic.multiplier * multiplier,
                              link.mimic.multiplier * offset + link.mimic.offset)
    return chain[-1].name, float(multiplier), float(offset)


def _free_name(wanted: str, used: set[str]) -> str:
    name, number = wanted, 1
    while name in used:
        number += 1
        name = f"{wanted}_{number}"
    used.add(name)
    return name


def _numbers(values) -> str:
    return " ".join(repr(float(v)) for v in values)
