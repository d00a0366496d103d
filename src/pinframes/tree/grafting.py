"""Grafting one frame tree onto another, and copying the part of a tree below a frame.

``graft`` is weldx's ``CoordinateSystemManager.merge`` with a mount point: the other tree's
root becomes frame ``at`` of this tree, every other frame of it (moving frames, robot links
with their joints and trajectories, data, and the entries of its tree metadata) comes along
with ``prefix`` before its name, and a :class:`Subsystem` records what came. ``subtree`` is
the reverse: a new tree rooted at a frame, holding what lies below it; a subsystem that
recorded exactly that part is unwrapped again, so that grafting and then taking the subtree
gives back the tree that was grafted (its frames; tree metadata is not taken back).
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np

from ..errors import ArgumentTypeError, FrameExistsError, FrameNotFoundError, TreeStructureError
from ..values.joint import Joint, Mimic
from ..values.joint_trajectory import JointTrajectory
from ..values.pose import Pose
from ..values.spatial_data import SpatialData
from ..values.subsystem import Subsystem
from ..values.timeline import source_reference
from ._structure import EditableTree

__all__ = ["Tree", "copy_tree", "graft", "subtree"]

Tree = TypeVar("Tree", bound=EditableTree)
"""A tree of one class throughout a call: ``subtree(tree)`` returns a tree of ``type(tree)``."""


def graft(tree: Tree, other: Tree, at: str | None = None, prefix: str = "",
          name: str | None = None, record: bool = True) -> Subsystem | None:
    """Mount ``other`` on ``tree``; see :meth:`pinframes.FrameTree.graft`."""
    if not isinstance(other, type(tree)):
        raise ArgumentTypeError(f"expected a pinframes.FrameTree, got {type(other).__name__}",
                                field="other")
    if not isinstance(prefix, str):
        raise ArgumentTypeError(f"expected a string, got {type(prefix).__name__}",
                                field="prefix")
    at = prefix + other.root if at is None else at
    if at not in tree:
        raise FrameNotFoundError(f"the mount frame {at!r} is not in the tree", frame=str(at),
                                 field="at")
    if other is tree:
        raise TreeStructureError("a tree cannot be grafted onto itself", field="other")

    def renamed(frame: str) -> str:
        return at if frame == other.root else prefix + frame

    record_name = name if name is not None else prefix + (other.name or other.root)
    subsystems = _renamed_subsystems(other, renamed, prefix, record_name if record else None)
    metadata = _renamed_metadata(other, prefix)
    _refuse_clashes(tree, other, renamed, prefix,
                    [record_name] * record + [s.name for s in subsystems], list(metadata))
    entry = Subsystem(record_name, at, tuple(renamed(frame) for frame in other.frames),
                      tree.name, other.reference_time,
                      tuple(s.name for s in subsystems if s.parent == record_name),
                      tuple(prefix + data for data in other.data_names)) if record else None
    added = [renamed(child) for child in other.children(other.root)]
    try:
        _copy_frames(other, tree, renamed, prefix, other.reference_time)
    except Exception:
        for child in added:
            if child in tree:
                tree.remove(child, recursive=True, drop_data=True)
        raise
    tree.subsystems = [*tree.subsystems, *([entry] if entry else []), *subsystems]
    tree.metadata.update(metadata)
    return entry


def subtree(tree: Tree, frame: str) -> Tree:
    """A copy of ``frame`` and everything below it; see :meth:`pinframes.FrameTree.subtree`."""
    if frame not in tree:
        raise FrameNotFoundError("no frame of this name in the tree", frame=str(frame),
                                 field="frame")
    below = _below(tree, frame)
    kept = [s for s in tree.subsystems if s.root in below and set(s.members) <= below]
    whole = [s for s in kept if s.root == frame and set(s.members) == below]
    record = whole[0] if len(whole) == 1 else None
    reference = tree.reference_time if record is None else record.reference_time
    copy_tree = type(tree)(frame, name=tree.name if record is None else record.name,
                          reference_time=reference)
    # keyframes counting from the tree's reference time keep it, if the copy has another
    anchor = None if reference == tree.reference_time else tree.reference_time
    _copy_frames(tree, copy_tree, lambda name: name, "", anchor, frame)
    copy_tree.subsystems = [s for s in kept if s is not record]
    return copy_tree


def copy_tree(tree: Tree) -> Tree:
    """An independent copy of ``tree``: frames, joints, trajectories, data, subsystems and
    metadata (deep-copied)."""
    copied = type(tree)(tree.root, name=tree.name, reference_time=tree.reference_time)
    _copy_frames(tree, copied, lambda name: name, "", None)
    copied.frame_metadata(tree.root).update(copy.deepcopy(tree.frame_metadata(tree.root)))
    copied.subsystems = list(tree.subsystems)
    copied.metadata = copy.deepcopy(tree.metadata)
    return copied


def _copy_frames(source: EditableTree, target: EditableTree, renamed: Callable[[str], str],
                 prefix: str, reference: np.datetime64 | None, top: str | None = None) -> None:
    """Add every frame below ``top`` (default: the root) of ``source`` to ``target``.

    Keyframes, joint trajectories and data that count from ``reference`` (the source's reference
    time, when it changes tree) get it as their own, so they keep their absolute times.
    """
    top = source.root if top is None else top
    below = _below(source, top)
    frames = [f for f in source.frames if f in below and f != top]
    for frame in frames:
        above = source.parent(frame)
        assert above is not None  # frames below top, never the root
        parent = renamed(above)
        pose = _anchored_pose(source.local_pose(frame), reference)
        joint = source.joint_of(frame)
        if joint is None:
            target.add(renamed(frame), parent, pose)
        else:
            mimic = None if joint.mimic is None else Mimic(
                prefix + joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset)
            target.attach_joint(renamed(frame), parent, Joint(
                prefix + joint.name, joint.kind, joint.axis, joint.lower, joint.upper,
                joint.velocity, joint.effort, mimic), pose)
        target.frame_metadata(renamed(frame)).update(
            copy.deepcopy(source.frame_metadata(frame)))
    for frame in frames:
        joint = source.joint_of(frame)
        trajectory = None if joint is None else source.joint_trajectory(joint.name)
        if joint is not None and trajectory is not None:
            target.replace_joint_trajectory(prefix + joint.name, JointTrajectory(
                trajectory.times, source_reference(trajectory.reference, reference),
                trajectory.values, trajectory.interpolation))
    for data_name in source.data_names:
        if source.data_frame(data_name) in below:
            target.assign_data(prefix + data_name,
                               _anchored_data(source.get_data(data_name), reference),
                               renamed(source.data_frame(data_name)))


def _anchored_pose(pose: Pose, reference: np.datetime64 | None) -> Pose:
    if not pose.is_time_dependent or pose.reference_time is not None or reference is None:
        return pose
    return Pose(pose.translation, pose.rotation, times=pose.times, reference_time=reference)


def _anchored_data(data: SpatialData, reference: np.datetime64 | None) -> SpatialData:
    times = data.times
    if times is None or data.reference_time is not None or reference is None:
        return data
    return data.with_points(data.points, times.astype(np.int64), reference)


def _refuse_clashes(tree: EditableTree, other: EditableTree, renamed: Callable[[str], str],
                    prefix: str, subsystem_names: list[str], metadata_keys: list[Any]) -> None:
    """A :class:`FrameExistsError` for any name the graft would take twice; nothing changed."""
    clashes = [
        ("frames", [renamed(f) for f in other.frames[1:] if renamed(f) in tree]),
        ("joints", [prefix + j for j in other.joints if prefix + j in tree.joints]),
        ("data", [prefix + d for d in other.data_names if prefix + d in tree.data_names]),
        ("subsystems", [n for n in subsystem_names
                        if n in {s.name for s in tree.subsystems}]),
        ("metadata", [key for key in metadata_keys if key in tree.metadata]),
    ]
    for kind, names in clashes:
        if names:
            raise FrameExistsError(
                f"the tree already has {kind} named {', '.join(map(repr, names[:5]))}"
                + (" ..." if len(names) > 5 else "") + "; graft with another prefix or name",
                frame=names[0] if kind == "frames" else None, field=kind)


def _renamed_metadata(other: EditableTree, prefix: str) -> dict[Any, Any]:
    """``other.metadata`` deep-copied, with ``prefix`` before every key; with a prefix, a key
    that is not a string is an :class:`ArgumentTypeError` (raised before the tree changes)."""
    if prefix:
        odd = [key for key in other.metadata if not isinstance(key, str)]
        if odd:
            raise ArgumentTypeError(f"metadata key {odd[0]!r} is not a string, so it cannot "
                                    f"take the prefix {prefix!r}", field="metadata")
    return {prefix + key if prefix else key: value
            for key, value in copy.deepcopy(other.metadata).items()}


def _renamed_subsystems(other: EditableTree, renamed: Callable[[str], str], prefix: str,
                        record: str | None) -> list[Subsystem]:
    """The grafted tree's subsystems: names prefixed, top-level ones nested in ``record``."""
    nesting = {inner: s.name for s in other.subsystems for inner in s.subsystems}
    return [Subsystem(prefix + s.name, renamed(s.root), tuple(renamed(m) for m in s.members),
                      prefix + nesting[s.name] if s.name in nesting else record,
                      s.reference_time, tuple(prefix + n for n in s.subsystems),
                      tuple(prefix + d for d in s.data))
            for s in other.subsystems]


def _below(tree: EditableTree, frame: str) -> set[str]:
    """``frame`` and every frame below it."""
    below, stack = set(), [frame]
    while stack:
        name = stack.pop()
        below.add(name)
        stack.extend(tree.children(name))
    return below
