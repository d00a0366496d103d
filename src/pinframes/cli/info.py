"""``pinframes info FILE``: the tree, with each frame's kind, time span and reference time;
for a ROS bag also its topics (used and ignored), time span and unused joint states."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

import numpy as np

from ..formats.rosbag import ROSBAG_METADATA_KEY
from ..formats.urdf import URDF_METADATA_KEY
from ..tree import FrameTree
from ..tree.robot_semantics import semantic_robots
from ..values.timeconv import format_timestamp_iso
from ..values.timeline import source_reference
from ._files import read_tree
from ._subcommand import Subparsers, subcommand_parser
from ._terminal_text import printable

__all__ = ["add_parser", "describe", "describe_json", "run"]


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``info`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "info", run,
        help="show the tree of frames",
        description="Print the tree of frames in FILE with each frame's kind (static, "
        "moving, robot joint), the time span of its keyframes or joint samples (seconds "
        "after its reference time) and that reference time, then the subsystems (weldx) "
        "merged into the tree, the joint groups and group states of robots read with an "
        "SRDF; for a ROS bag, its topics (used and ignored), the time span "
        "of the stamps used and the joint states no joint took.", tree_file=None)
    parser.add_argument("file", metavar="FILE", help="scene, frames.yaml, ASDF or URDF file, "
                        "or a ROS bag (.bag, .mcap, .db3 or a ROS 2 bag folder)")
    parser.add_argument("--format", "-f", choices=("text", "json"), default="text",
                        help="a table to read, or JSON for programs (default: text)")


def run(args: argparse.Namespace) -> int:
    """Print the description of the tree."""
    tree = read_tree(args.file, args)
    if args.format == "json":
        sys.stdout.write(json.dumps(describe_json(tree), indent=1) + "\n")
    else:
        sys.stdout.write(describe(tree))
    return 0


def describe_json(tree: FrameTree) -> dict[str, Any]:
    """The tree as JSON data: each frame (root first, parents before children) with its
    parent, kind, joint, keyframe or joint-sample times (seconds after ``reference_time``)
    and reference time; then the subsystems."""
    frames = []
    for _, name in _walk(tree, tree.root, "", ""):
        entry: dict[str, Any] = {"name": name, "parent": tree.parent(name), "kind": "static",
                                 "joint": None, "samples": 0, "time_span_s": None,
                                 "reference_time": None}
        joint = tree.joint_of(name)
        times, reference = None, None
        if name == tree.root:
            entry["kind"] = "root"
        elif joint is not None:
            entry["kind"] = "robot joint"
            entry["joint"] = {"name": joint.name, "type": joint.kind, "axis": list(joint.axis),
                              "lower": joint.lower, "upper": joint.upper,
                              "mimics": None if joint.mimic is None else joint.mimic.joint}
            trajectory = tree.joint_trajectory(joint.name)
            if trajectory is not None:
                times, reference = trajectory.times, trajectory.reference
        elif tree.local_pose(name).is_time_dependent:
            pose = tree.local_pose(name)
            entry["kind"] = "moving"
            times, reference = pose.keyframes.times, pose.reference_time
        if times is not None:
            entry["samples"] = int(times.shape[0])
            entry["time_span_s"] = [times[0] / 1e9, times[-1] / 1e9]
            entry["reference_time"] = _timestamp(source_reference(reference, tree.reference_time))
        frames.append(entry)
    described = {
        "name": tree.name, "root": tree.root, "reference_time": _timestamp(tree.reference_time),
        "frames": frames,
        "subsystems": [{"name": s.name, "root": s.root, "members": list(s.members),
                        "parent": s.parent} for s in tree.subsystems],
    }
    robots = _srdf_robots(tree)
    if robots:
        described["srdf"] = robots
    if ROSBAG_METADATA_KEY in tree.metadata:
        described["rosbag"] = tree.metadata[ROSBAG_METADATA_KEY]
    return described


def _srdf_robots(tree: FrameTree) -> list[dict[str, Any]]:
    """Per robot read with an SRDF: the robot's name (its URDF's), its top frame, the file,
    each group's joints (tree names), the group states and the number of link pairs never
    checked."""
    robots = tree.metadata.get(URDF_METADATA_KEY, {})
    return [{"robot": robots.get(robot.top, {}).get("name"),
             "frame": robot.top, "file": robot.semantics.source,
             "groups": {group: [name for joint in joints
                                if (name := robot.joint(tree, joint)) is not None]
                        for group, joints in robot.semantics.groups.items()},
             "group_states": {state: value.group
                              for state, value in robot.semantics.states.items()},
             "disabled_pairs": robot.semantics.disabled_pair_count()}
            for robot in semantic_robots(tree)]


def _timestamp(stamp: np.datetime64 | None) -> str | None:
    return None if stamp is None else format_timestamp_iso(stamp)


def describe(tree: FrameTree) -> str:
    """A text table of the tree: one line per frame, children indented under parents; names
    with characters that do not print show them escaped."""
    reference = "none" if tree.reference_time is None else str(tree.reference_time)
    sampled = sum(tree.joint_trajectory(name) is not None for name in tree.joints)
    header = (f"tree {tree.name or '(unnamed)'}: {len(tree)} frames, "
              f"{sum(tree.is_moving(f) for f in tree.frames[1:])} moving, "
              f"{len(tree.joints)} robot joints ({sampled} with samples); "
              f"reference time {reference}")
    rows = [["FRAME", "KIND", "TIME SPAN", "REFERENCE TIME"]]
    for prefix, name in _walk(tree, tree.root, "", ""):
        rows.append([printable(cell) for cell in (prefix + name, *_frame_columns(tree, name))])
    widths = [max(len(row[column]) for row in rows) for column in range(3)]
    lines = [printable(header)]
    for row in rows:
        cells = [cell.ljust(width) for cell, width in zip(row[:3], widths, strict=True)]
        lines.append("  ".join([*cells, row[3]]).rstrip())
    for subsystem in tree.subsystems:
        inside = "" if subsystem.parent is None else f", merged into {subsystem.parent}"
        lines.append(printable(f"subsystem {subsystem.name}: root {subsystem.root}, "
                               f"{len(subsystem.members)} frames{inside}"))
    for robot in _srdf_robots(tree):
        groups = ", ".join(f"{name!r} ({len(joints)} joints)"
                           for name, joints in robot["groups"].items()) or "none"
        states = ", ".join(map(repr, robot["group_states"])) or "none"
        lines.append(printable(f"srdf of robot {robot['robot']!r} (top frame "
                               f"{robot['frame']!r}): groups {groups}; group states "
                               f"{states}; {robot['disabled_pairs']} link pairs never checked"))
    if ROSBAG_METADATA_KEY in tree.metadata:
        lines += map(printable, _bag_lines(tree.metadata[ROSBAG_METADATA_KEY]))
    return "\n".join(lines) + "\n"


def _bag_lines(bag: dict[str, Any]) -> list[str]:
    """The bag a tree was read from: kind, time span, topics used and ignored."""
    span = bag["time_span"]
    lines = [f"{bag['kind']} {bag['file']}: "
             + (f"stamps {span[0]} .. {span[1]}" if span else "nothing moves")]
    for used in (True, False):
        topics = [topic for topic in bag["topics"] if (topic["use"] is not None) == used]
        label = "topics used:   " if used else "topics ignored:"
        for number, topic in enumerate(topics):
            use = f": {topic['use']}" if used else ""
            lines.append(f"{label if number == 0 else ' ' * len(label)} {topic['name']} "
                         f"({topic['type']}, {topic['messages']} "
                         f"message{'' if topic['messages'] == 1 else 's'}){use}")
    if bag["joint_states_not_used"]:
        lines.append("joint states not used (no robot description drives them): "
                     + ", ".join(bag["joint_states_not_used"]))
    return lines


def _walk(tree: FrameTree, name: str, prefix: str, child_prefix: str):
    """``(prefix, frame)`` depth first, with a stack: trees may be thousands of frames deep."""
    stack = [(name, prefix, child_prefix)]
    while stack:
        name, prefix, child_prefix = stack.pop()
        yield prefix, name
        children = tree.children(name)
        for position in reversed(range(len(children))):
            last = position == len(children) - 1
            stack.append((children[position], child_prefix + ("`-- " if last else "|-- "),
                          child_prefix + ("    " if last else "|   ")))


def _frame_columns(tree: FrameTree, name: str) -> tuple[str, str, str]:
    if name == tree.root:
        return "root", "", ""
    joint = tree.joint_of(name)
    if joint is not None:
        kind = f"robot joint {joint.name} ({joint.kind}"
        kind += f", mimics {joint.mimic.joint})" if joint.mimic is not None else ")"
        trajectory = tree.joint_trajectory(joint.name)
        if trajectory is None:
            return kind, "mimic" if joint.mimic is not None else "no trajectory", ""
        return kind, _span(trajectory.times, "sample"), _reference(trajectory.reference, tree)
    pose = tree.local_pose(name)
    if not pose.is_time_dependent:
        return "static", "", ""
    return ("moving", _span(pose.keyframes.times, "keyframe"),
            _reference(pose.reference_time, tree))


def _span(nanoseconds: np.ndarray, what: str) -> str:
    """``0 s .. 10 s (2 samples)``; one sample (``what`` singular) is ``5 s (1 sample)``."""
    first, last = nanoseconds[0] / 1e9, nanoseconds[-1] / 1e9
    if nanoseconds.shape[0] == 1:
        return f"{first:g} s (1 {what})"
    return f"{first:g} s .. {last:g} s ({nanoseconds.shape[0]} {what}s)"


def _reference(own: np.datetime64 | None, tree: FrameTree) -> str:
    if own is not None:
        return str(own)
    if tree.reference_time is not None:
        return f"{tree.reference_time} (tree)"
    return "none"
