"""A frame tree from the tracks of a bag's frames, its robot descriptions and joint states.

Each robot (URDF) is mounted at the frame named as its root link: where tf gives that frame
a parent, the robot hangs there at the pose tf gives it; otherwise the root link is the
tree's root. tf frames of the robots' other links are what ``robot_state_publisher``
republished from the same joint states: they are left out (one warning when they differ
from what the description gives), the URDFs and the joint states place those links. Frames
of tf below a link (a camera on the flange) hang on that link. The result must have one root
and no cycle.
"""

from __future__ import annotations

from collections import deque
from pathlib import Path

import numpy as np

from ...errors import BagWarning, TreeStructureError, warn_at_caller
from ...tree import FrameTree
from ...values.pose import Pose
from ...values.rotations import matrix_from_quaternion
from ..urdf import DRIVEN_JOINT_TYPES, RobotDescription, mount_robot
from ._joint_states import JointSamples
from ._tf_tracks import FrameTrack

__all__ = ["assemble_tree", "reference_stamp"]

REPUBLISHED_TOLERANCE = 1e-9
"""Below this (metres, and rotation-matrix entries) a link's tf transform agrees with the
description's."""


def reference_stamp(tracks: dict[str, FrameTrack], joints: dict[str, JointSamples]
                    ) -> int | None:
    """The earliest stamp (ns since the epoch) of the moving frames and the joints used,
    or None when nothing moves."""
    stamps = [int(track.stamps_ns[0]) for track in tracks.values() if not track.static]
    stamps += [int(samples.stamps_ns[0]) for samples in joints.values()]
    return min(stamps) if stamps else None


def assemble_tree(name: str, tracks: dict[str, FrameTrack], robots: list[RobotDescription],
                  joints: dict[str, JointSamples], file: Path) -> FrameTree:
    """The tree of ``tracks`` and ``robots`` (their joints driven by ``joints``, only those
    they drive), with the earliest stamp used as its reference time."""
    links = {link for robot in robots for link in robot.links}
    by_root = {robot.root_link: robot for robot in robots}
    republished = [child for child in tracks if child in links and child not in by_root]
    parent_of = {child: track.parent for child, track in tracks.items()
                 if child not in links or child in by_root}
    for robot in robots:
        parent_of.update((joint.child, joint.parent) for joint in robot.joints)
    root = _single_root(parent_of, set(by_root), file)
    driven = {name for robot in robots for name in _driven_joints(robot)}
    if robots:
        _warn_unused(joints, driven, file)
    joints = {name: samples for name, samples in joints.items() if name in driven}
    reference = reference_stamp({c: t for c, t in tracks.items() if c in parent_of}, joints)
    reference_time = None if reference is None else np.datetime64(reference, "ns")
    tree = FrameTree(root, name=name, reference_time=reference_time)
    for frame in _parents_first(root, parent_of, file):
        if frame in by_root:
            track = tracks.get(frame)
            pose = None if track is None else _pose(track, reference)
            mount_robot(tree, by_root[frame], parent_of.get(frame), pose, "")
        elif frame not in links and frame != root:
            tree.add(frame, parent_of[frame], _pose(tracks[frame], reference))
    for joint, samples in joints.items():
        tree.set_joint_trajectory(samples.stamps_ns.astype("datetime64[ns]"),
                                  samples.positions[:, None], [joint])
    _warn_republished(tree, [tracks[child] for child in republished], file)
    return tree


def _warn_republished(tree: FrameTree, republished: list[FrameTrack], file: Path) -> None:
    """One warning when tf transforms of robot links (what ``robot_state_publisher``
    republished) differ from what the URDF and the joint states give: those are ignored,
    the tree places the links. Transforms that agree (to 1e-9 m, and rotation matrices to
    1e-9) lose nothing and need no word."""
    differ, largest = [], 0.0
    for track in republished:
        parent = tree.parent(track.child)
        if track.parent != parent:
            differ.append(track.child)
            continue
        if tree.reference_time is None:
            pose = tree.pose(track.child, parent)
            translations, rotations = pose.translation[None], pose.rotation[None]
        else:
            pose = tree.pose(track.child, parent,
                             times=track.stamps_ns.astype("datetime64[ns]"))
            translations, rotations = pose.translation, pose.rotation
        gap = max(float(np.abs(translations - track.translations).max()),
                  float(np.abs(rotations - matrix_from_quaternion(track.quaternions)).max()))
        if gap > REPUBLISHED_TOLERANCE:
            differ.append(track.child)
            largest = max(largest, gap)
    if differ:
        shown = ", ".join(repr(link) for link in differ[:5])
        warn_at_caller(
            f"{file}: ignored the tf transforms of {len(differ)} links the robot description "
            f"has, which differ from what the URDF and the joint states give (by up to "
            f"{largest:.3g} m or in rotation-matrix entries, or in their parent); the URDF "
            f"and the joint states place them: {shown}" + (" ..." if len(differ) > 5 else ""),
            BagWarning)


def _single_root(parent_of: dict[str, str], root_links: set[str], file: Path) -> str:
    frames = set(parent_of) | set(parent_of.values()) | root_links
    roots = sorted(frames - set(parent_of))
    if len(roots) > 1:
        raise TreeStructureError(
            f"the frames form {len(roots)} trees, with the roots {', '.join(map(repr, roots))}"
            "; tf2 keeps unconnected trees apart, a frame tree has one root (publish the "
            "transforms that join them, or read the bag's topics separately)", file=file)
    if not roots:
        raise TreeStructureError("the frames' parents form a cycle: "
                                 + ", ".join(map(repr, sorted(frames)[:10])), file=file)
    return roots[0]


def _parents_first(root: str, parent_of: dict[str, str], file: Path) -> list[str]:
    """Every frame, each after its parent; frames not below ``root`` lie on a cycle."""
    children: dict[str, list[str]] = {}
    for child, parent in parent_of.items():
        children.setdefault(parent, []).append(child)
    order, queue = [], deque([root])
    while queue:
        frame = queue.popleft()
        order.append(frame)
        queue.extend(children.get(frame, ()))
    if len(order) < len(parent_of) + 1:
        cycle = sorted(set(parent_of) - set(order))
        raise TreeStructureError("the frames' parents form a cycle: "
                                 + ", ".join(map(repr, cycle[:10])), file=file)
    return order


def _pose(track: FrameTrack, reference: int | None) -> Pose:
    """The pose of a track in its parent: static, or keyframed counting from the tree's
    reference time."""
    if track.static or reference is None:
        return Pose(track.translations[-1], track.quaternions[-1])
    return Pose(track.translations, track.quaternions,
                times=(track.stamps_ns - reference).astype("timedelta64[ns]"),
                reference_time=np.datetime64(reference, "ns"))


def _driven_joints(robot: RobotDescription) -> set[str]:
    """The joints of ``robot`` that joint states drive (not fixed, not mimic)."""
    return {joint.name for joint in robot.joints
            if joint.type in DRIVEN_JOINT_TYPES and joint.mimic is None}


def _warn_unused(joints: dict[str, JointSamples], driven: set[str], file: Path) -> None:
    unused = [name for name in joints if name not in driven]
    if unused:
        shown = ", ".join(repr(name) for name in unused[:5])
        warn_at_caller(f"{file}: joint states of {len(unused)} joints the robot description "
                       f"does not drive (fixed, mimic or not in it) are not used: {shown}"
                       + (" ..." if len(unused) > 5 else ""), BagWarning)
