"""The SRDF names of the robots in a tree, as the tree names things.

A robot read with an SRDF carries a :class:`~pinframes.values.robot_semantics.LinkSemantics`
on each of its link frames. A robot is found as the frames that carry the same SRDF and hang
together through their URDF parent links, so two copies of one robot under different
prefixes stay two robots, and renaming or grafting keeps them (a graft mounts the root link
on another tree's frame, which keeps no record: the frame the robot's links then hang from
stands for it).
Here the SRDF's link pairs become frame pairs (for ``clearance``), its groups tree joint
names and its group states joint values by tree joint name (for ``solve_joints``).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from ..errors import NameNotFoundError, near_misses
from ..values.robot_semantics import SEMANTICS_METADATA_KEY, LinkSemantics, RobotSemantics
from ._structure import EditableTree

__all__ = ["SemanticRobot", "disabled_frame_pairs", "group_joints", "group_state_values",
           "semantic_robots"]


@dataclass(frozen=True)
class SemanticRobot:
    """One robot of a tree that has an SRDF: its top frame and its links' frames by URDF
    link name."""

    top: str
    semantics: RobotSemantics
    frames: dict[str, str]

    def joint(self, tree: EditableTree, urdf_joint: str) -> str | None:
        """The tree's name of the robot's URDF joint ``urdf_joint`` (None: not driven)."""
        frame = self.frames.get(self.semantics.joint_links.get(urdf_joint, ""))
        joint = None if frame is None else tree.joint_of(frame)
        return None if joint is None else joint.name


def semantic_robots(tree: EditableTree) -> list[SemanticRobot]:
    """Every robot of ``tree`` that was read with an SRDF."""
    found: dict[str, tuple[RobotSemantics, dict[str, str]]] = {}
    tops: dict[str, str] = {}
    for frame in tree.frames:
        own = _semantics(tree, frame)
        if own is None:
            continue
        top = tops[frame] = _robot_top(tree, frame, own, tops)
        found.setdefault(top, (own.robot, {}))[1][own.link] = frame
    for top, (semantics, frames) in found.items():
        root = semantics.root_link
        if root not in frames and _semantics(tree, top) is None:
            frames[root] = top  # the root link's frame lost its record: a graft's mount frame
    return [SemanticRobot(top, semantics, frames)
            for top, (semantics, frames) in found.items()]


def _robot_top(tree: EditableTree, frame: str, own: LinkSemantics,
               tops: dict[str, str]) -> str:
    """The highest frame of ``frame``'s robot: up through the URDF parent links that carry
    the same SRDF, then one frame more when the last is a child of the robot's root link and
    its parent carries nothing (the root link's frame of a grafted tree, which keeps no
    record). ``tops``: the frames whose top is known, where the walk up stops."""
    top, link = frame, own
    while (parent := tree.parent(top)) is not None:
        above = _parent_link(tree, parent, link)
        if above is not None and parent in tops:
            return tops[parent]
        if above is None:
            if (link.robot.link_parents.get(link.link) == link.robot.root_link
                    and _semantics(tree, parent) is None):
                top = parent
            break
        top, link = parent, above
    return top


def disabled_frame_pairs(tree: EditableTree, frames: Iterable[str]
                         ) -> list[tuple[str, str]]:
    """The pairs among ``frames`` whose links' SRDF disables their collisions (a disabled
    link pairs with every other link of its robot among ``frames``)."""
    wanted = set(frames)
    pairs: dict[frozenset[str], tuple[str, str]] = {}
    for robot in semantic_robots(tree):
        semantics = robot.semantics
        here = {link: frame for link, frame in robot.frames.items() if frame in wanted}
        named = [sorted(pair) for pair in semantics.disabled_pairs]
        by_link = [(link, other) for link in sorted(semantics.disabled_links & here.keys())
                   for other in here if other != link]
        for link_a, link_b in [*named, *by_link]:
            first, second = sorted((link_a, link_b))
            if first in here and second in here and semantics.disables(first, second):
                frame_pair = here[first], here[second]
                pairs.setdefault(frozenset(frame_pair), frame_pair)
    return list(pairs.values())


def group_joints(tree: EditableTree, group: str, near: Iterable[str]) -> list[str]:
    """The tree joint names of SRDF group ``group`` (a :class:`NameNotFoundError` naming
    the groups there are when no robot has it). Of several robots that have it, the one
    holding a frame of ``near`` or one of their ancestors."""
    robot = _robot_with(tree, group, "groups", near, "joints")
    return [name for joint in robot.semantics.groups[group]
            if (name := robot.joint(tree, joint)) is not None]


def group_state_values(tree: EditableTree, state: str, near: Iterable[str]
                       ) -> dict[str, float]:
    """The joint values (tree joint names) of SRDF group state ``state``."""
    robot = _robot_with(tree, state, "states", near, "seed")
    values = robot.semantics.states[state].values
    return {name: value for joint, value in values.items()
            if (name := robot.joint(tree, joint)) is not None}


def _robot_with(tree: EditableTree, name: str, table: str, near: Iterable[str],
                field: str) -> SemanticRobot:
    robots = semantic_robots(tree)
    having = [robot for robot in robots if name in getattr(robot.semantics, table)]
    what = "group" if table == "groups" else "group state"
    if not having:
        known = sorted({known for robot in robots for known in getattr(robot.semantics, table)})
        detail = (f"the SRDFs define {', '.join(map(repr, known))}" if known else
                  "no robot of the tree was read with an SRDF (srdf=, --srdf)")
        raise NameNotFoundError(f"no SRDF {what} {name!r}; {detail}"
                                + near_misses(name, known), field=field)
    if len(having) == 1:
        return having[0]
    around = {ancestor for frame in near for ancestor in _up(tree, frame)}
    close = [robot for robot in having if around & set(robot.frames.values())]
    if len(close) != 1:
        tops = ", ".join(repr(robot.top) for robot in having)
        raise NameNotFoundError(f"SRDF {what} {name!r} is one of several robots ({tops}); "
                                "name the joints instead", field=field)
    return close[0]


def _up(tree: EditableTree, frame: str) -> list[str]:
    chain = []
    current: str | None = frame
    while current is not None:
        chain.append(current)
        current = tree.parent(current)
    return chain


def _semantics(tree: EditableTree, frame: str) -> LinkSemantics | None:
    found = tree.frame_metadata(frame).get(SEMANTICS_METADATA_KEY)
    return found if isinstance(found, LinkSemantics) else None


def _parent_link(tree: EditableTree, frame: str, link: LinkSemantics
                 ) -> LinkSemantics | None:
    """What ``frame`` (the parent of ``link``'s frame) carries when it is the parent link of
    ``link`` in the same robot, else None."""
    other = _semantics(tree, frame)
    if (other is not None and other.link == link.robot.link_parents.get(link.link)
            and (other.robot is link.robot or other.robot == link.robot)):
        return other
    return None
