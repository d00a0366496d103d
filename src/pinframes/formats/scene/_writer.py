"""Writing a :class:`FrameTree` as a self-contained scene file (inline frames only).

Every frame becomes an inline frame with its pose in its parent: ``xyz`` in metres and a
``quaternion`` ``(x, y, z, w)``, to double precision. Moving frames get their keyframes; a
weave (:meth:`Pose.weave`) keeps its pattern as a ``weave`` entry.
A link driven by a robot joint becomes a moving frame keyed at its joint's trajectory
samples, which is exact: between two samples a revolute joint turns about a fixed axis, as
SLERP does, and a prismatic joint slides, as linear interpolation does. Joint kinds, limits
and the URDF itself are not kept; use ``write_urdf`` for those. Every frame's shapes (its
URDF link's and those of ``add_geometry``) are kept as its ``geometry`` entry. A program
section the scene was read with is written back as it was read.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from ...tree import FrameTree
from ...values.pose import Pose
from ...values.timeconv import format_timedelta_iso
from .._joint_steps import check_joint_steps
from .._snapshot import one_instant
from .._writable import check_writable_tree, refuse_attached_data
from ..atomic import atomic_write
from ._geometry import geometry_entries
from ._recognise import SCENE_FORMAT_KEY, SCENE_FORMAT_VERSION
from .program_section import PROGRAM_METADATA_KEY

__all__ = ["write_scene"]


def write_scene(tree: FrameTree, path: str | os.PathLike[str], time: Any = None) -> None:
    """Write ``tree`` as a scene file (atomically).

    Parameters
    ----------
    tree : FrameTree
        The tree to write.
    path : path-like
        The ``.yaml`` file to write.
    time : None or a time
        None keeps motion as keyframes; a time (seconds, duration, timestamp, counted as in
        :meth:`FrameTree.pose`) writes every frame at its pose at that time, static.

    Raises
    ------
    UnsupportedFeatureError
        A revolute or continuous joint turns by half a turn or more between two samples,
        which keyframes cannot say unambiguously (resample the trajectory more densely);
        data is attached to frames (a scene file cannot hold it).
    WriteError
        The file cannot be written; an existing file is left untouched.
    """
    check_writable_tree(tree, path)
    refuse_attached_data(tree, path, "a scene file")
    document: dict[str, Any] = {SCENE_FORMAT_KEY: SCENE_FORMAT_VERSION}
    if tree.name is not None:
        document["name"] = tree.name
    document["root"] = tree.root
    if tree.reference_time is not None and time is None:
        document["reference_time"] = str(tree.reference_time)
    instant = None if time is None else one_instant(tree, time, path, "a scene at one time")
    folder = Path(path).parent
    geometry_entries(tree, tree.root, folder)  # refuses shapes on the root
    frames = []
    for name in tree.frames[1:]:
        parent = tree.parent(name)
        assert parent is not None  # every frame but the root has one
        weave = tree.local_pose(name)
        if instant is None and weave.weaving is not None:
            frames.append(_weave_entry(name, parent, weave, tree.reference_time))
            continue
        if instant is None:
            check_joint_steps(tree, name)
            pose = tree.pose(name, relative_to=parent)
        else:
            pose = _at(tree.pose(name, relative_to=parent, times=[instant.time]), 0)
        entry = _frame_entry(name, parent, pose, tree.reference_time)
        shapes = geometry_entries(tree, name, folder)
        if shapes:
            entry["geometry"] = shapes
        frames.append(entry)
    if frames:
        document["frames"] = frames
    program = tree.metadata.get(PROGRAM_METADATA_KEY)
    if isinstance(program, dict):  # the program a scene was read with, as it was read
        document["program"] = program
    text = yaml.dump(document, Dumper=_FlowListDumper, sort_keys=False, width=100,
                     allow_unicode=True)
    with atomic_write(path, "w") as handle:
        handle.write(text)


class _FlowListDumper(yaml.SafeDumper):
    """Lists of numbers and keyframes on one line each; everything else in block style."""


class _Keyframe(dict):
    """A keyframe mapping, written on one line."""


def _represent_list(dumper: yaml.SafeDumper, data: list) -> yaml.Node:
    flow = all(isinstance(item, (int, float, str)) for item in data)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow)


def _represent_keyframe(dumper: yaml.SafeDumper, data: _Keyframe) -> yaml.Node:
    return dumper.represent_mapping("tag:yaml.org,2002:map", data, flow_style=True)


_FlowListDumper.add_representer(list, _represent_list)
_FlowListDumper.add_representer(_Keyframe, _represent_keyframe)


def _frame_entry(name: str, parent: str, pose: Pose, tree_reference: np.datetime64 | None
                 ) -> dict[str, Any]:
    entry: dict[str, Any] = {"name": name, "parent": parent}
    if not pose.is_time_dependent:
        entry.update(_pose_fields(pose.translation, pose.quaternion))
        return entry
    entry.update(_own_reference(pose, tree_reference))
    quaternions = pose.quaternion
    entry["keyframes"] = [
        _Keyframe(time=_time_value(int(offset)), **_pose_fields(translation, quaternion))
        for offset, translation, quaternion in zip(
            pose.keyframes.times, pose.translation, quaternions, strict=True)
    ]
    return entry


def _weave_entry(name: str, parent: str, pose: Pose, tree_reference: np.datetime64 | None
                 ) -> dict[str, Any]:
    """A ``weave`` entry: the pattern of :attr:`Pose.weaving`, sampled at the pose's times
    (``duration`` and ``step`` when they are every step from 0, else the ``times``)."""
    weave = pose.weaving
    assert weave is not None  # the caller checked
    fields: dict[str, Any] = {"amplitude": float(weave.amplitude),
                              "frequency": float(weave.frequency), "pattern": weave.pattern}
    if weave.dwell is not None:
        fields["dwell"] = float(weave.dwell)
    offsets = pose.keyframes.times
    step = int(offsets[1] - offsets[0])
    grid = _time_value(step), _time_value(int(offsets[-1]))
    times = [_time_value(int(offset)) for offset in offsets]
    if (offsets[0] == 0 and np.array_equal(offsets, step * np.arange(offsets.shape[0]))
            and all(isinstance(value, float) for value in grid)):
        fields["duration"], fields["step"] = grid[1], grid[0]
    elif all(isinstance(value, float) for value in times):
        fields["times"] = times
    else:  # one form for all: durations to the nanosecond
        fields["times"] = [format_timedelta_iso(int(offset)) for offset in offsets]
    return {"name": name, "parent": parent, **_own_reference(pose, tree_reference),
            "weave": fields}


def _own_reference(pose: Pose, tree_reference: np.datetime64 | None) -> dict[str, str]:
    """``reference_time`` of a moving frame whose times count from another than the tree's."""
    if pose.reference_time is not None and pose.reference_time != tree_reference:
        return {"reference_time": str(pose.reference_time)}
    return {}


def _pose_fields(translation: np.ndarray, quaternion: np.ndarray) -> dict[str, list[float]]:
    fields = {}
    if np.any(translation != 0.0):
        fields["xyz"] = [float(v) for v in translation]
    if not np.array_equal(quaternion, [0.0, 0.0, 0.0, 1.0]):
        fields["quaternion"] = [float(v) for v in quaternion]
    return fields


def _time_value(nanoseconds: int) -> float | str:
    """Seconds as a float when that is exact to the nanosecond, else an ISO duration."""
    seconds = nanoseconds / 1e9
    return seconds if round(seconds * 1e9) == nanoseconds else format_timedelta_iso(nanoseconds)


def _at(pose: Pose, index: int) -> Pose:
    return Pose(pose.translation[index], pose.rotation[index])
