"""Reading URDF XML into a checked :class:`RobotDescription` (no tree is touched here)."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import BrokenMimicWarning, FileFormatError, GeometryWarning, warn_at_caller
from ...values.pose import Pose
from .._content import xml_root
from ..limits import Limits, current_limits, exceeded, reader_with_limits
from ..reading import InputFile, read_text
from ._bounded_xml import parse_bounded_xml
from ._geometry import link_geometry, named_colours, stray_geometry_origins
from ._numbers import numbers
from ._robot_description import JointDescription, RobotDescription
from ._srdf import looks_like_srdf, read_srdf
from ._xacro import expand_xacro, is_xacro, wants_expansion

__all__ = ["URDF_JOINT_TYPES", "is_urdf", "parse_urdf"]

URDF_JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
_DRIVEN_TYPES = ("revolute", "continuous", "prismatic")
_JOINT_FIELDS_READ = {"parent", "child", "origin", "axis", "limit", "mimic"}


def is_urdf(source: InputFile) -> bool:
    """Whether ``source`` is a URDF (the format's content test): XML whose root element is
    ``<robot>``."""
    return xml_root(source) == "robot"


@reader_with_limits
def parse_urdf(urdf: str | os.PathLike[str], *, strict: bool = False,
               limits: Limits | None = None,
               package_dirs: Iterable[str | os.PathLike[str]] = (),
               xacro_args: Mapping[str, Any] | None = None,
               srdf: str | os.PathLike[str] | None = None,
               xacro: bool | None = None) -> RobotDescription:
    """Parse a URDF file path or XML string and check that it describes one tree of links.

    A xacro file is expanded first (:func:`~pinframes.formats.urdf.expand_xacro`, with
    ``xacro_args`` and ``$(find PKG)`` looked up in ``package_dirs``) only when the caller
    asks, since the expansion runs the file's code: ``xacro=True``, or (``xacro=None``) a
    file whose name ends in ``.xacro``; other xacro content is a ``FileFormatError`` saying
    how to opt in (``xacro=False`` never expands). ``package_dirs`` are also kept with
    every link's geometry (absolute), for its meshes. ``srdf`` (a file) is read against the
    robot into :attr:`RobotDescription.semantics`; an SRDF shipped as xacro
    (``*.srdf.xacro``) is expanded as the URDF is, with the same ``xacro`` choice and
    ``xacro_args``.

    Raises :class:`~pinframes.errors.FileFormatError` naming the file (or ``<urdf string>``),
    the link or joint and the field for malformed XML, missing or duplicate names, unknown
    joint types, a link with two parents, several root links and mimic cycles. A mimic of a
    joint the file does not have gives one :class:`BrokenMimicWarning` per such joint, which
    then stays an independent joint (Pinocchio and urdfdom load such files too); with
    ``strict`` it is an error. Meshes are never opened; ``package://`` URIs stay as written.
    ``limits`` (:class:`pinframes.Limits`) bounds the XML elements and their nesting; a
    ``<!DOCTYPE>`` (and with it any entity definition) is refused.
    """
    text, source = _read_source(urdf)
    folders = tuple(os.path.abspath(os.fspath(folder)) for folder in package_dirs)
    macros_only = False
    if source == "<urdf string>" and is_xacro(text):
        raise FileFormatError("xacro text: give the xacro file's path, whose folder its "
                              "includes are relative to", file=source, field="xacro")
    srdf_text = None if srdf is None else read_text(srdf)
    srdf_expanded = srdf is not None and srdf_text is not None and wants_expansion(
        os.fspath(srdf), srdf_text, xacro)
    if wants_expansion(source, text, xacro):
        macros_only = "xacro:macro" in text
        text = expand_xacro(source, args=xacro_args, package_dirs=folders)
    elif xacro_args and not srdf_expanded:
        raise FileFormatError("xacro_args were given, but this is no xacro file",
                              file=source, field="xacro_args")
    root = parse_bounded_xml(text, source)
    if root.tag != "robot":
        raise FileFormatError(f"the root element is <{root.tag}>, expected <robot>",
                              file=source, field="robot")
    if looks_like_srdf(root):
        raise FileFormatError(
            "this is an SRDF (MoveIt's semantic description: groups, group states, disabled "
            "collision pairs), not a URDF: give it beside its URDF, as srdf= (Python), "
            "'srdf:' of a scene robot or --srdf (command line)", file=source, field="robot")
    name = root.get("name")
    if not name:
        name = Path(source).stem if source != "<urdf string>" else "robot"
        warn_at_caller(f"{source}: <robot> has no name; using {name!r}")
    try:
        links, joints, extra = _elements(root, source)
    except RecursionError:
        raise FileFormatError("XML elements nested too deeply to keep", file=source) from None
    if not links:
        hint = (": it defines xacro macros only; read the xacro file that calls them"
                if macros_only else "")
        raise FileFormatError(f"no <link>: a robot has at least one{hint}", file=source,
                              field="link")
    ordered, root_link = _check_tree(links, joints, source)
    ordered = _without_broken_mimics(ordered, source, strict)
    _check_mimics(ordered, source)
    colours = named_colours(root, source)
    geometry = {link: link_geometry(element, link, source, colours, folders)
                for link, element in _link_elements(root)}
    stray = stray_geometry_origins(root)
    if stray:
        warn_at_caller(f"{source}: an <origin> inside <geometry> is ignored, as urdfdom and "
                       f"Pinocchio ignore it (the shape's <origin> belongs beside its "
                       f"<geometry>): {', '.join(stray)}", GeometryWarning)
    robot = RobotDescription(name, source, root_link, links, tuple(ordered), tuple(extra),
                             geometry)
    if srdf is None:
        return robot
    if srdf_expanded:
        srdf_text = expand_xacro(srdf, args=xacro_args, package_dirs=folders)
    return replace(robot, semantics=read_srdf(srdf, robot, text=srdf_text))


def _link_elements(root: ET.Element) -> list[tuple[str, ET.Element]]:
    """Every ``<link>`` with its name (names checked by :func:`_elements`)."""
    return [(element.get("name", ""), element) for element in root.iterfind("link")]


def _elements(root: ET.Element, source: str
              ) -> tuple[dict[str, tuple[str, ...]], list[JointDescription], list[str]]:
    """The links (their inner XML as written), the joints and the other top-level XML."""
    links: dict[str, tuple[str, ...]] = {}
    joints: list[JointDescription] = []
    extra: list[str] = []
    for element in root:
        if element.tag == "link":
            link_name = _required(element, "name", source, None)
            if link_name in links:
                raise FileFormatError("duplicate link name", file=source, frame=link_name,
                                      field="name")
            links[link_name] = tuple(_xml(child) for child in element)
        elif element.tag == "joint":
            joints.append(_parse_joint(element, source))
        elif isinstance(element.tag, str):
            extra.append(_xml(element))
    return links, joints, extra


def _read_source(urdf: str | os.PathLike[str]) -> tuple[str, str]:
    if isinstance(urdf, str) and urdf.lstrip().startswith("<"):
        return urdf, "<urdf string>"
    return read_text(urdf), os.fspath(urdf)


def _parse_joint(element: ET.Element, source: str) -> JointDescription:
    name = _required(element, "name", source, None)
    joint_type = element.get("type")
    if joint_type not in URDF_JOINT_TYPES:
        raise FileFormatError(f"unknown joint type {joint_type!r}; expected one of "
                              f"{', '.join(URDF_JOINT_TYPES)}", file=source, joint=name,
                              field="type")
    parent = _child_attribute(element, "parent", "link", source, name)
    child = _child_attribute(element, "child", "link", source, name)
    origin = element.find("origin")
    xyz = _vector(origin, "xyz", source, name, "origin.xyz", (0.0, 0.0, 0.0))
    rpy = _vector(origin, "rpy", source, name, "origin.rpy", (0.0, 0.0, 0.0))
    axis = _vector(element.find("axis"), "xyz", source, name, "axis.xyz", (1.0, 0.0, 0.0))
    if joint_type in ("revolute", "continuous", "prismatic", "planar") and not np.any(axis):
        raise FileFormatError("the axis must not be zero", file=source, joint=name,
                              field="axis.xyz")
    limit = element.find("limit")
    bounds = {key: _number(limit, key, source, name) for key in
              ("lower", "upper", "effort", "velocity")}
    lower, upper = bounds["lower"], bounds["upper"]
    if (joint_type in ("revolute", "prismatic") and lower is not None and upper is not None
            and lower > upper):
        raise FileFormatError(f"the lower limit {lower:g} is above the upper limit {upper:g}",
                              file=source, joint=name, field="limit")
    mimic_element = element.find("mimic")
    mimic = None
    if mimic_element is not None:
        target = _required(mimic_element, "joint", source, name)
        multiplier = _number(mimic_element, "multiplier", source, name)
        offset = _number(mimic_element, "offset", source, name)
        mimic = (target, 1.0 if multiplier is None else multiplier,
                 0.0 if offset is None else offset)
    extra = tuple(_xml(child) for child in element if child.tag not in _JOINT_FIELDS_READ)
    return JointDescription(
        name=name, type=joint_type, parent=parent, child=child,
        origin=Pose.from_xyz_rpy(*xyz, *rpy), axis=(axis[0], axis[1], axis[2]), mimic=mimic,
        extra_xml=extra, **bounds)


def _check_tree(
    links: dict[str, tuple[str, ...]], joints: list[JointDescription], source: str
) -> tuple[list[JointDescription], str]:
    """Joints ordered from the root link outwards, and the root link."""
    by_child: dict[str, JointDescription] = {}
    names = set()
    for joint in joints:
        if joint.name in names:
            raise FileFormatError("duplicate joint name", file=source, joint=joint.name,
                                  field="name")
        names.add(joint.name)
        for role in ("parent", "child"):
            if getattr(joint, role) not in links:
                raise FileFormatError(f"{role} link {getattr(joint, role)!r} is not defined",
                                      file=source, joint=joint.name, field=f"{role}.link")
        if joint.child in by_child:
            raise FileFormatError(
                f"link {joint.child!r} has two parents (joints {by_child[joint.child].name!r} "
                f"and {joint.name!r})", file=source, joint=joint.name, field="child.link")
        by_child[joint.child] = joint
    roots = [link for link in links if link not in by_child]
    if len(roots) != 1:
        detail = ("no link without a parent: the joints form a cycle" if not roots
                  else f"several links without a parent: {', '.join(roots)}")
        raise FileFormatError(f"not one tree of links ({detail})", file=source, field="link")
    children: dict[str, list[JointDescription]] = {}
    for joint in joints:
        children.setdefault(joint.parent, []).append(joint)
    # Depth first from the root, children in document order (Pinocchio's joint order).
    ordered: list[JointDescription] = []
    stack = [iter(children.get(roots[0], []))]
    while stack:
        following = next(stack[-1], None)
        if following is None:
            stack.pop()
            continue
        ordered.append(following)
        stack.append(iter(children.get(following.child, [])))
    if len(ordered) != len(joints):
        cut_off = sorted({j.child for j in joints} - {j.child for j in ordered})
        raise FileFormatError(f"links {', '.join(cut_off)} form a cycle", file=source,
                              field="link")
    return ordered, roots[0]


def _without_broken_mimics(joints: list[JointDescription], source: str, strict: bool
                           ) -> list[JointDescription]:
    """``joints`` with the mimic dropped from those whose primary is not in the file."""
    names = {joint.name for joint in joints}
    kept = []
    for joint in joints:
        if joint.mimic is not None and joint.type in _DRIVEN_TYPES and joint.mimic[0] not in names:
            if strict:
                raise FileFormatError(f"mimics unknown joint {joint.mimic[0]!r}", file=source,
                                      joint=joint.name, field="mimic.joint")
            warn_at_caller(
                f"{source}: joint {joint.name!r} mimics joint {joint.mimic[0]!r}, which the "
                "file does not have; it is loaded as an independent joint (strict=True "
                "refuses the file)", BrokenMimicWarning)
            joint = replace(joint, mimic=None)
        kept.append(joint)
    return kept


def _check_mimics(joints: list[JointDescription], source: str) -> None:
    """Mimic targets exist, are driven joints, and no chain of mimics closes on itself.

    A mimic of a mimic is allowed (its value follows the chain to a driven joint), up to
    ``max_depth`` joints in a chain (each query follows the whole chain of every joint).
    Each joint is walked once: a walk stops at a joint whose chain is known, so a file of n
    joints each mimicking the one before costs n steps, not n**2.
    """
    by_name = {joint.name: joint for joint in joints}
    for joint in joints:
        if joint.mimic is None or joint.type not in _DRIVEN_TYPES:
            continue
        target = by_name.get(joint.mimic[0])
        if target is None:
            raise FileFormatError(f"mimics unknown joint {joint.mimic[0]!r}", file=source,
                                  joint=joint.name, field="mimic.joint")
        if target.type not in _DRIVEN_TYPES:
            raise FileFormatError(
                f"mimics {target.name!r}, a {target.type} joint; only "
                f"{', '.join(_DRIVEN_TYPES)} joints have a value to follow", file=source,
                joint=joint.name, field="mimic.joint")
    length: dict[str, int] = {}  # joints in the chain from a joint to one that mimics none
    for joint in joints:
        chain: dict[str, None] = {}  # in order, with constant-time membership
        current = joint
        while (current.name not in length and current.mimic is not None
               and current.type in _DRIVEN_TYPES):
            if current.name in chain:
                names = list(chain)
                cycle = [*names[names.index(current.name):], current.name]
                raise FileFormatError(f"mimic cycle: {' -> '.join(cycle)}", file=source,
                                      joint=current.name, field="mimic.joint")
            chain[current.name] = None
            current = by_name[current.mimic[0]]  # checked above
        rest = length.get(current.name, 1)
        for step, name in enumerate(reversed(chain), start=1):
            length[name] = rest + step
        if length.get(joint.name, 1) > current_limits().max_depth:
            raise exceeded("max_depth", f"a chain of {length[joint.name]:,} joints, each "
                           "mimicking the next", field="mimic.joint").located(
                               file=source, joint=joint.name)


def _required(element: ET.Element, attribute: str, source: str, joint: str | None) -> str:
    value = element.get(attribute)
    if not value:
        raise FileFormatError(f"<{element.tag}> without {attribute!r}", file=source,
                              joint=joint, field=f"{element.tag}.{attribute}")
    return value


def _child_attribute(element: ET.Element, tag: str, attribute: str, source: str,
                     joint: str) -> str:
    child = element.find(tag)
    value = None if child is None else child.get(attribute)
    if not value:
        raise FileFormatError(f"missing <{tag} {attribute}=...>", file=source, joint=joint,
                              field=f"{tag}.{attribute}")
    return value


def _vector(element: ET.Element | None, attribute: str, source: str, joint: str, field: str,
            default: tuple[float, float, float]) -> tuple[float, float, float]:
    try:
        x, y, z = numbers(element, attribute, 3, source, None, field, default)
    except FileFormatError as exc:
        raise exc.located(joint=joint) from None
    return x, y, z


def _number(element: ET.Element | None, attribute: str, source: str, joint: str
            ) -> float | None:
    if element is None:
        return None
    text = element.get(attribute)
    if text is None:
        return None
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not np.isfinite(value):
        raise FileFormatError(f"expected a finite number, got {text!r}", file=source,
                              joint=joint, field=f"{element.tag}.{attribute}")
    return value


def _xml(element: ET.Element) -> str:
    text = ET.tostring(element, encoding="unicode")
    return text.strip()
