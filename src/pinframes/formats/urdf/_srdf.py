"""SRDF files (MoveIt's semantic robot description) read against their URDF.

Read as MoveIt's srdfdom reads them: top-level ``<group>`` elements (``<chain base_link
tip_link>``, ``<joint name>``, ``<link name>`` and ``<group name>`` subgroups), top-level
``<group_state name group>`` with ``<joint name value>``, ``<disable_collisions link1
link2>``, ``<disable_default_collisions link>`` and ``<enable_collisions link1 link2>``.
A chain holds the joints on the path from its base link to its tip link; a link stands for
the joint above it; only driven joints count (a group of a positioner and a robot is both).

Other tools write more into the file (Tesseract's ``<contact_managers_plugin_config>``,
group states nested inside a group, names of links that are not in the URDF): what
pinframes does not use is skipped with one :class:`SrdfWarning` per file naming all of it;
only a file that cannot mean anything (malformed XML, another root element, an element
without the name it needs, a value that is no number, a group that contains itself) is a
:class:`FileFormatError` naming the file and the element.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET

from ...errors import FileFormatError, SrdfWarning, warn_at_caller
from ...values.robot_semantics import GroupState, RobotSemantics
from ..reading import read_text
from ._bounded_xml import parse_bounded_xml
from ._robot_description import RobotDescription

__all__ = ["SRDF_ELEMENTS", "looks_like_srdf", "read_srdf"]

SRDF_ELEMENTS = frozenset({
    "group", "group_state", "disable_collisions", "disable_default_collisions",
    "enable_collisions", "virtual_joint", "end_effector", "passive_joint",
    "link_sphere_approximation"})
"""The top-level elements of MoveIt's SRDF (those that bear on neither poses, groups nor
clearance, such as ``<virtual_joint>`` and ``<end_effector>``, are passed over silently)."""


def looks_like_srdf(root: ET.Element) -> bool:
    """Whether a ``<robot>`` element is an SRDF rather than a URDF: no links, and SRDF
    elements."""
    tags = {child.tag for child in root if isinstance(child.tag, str)}
    return "link" not in tags and bool(tags & SRDF_ELEMENTS)


def read_srdf(path: str | os.PathLike[str], robot: RobotDescription, *,
              text: str | None = None) -> RobotSemantics:
    """The SRDF at ``path`` (or its ``text``, a xacro SRDF's expansion), its names checked
    against ``robot`` (the URDF it describes)."""
    source = os.fspath(path)
    root = parse_bounded_xml(read_text(path) if text is None else text, source)
    if root.tag != "robot":
        raise FileFormatError(f"the root element is <{root.tag}>, expected <robot> (an SRDF)",
                              file=source, field="robot")
    reader = _Reader(root, source, robot)
    semantics = reader.semantics()
    _check_some_pair_applies(root, source, robot)
    if reader.skipped:
        warn_at_caller(f"{source}: skipped what pinframes does not use or the robot "
                       f"{robot.name!r} does not have: {'; '.join(dict.fromkeys(reader.skipped))}",
                       SrdfWarning)
    return semantics


def _check_some_pair_applies(root: ET.Element, source: str, robot: RobotDescription) -> None:
    """Refuse an SRDF whose collision rules all name links the robot does not have: the
    SRDF of another robot, or names with another prefix (a clearance would silently check
    every pair it leaves out)."""
    rules = [element for element in root
             if element.tag in ("disable_collisions", "disable_default_collisions")]
    names = {"disable_collisions": ("link1", "link2"), "disable_default_collisions": ("link",)}
    if rules and not any(all(rule.get(key) in robot.links for key in names[str(rule.tag)])
                         for rule in rules):
        first = " ".join(str(rules[0].get(key)) for key in names[str(rules[0].tag)])
        raise FileFormatError(
            f"none of its {len(rules):,} disabled collision pairs names links of the robot "
            f"{robot.name!r} (the first: {first}): the SRDF of another robot, or link names "
            "with another prefix (tf_prefix); a clearance without them would check every "
            "pair it leaves out", file=source,
            field=str(rules[0].tag))


class _Reader:
    """One SRDF against one URDF; :attr:`skipped` collects what is left out."""

    def __init__(self, root: ET.Element, source: str, robot: RobotDescription) -> None:
        self.root, self.source, self.robot = root, source, robot
        self.skipped: list[str] = []
        self.parent_joint = {joint.child: joint for joint in robot.joints}
        self.driven = [joint.name for joint in robot.joints
                       if joint.type in ("revolute", "continuous", "prismatic")
                       and joint.mimic is None]
        self.joint_child = {joint.name: joint.child for joint in robot.joints}

    def semantics(self) -> RobotSemantics:
        elements = [child for child in self.root if isinstance(child.tag, str)]
        other = sorted({child.tag for child in elements} - SRDF_ELEMENTS)
        if other:
            self.skipped.append("elements " + ", ".join(f"<{tag}>" for tag in other))
        definitions = {}
        for element in self.root.iterfind("group"):
            definitions[self._required(element, "name")] = element
        groups: dict[str, tuple[str, ...]] = {}
        for name in definitions:
            joints = self._group(name, definitions, ())
            if joints is not None:
                groups[name] = joints
        return RobotSemantics(self.source, groups, self._states(groups),
                              self._disabled_pairs(), dict(self.joint_child),
                              {joint.child: joint.parent for joint in self.robot.joints},
                              self.robot.root_link)

    def _group(self, name: str, definitions: dict[str, ET.Element],
               within: tuple[str, ...]) -> tuple[str, ...] | None:
        """The driven joints of group ``name``, in URDF order; None if it names nothing."""
        if name in within:
            raise FileFormatError(f"group {name!r} contains itself: "
                                  f"{' -> '.join([*within, name])}", file=self.source,
                                  field=f"group[{within[0]}]")
        members: set[str] = set()
        for child in definitions[name]:
            if child.tag == "group_state":
                self.skipped.append(f"group_state {child.get('name')!r} inside group "
                                    f"{name!r} (group states are read at the top level)")
            elif child.tag == "chain":
                members |= self._chain(child, name)
            elif child.tag == "joint":
                joint = self._required(child, "name", name)
                if joint in self.joint_child:
                    members.add(joint)
                else:
                    self.skipped.append(f"joint {joint!r} of group {name!r}")
            elif child.tag == "link":
                link = self._required(child, "name", name)
                if link in self.robot.links:
                    if link in self.parent_joint:
                        members.add(self.parent_joint[link].name)
                else:
                    self.skipped.append(f"link {link!r} of group {name!r}")
            elif child.tag == "group":
                inner = self._required(child, "name", name)
                if inner in definitions:
                    members |= set(self._group(inner, definitions, (*within, name)) or ())
                else:
                    self.skipped.append(f"subgroup {inner!r} of group {name!r}")
            elif isinstance(child.tag, str):
                self.skipped.append(f"<{child.tag}> in group {name!r}")
        return tuple(joint for joint in self.driven if joint in members)

    def _chain(self, element: ET.Element, group: str) -> set[str]:
        """The joints on the path from the chain's base link to its tip link."""
        base = self._required(element, "base_link", group)
        tip = self._required(element, "tip_link", group)
        missing = [link for link in (base, tip) if link not in self.robot.links]
        if missing:
            self.skipped.append(f"chain of group {group!r} (no link {missing[0]!r})")
            return set()
        up_from_tip, up_from_base = self._joints_up(tip), self._joints_up(base)
        return set(up_from_tip) ^ set(up_from_base)

    def _joints_up(self, link: str) -> list[str]:
        """The joints from ``link`` up to the root link."""
        joints = []
        while link in self.parent_joint:
            joint = self.parent_joint[link]
            joints.append(joint.name)
            link = joint.parent
        return joints

    def _states(self, groups: dict[str, tuple[str, ...]]) -> dict[str, GroupState]:
        states = {}
        for element in self.root.iterfind("group_state"):
            name = self._required(element, "name")
            group = self._required(element, "group")
            if group not in groups:
                self.skipped.append(f"group_state {name!r} of group {group!r}, which is "
                                    "not defined")
                continue
            values = {}
            for joint in element.iterfind("joint"):
                joint_name = self._required(joint, "name", name)
                value = self._number(joint, name)
                if joint_name in self.joint_child:
                    values[joint_name] = value
                else:
                    self.skipped.append(f"joint {joint_name!r} of group_state {name!r}")
            states[name] = GroupState(group, values)
        return states

    def _disabled_pairs(self) -> frozenset[frozenset[str]]:
        links = list(self.robot.links)
        disabled: set[frozenset[str]] = set()
        for element in self.root.iterfind("disable_default_collisions"):
            link = self._required(element, "link")
            if self._known_links(element.tag, link):
                disabled.update(frozenset((link, other)) for other in links if other != link)
        for element in self.root.iterfind("disable_collisions"):
            pair = self._required(element, "link1"), self._required(element, "link2")
            if self._known_links(element.tag, *pair):
                disabled.add(frozenset(pair))
        for element in self.root.iterfind("enable_collisions"):
            pair = self._required(element, "link1"), self._required(element, "link2")
            disabled.discard(frozenset(pair))
        return frozenset(disabled)

    def _known_links(self, tag: str, *names: str) -> bool:
        unknown = [name for name in names if name not in self.robot.links]
        if unknown:
            self.skipped.append(f"<{tag}> of link {unknown[0]!r}")
        return not unknown

    def _required(self, element: ET.Element, attribute: str, within: str | None = None) -> str:
        value = element.get(attribute)
        if not value:
            where = f"{element.tag}" if within is None else f"{within}.{element.tag}"
            raise FileFormatError(f"<{element.tag}> without {attribute!r}", file=self.source,
                                  field=f"{where}.{attribute}")
        return value

    def _number(self, joint: ET.Element, state: str) -> float:
        text = joint.get("value", "")
        try:
            value = float(text.split()[0])
        except (ValueError, IndexError):
            value = math.nan
        if not math.isfinite(value):
            raise FileFormatError(f"joint {joint.get('name')!r}: expected a number, got "
                                  f"{text!r}", file=self.source,
                                  field=f"group_state[{state}].joint.value")
        return value
