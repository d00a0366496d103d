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
a group or group state defined twice keeps its last definition, with that warning;
only a file that cannot mean anything (malformed XML, another root element, an element
without the name it needs, a value that is no number, a group that contains itself) is a
:class:`FileFormatError` naming the file and the element.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from collections.abc import Iterable

from ...errors import FileFormatError, SrdfWarning, warn_at_caller
from ...values.robot_semantics import GroupState, RobotSemantics
from ..limits import current_limits, exceeded
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
                       f"{robot.name!r} does not have: {'; '.join(reader.skipped)}",
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
    """One SRDF against one URDF; :attr:`skipped` collects what is left out.

    Each group is resolved once (its driven joints as the bits of an integer, one bit per
    driven joint), each chain and each link's joints up to the root once, so that groups
    naming their subgroups many times, and repeated elements, cost what the file's elements
    cost; the joints of all groups together are bounded by ``max_xml_elements``.
    """

    def __init__(self, root: ET.Element, source: str, robot: RobotDescription) -> None:
        self.root, self.source, self.robot = root, source, robot
        self.skipped: dict[str, None] = {}
        self.parent_joint = {joint.child: joint for joint in robot.joints}
        self.driven = [joint.name for joint in robot.joints
                       if joint.type in ("revolute", "continuous", "prismatic")
                       and joint.mimic is None]
        self.bit = {name: 1 << index for index, name in enumerate(self.driven)}
        self.joint_child = {joint.name: joint.child for joint in robot.joints}
        self._up: dict[str, int] = {}
        self._chains: dict[tuple[str, str], int] = {}
        self._parts: dict[str, tuple[int, tuple[str, ...]]] = {}
        self._resolved: dict[str, int] = {}

    def semantics(self) -> RobotSemantics:
        elements = [child for child in self.root if isinstance(child.tag, str)]
        other = sorted({child.tag for child in elements} - SRDF_ELEMENTS)
        if other:
            self._skip("elements " + ", ".join(f"<{tag}>" for tag in other))
        definitions = self._once("group", (
            (self._required(element, "name"), element)
            for element in self.root.iterfind("group")))
        masks = {name: self._resolve(name, definitions) for name in definitions}
        joints = sum(mask.bit_count() for mask in masks.values())
        if joints > current_limits().max_xml_elements:
            raise exceeded("max_xml_elements", f"the SRDF's groups hold {joints:,} joints "
                           "in all", field="group").located(file=self.source)
        groups = {name: self._joints_of(mask) for name, mask in masks.items()}
        disabled_links, disabled, enabled = self._collision_rules()
        return RobotSemantics(self.source, groups, self._states(groups), disabled,
                              dict(self.joint_child),
                              {joint.child: joint.parent for joint in self.robot.joints},
                              self.robot.root_link, disabled_links, enabled)

    def _skip(self, what: str) -> None:
        self.skipped[what] = None

    def _once(self, kind: str, named: Iterable[tuple[str, ET.Element]]
              ) -> dict[str, ET.Element]:
        """Elements by name; a name given twice keeps its last element, with a warning."""
        found: dict[str, ET.Element] = {}
        repeated: dict[str, int] = {}
        for name, element in named:
            if name in found:
                repeated[name] = repeated.get(name, 1) + 1
            found[name] = element
        for name, count in repeated.items():
            self._skip(f"all but the last of the {count} {kind}s named {name!r}")
        return found

    def _joints_of(self, mask: int) -> tuple[str, ...]:
        """The driven joints whose bits ``mask`` sets, in URDF order."""
        return tuple(joint for joint in self.driven if mask & self.bit[joint]) if mask else ()

    def _resolve(self, name: str, definitions: dict[str, ET.Element]) -> int:
        """The driven joints of group ``name`` as bits, each group walked once (a depth-
        first walk with its own stack: groups may nest as deep as the file is long)."""
        if name in self._resolved:
            return self._resolved[name]
        path = [name]
        pending = [iter(self._members(name, definitions)[1])]
        while pending:
            for inner in pending[-1]:
                if inner in path:
                    cycle = [*path[path.index(inner):], inner]
                    raise FileFormatError(f"group {inner!r} contains itself: "
                                          f"{' -> '.join(cycle)}", file=self.source,
                                          field=f"group[{path[0]}]")
                if inner not in self._resolved:
                    path.append(inner)
                    pending.append(iter(self._members(inner, definitions)[1]))
                    break
            else:
                current = path.pop()
                pending.pop()
                own, inner_groups = self._parts[current]
                for inner in inner_groups:
                    own |= self._resolved[inner]
                self._resolved[current] = own
        return self._resolved[name]

    def _members(self, name: str, definitions: dict[str, ET.Element]
                 ) -> tuple[int, tuple[str, ...]]:
        """Group ``name``'s own joints (bits) and the subgroups it names, each once."""
        if name in self._parts:
            return self._parts[name]
        members = 0
        inner_groups: dict[str, None] = {}
        for child in definitions[name]:
            if child.tag == "group_state":
                self._skip(f"group_state {child.get('name')!r} inside group {name!r} (group "
                           "states are read at the top level)")
            elif child.tag == "chain":
                members |= self._chain(child, name)
            elif child.tag == "joint":
                joint = self._required(child, "name", name)
                if joint in self.joint_child:
                    members |= self.bit.get(joint, 0)
                else:
                    self._skip(f"joint {joint!r} of group {name!r}")
            elif child.tag == "link":
                link = self._required(child, "name", name)
                if link in self.robot.links:
                    if link in self.parent_joint:
                        members |= self.bit.get(self.parent_joint[link].name, 0)
                else:
                    self._skip(f"link {link!r} of group {name!r}")
            elif child.tag == "group":
                inner = self._required(child, "name", name)
                if inner in definitions:
                    inner_groups[inner] = None
                else:
                    self._skip(f"subgroup {inner!r} of group {name!r}")
            elif isinstance(child.tag, str):
                self._skip(f"<{child.tag}> in group {name!r}")
        self._parts[name] = members, tuple(inner_groups)
        return self._parts[name]

    def _chain(self, element: ET.Element, group: str) -> int:
        """The joints on the path from the chain's base link to its tip link, as bits."""
        base = self._required(element, "base_link", group)
        tip = self._required(element, "tip_link", group)
        if (base, tip) not in self._chains:
            missing = [link for link in (base, tip) if link not in self.robot.links]
            if missing:
                self._skip(f"chain of group {group!r} (no link {missing[0]!r})")
            self._chains[base, tip] = 0 if missing else self._joints_up(tip) ^ self._joints_up(
                base)
        return self._chains[base, tip]

    def _joints_up(self, link: str) -> int:
        """The driven joints from ``link`` up to the root link, as bits (each link's once)."""
        walked = []
        while link in self.parent_joint and link not in self._up:
            walked.append(link)
            link = self.parent_joint[link].parent
        above = self._up.get(link, 0)
        for below in reversed(walked):
            above |= self.bit.get(self.parent_joint[below].name, 0)
            self._up[below] = above
        return self._up.get(walked[0], 0) if walked else above

    def _states(self, groups: dict[str, tuple[str, ...]]) -> dict[str, GroupState]:
        states = {}
        named = self._once("group_state", (
            (self._required(element, "name"), element)
            for element in self.root.iterfind("group_state")))
        for name, element in named.items():
            group = self._required(element, "group")
            if group not in groups:
                self._skip(f"group_state {name!r} of group {group!r}, which is not defined")
                continue
            values = {}
            for joint in element.iterfind("joint"):
                joint_name = self._required(joint, "name", name)
                value = self._number(joint, name)
                if joint_name in self.joint_child:
                    values[joint_name] = value
                else:
                    self._skip(f"joint {joint_name!r} of group_state {name!r}")
            states[name] = GroupState(group, values)
        return states

    def _collision_rules(self) -> tuple[frozenset[str], frozenset[frozenset[str]],
                                        frozenset[frozenset[str]]]:
        """Links of which no pair is checked, pairs never checked, pairs checked even so;
        repeats merged."""
        links: set[str] = set()
        for element in self.root.iterfind("disable_default_collisions"):
            link = self._required(element, "link")
            if self._known_links(element.tag, link):
                links.add(link)
        disabled: set[frozenset[str]] = set()
        for element in self.root.iterfind("disable_collisions"):
            pair = self._required(element, "link1"), self._required(element, "link2")
            if self._known_links(element.tag, *pair):
                disabled.add(frozenset(pair))
        enabled = {frozenset((self._required(element, "link1"),
                              self._required(element, "link2")))
                   for element in self.root.iterfind("enable_collisions")}
        return frozenset(links), frozenset(disabled), frozenset(enabled)

    def _known_links(self, tag: str, *names: str) -> bool:
        unknown = [name for name in names if name not in self.robot.links]
        if unknown:
            self._skip(f"<{tag}> of link {unknown[0]!r}")
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
