"""``read_urdf`` and ``write_urdf``: a robot file as a tree, and a whole tree as one URDF."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import PinframesError, UnsupportedFeatureError
from ...kinematics import Snapshot
from ...tree import FrameTree
from ...values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry
from ...values.joint import Joint, mimic_drive
from ...values.rotations import rpy_from_matrix
from .._snapshot import moving_parts, one_instant
from .._writable import check_joint_names, check_writable_tree, refuse_attached_data
from ..atomic import atomic_write
from ..joint_trajectory import joint_trajectory_csv
from ..limits import Limits
from ._geometry import shape_elements
from ._mount import URDF_METADATA_KEY, mount_robot
from ._parse import parse_urdf

__all__ = ["joint_state_path", "read_robot", "robot_links", "robot_urdf", "shapes_urdf",
           "write_urdf"]


def read_robot(path: str | os.PathLike[str], *, strict: bool = False,
               limits: Limits | None = None,
               package_dirs: Iterable[str | os.PathLike[str]] = (),
               xacro_args: Mapping[str, Any] | None = None,
               srdf: str | os.PathLike[str] | None = None,
               xacro: bool | None = None) -> FrameTree:
    """A robot file alone: the tree's root is the robot's root link, named after the robot,
    every joint at its rest value (:func:`pinframes.read_urdf` adds the joint values written
    beside the file).

    ``strict`` refuses a mimic of a joint the file does not have (by default such a joint
    stays independent, with a :class:`~pinframes.BrokenMimicWarning`). ``limits``
    (:class:`pinframes.Limits`; None: the defaults) bounds the XML elements
    (``max_xml_elements``) and their nesting (``max_depth``); a ``<!DOCTYPE>`` is refused.
    ``package_dirs``, ``xacro_args``, ``srdf`` and ``xacro`` as for :func:`parse_urdf`.
    """
    robot = parse_urdf(path, strict=strict, limits=limits, package_dirs=package_dirs,
                       xacro_args=xacro_args, srdf=srdf, xacro=xacro)
    tree = FrameTree(root=robot.root_link, name=robot.name)
    mount_robot(tree, robot, None, None, "")
    return tree


def write_urdf(tree: FrameTree, path: str | os.PathLike[str], time: Any = None, *,
               freeze_joints: bool = False) -> None:
    """Write the whole tree as one URDF, atomically: the tree at one time.

    Every frame is a link; static frames are fixed joints. A URDF holds one pose per frame:
    with ``time`` (the instant of :meth:`FrameTree.snapshot`), moving frames become fixed
    joints at their pose then; without it, a tree in which something moves is an
    :class:`~pinframes.errors.UnsupportedFeatureError` naming what moves.

    Robot joints keep their type, axis, limits and mimic, and their values at ``time`` go
    beside the file, to :func:`joint_state_path` (one row of a joint trajectory CSV:
    ``read_joint_trajectory`` reads it back), whenever a joint is driven. With
    ``freeze_joints`` every robot joint becomes a fixed joint at its value then instead,
    and no joint-state file is written. Link contents (visuals, inertials, ``package://``
    URIs) and unread joint elements are written back as they were read; a frame that is no
    URDF link gets the shapes ``add_geometry`` gave it as ``<collision>`` and ``<visual>``
    elements (shapes added to a URDF link are not written). Data attached to
    frames cannot go into a URDF: such a tree is an ``UnsupportedFeatureError`` naming it.
    """
    check_writable_tree(tree, path)
    refuse_attached_data(tree, path, "a URDF")
    instant = one_instant(tree, time, path, "URDF")
    robot = ET.Element("robot", name=tree.name or tree.root)
    written: set[str] = set()
    for kept in tree.metadata.get(URDF_METADATA_KEY, {}).values():
        for text in kept.get("extra_xml", ()):
            if text not in written:  # robots sharing a material define it once
                written.add(text)
                robot.append(ET.fromstring(text))
    used_joint_names = {name for name in tree.joints}
    for frame in tree.frames:
        robot.append(_link(tree, frame))
        if frame != tree.root:
            robot.append(_joint(tree, frame, instant, freeze_joints, used_joint_names))
    if not freeze_joints and moving_parts(tree)[1]:
        _write_joint_state(tree, instant, path)
    with atomic_write(path, "w") as handle:
        handle.write(_xml_text(robot))


def robot_links(tree: FrameTree, root_link: str) -> list[str]:
    """The frames of the robot mounted with the root link ``root_link`` (its URDF links as
    the tree names them), parents first."""
    return [frame for frame in tree.frames
            if tree.frame_metadata(frame).get(URDF_METADATA_KEY, {}).get("robot") == root_link]


def robot_urdf(tree: FrameTree, root_link: str) -> str:
    """The URDF text of one robot of ``tree``, as the tree holds it: the links of
    :func:`robot_links` under the tree's names (prefix included), their joints with their
    names, types, axes, limits and mimics, and what its file held besides (materials, link
    contents). Joint values are not part of it. A text has no folder: mesh names relative
    to the robot's file become absolute ``file://`` URIs (``package://`` names stay). A link
    that moves in its parent without a joint is an
    :class:`~pinframes.errors.UnsupportedFeatureError` (a URDF cannot hold it).
    """
    kept = tree.metadata.get(URDF_METADATA_KEY, {}).get(root_link, {})
    robot = ET.Element("robot", name=kept.get("name") or root_link)
    for text in kept.get("extra_xml", ()):
        robot.append(ET.fromstring(text))
    used = set(tree.joints)
    at_rest = Snapshot(None, {})
    for frame in robot_links(tree, root_link):
        link = _link(tree, frame)
        _absolute_mesh_names(link, tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY))
        robot.append(link)
        if frame == root_link:
            continue
        if tree.is_moving(frame):
            raise UnsupportedFeatureError(
                f"a link of the robot {kept.get('name') or root_link!r} moves in its parent "
                "without a joint, which a URDF cannot hold", frame=frame, field="pose")
        robot.append(_joint(tree, frame, at_rest, False, used))
    return _xml_text(robot)


def shapes_urdf(tree: FrameTree, frame: str) -> str:
    """The URDF text of one link: ``frame`` with the shapes recorded on it
    (``FrameTree.add_geometry``, a scene's geometry entries), as ``<collision>`` and
    ``<visual>`` elements; for a frame that is no URDF link."""
    robot = ET.Element("robot", name=frame)
    link = _link(tree, frame)
    _absolute_mesh_names(link, tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY))
    robot.append(link)
    return _xml_text(robot)


def _absolute_mesh_names(link: ET.Element, geometry: FrameGeometry | None) -> None:
    """Mesh names of ``link`` relative to its URDF file, as ``file://`` URIs."""
    source = None if geometry is None else geometry.urdf
    if not source or not os.path.isabs(source):  # a URDF given as text: nothing to resolve
        return
    for mesh in link.iter("mesh"):
        name = mesh.get("filename", "")
        if name and "://" not in name and not os.path.isabs(name):
            mesh.set("filename", (Path(source).parent / name).resolve().as_uri())


def _xml_text(robot: ET.Element) -> str:
    ET.indent(robot, "  ")
    text = ET.tostring(robot, encoding="unicode", xml_declaration=False)
    return '<?xml version="1.0" encoding="utf-8"?>\n' + text + "\n"


def joint_state_path(urdf_path: str | os.PathLike[str]) -> Path:
    """Where :func:`write_urdf` puts the joint values: ``cell.urdf`` -> ``cell.joints.csv``."""
    path = Path(urdf_path)
    return path.with_name(path.stem + ".joints.csv")


def _write_joint_state(tree: FrameTree, instant: Snapshot, urdf_path: str | os.PathLike[str]
                       ) -> None:
    """The actuated joints' values at the URDF's instant (mimic joints follow the URDF)."""
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    try:  # a CSV header: names that read back unchanged and run nothing in a spreadsheet
        if names:
            check_joint_names(names, csv_header=True)
    except PinframesError as exc:
        raise exc.located(file=joint_state_path(urdf_path)) from None
    when = instant.time
    time = (np.array([when], "datetime64[ns]") if isinstance(when, np.datetime64)
            else np.array([0.0 if when is None else when / np.timedelta64(1, "s")]))
    text = joint_trajectory_csv(
        time, np.array([[instant.joint_values[name] for name in names]]), names,
        comment=f"robot joint values (radians, metres) of {Path(urdf_path).name} at the time "
        "it was written; pinframes.read_joint_trajectory reads this file")
    with atomic_write(joint_state_path(urdf_path), "w") as handle:
        handle.write(text)


def _link(tree: FrameTree, frame: str) -> ET.Element:
    """A URDF link's elements as read; a frame that is no link gets its shapes (those of
    ``add_geometry``) as ``<collision>`` and ``<visual>`` elements."""
    link = ET.Element("link", name=frame)
    metadata = tree.frame_metadata(frame)
    kept = metadata.get(URDF_METADATA_KEY, {})
    for text in kept.get("link_xml", ()):
        link.append(ET.fromstring(text))
    recorded = metadata.get(GEOMETRY_METADATA_KEY)
    if "link_xml" not in kept and isinstance(recorded, FrameGeometry):
        link.extend(shape_elements(recorded, frame))
    return link


def _joint(tree: FrameTree, frame: str, instant: Snapshot, freeze: bool, used: set[str]
           ) -> ET.Element:
    parent = tree.parent(frame)
    assert parent is not None
    driven = tree.joint_of(frame)
    kept = tree.frame_metadata(frame).get(URDF_METADATA_KEY, {}).get("joint", {})
    if driven is not None:
        name, joint_type = driven.name, "fixed" if freeze else driven.kind
    else:
        joint_type = kept.get("type", "fixed")
        name = kept.get("name") or _free_name(f"{parent}_to_{frame}", used)
    joint = ET.Element("joint", name=name, type=joint_type)
    ET.SubElement(joint, "parent", link=parent)
    ET.SubElement(joint, "child", link=frame)
    rotation, translation = _origin(tree, frame, parent, instant, freeze)
    ET.SubElement(joint, "origin", xyz=_numbers(translation),
                  rpy=_numbers(rpy_from_matrix(rotation)))
    if driven is not None and not freeze:
        _driven_elements(joint, driven, tree.joints)
    elif joint_type == "planar":
        ET.SubElement(joint, "axis", xyz=_numbers(kept.get("axis", (0.0, 0.0, 1.0))))
    for text in kept.get("extra_xml", ()):
        joint.append(ET.fromstring(text))
    return joint


def _origin(tree: FrameTree, frame: str, parent: str, instant: Snapshot, freeze: bool
            ) -> tuple[np.ndarray, np.ndarray]:
    """The joint origin, ``(rotation, translation)``: the stored pose, or for a moving
    frame (and a frozen robot joint) its pose in the parent at the snapshot's instant."""
    local = tree.local_pose(frame)
    sampled = local.is_time_dependent or (freeze and tree.joint_of(frame) is not None)
    if not sampled:
        return local.rotation, local.translation
    if instant.time is None:  # nothing moves: a robot joint at its value (0 or its mimic's)
        frozen = tree.pose(frame, parent)
        return frozen.rotation, frozen.translation
    frozen = tree.pose(frame, parent, times=[instant.time])
    return frozen.rotation[0], frozen.translation[0]


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
        ET.SubElement(element, "limit", written)
    if joint.mimic is not None:  # URDF readers such as Pinocchio's refuse a mimic of a
        # mimic: a chain is written as one mimic of the actuated joint at its end
        drive = mimic_drive(joint, joints)
        ET.SubElement(element, "mimic", joint=drive.primary,
                      multiplier=repr(float(drive.multiplier)), offset=repr(float(drive.offset)))


def _free_name(wanted: str, used: set[str]) -> str:
    name, number = wanted, 1
    while name in used:
        number += 1
        name = f"{wanted}_{number}"
    used.add(name)
    return name


def _numbers(values) -> str:
    return " ".join(repr(float(v)) for v in values)
