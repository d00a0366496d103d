"""Reading scene files: one YAML file that puts a whole cell together.

A scene combines frame layers (``frames.yaml`` files and ASDF hierarchies), inline frames,
robots (URDF files with joint trajectories) and tool frames into one :class:`FrameTree`.
The format is described in ``docs/scene-format.md``; in short::

    pinframes_scene: 1
    root: world
    layers:  [{file: cell.frames.yaml, mount: world}]
    frames:  [{name: table, parent: world, xyz: [1, 0, 0.8], rpy: [0, 0, 0],
               geometry: [{box: {size: [1.2, 0.8, 0.05]}}]}]
    robots:  [{urdf: robot.urdf, parent: table, prefix: "robot/", trajectory: motion.csv,
               srdf: robot.srdf, package_dirs: [meshes], xacro_args: {ur_type: ur5e}}]
    tools:   [{name: tcp, parent: robot/flange, xyz: [0, 0, 0.2]}]

Paths inside a scene are relative to the scene file. Lengths in metres, angles in radians.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import FileFormatError, PinframesError, UnsupportedFeatureError
from ...tree import FrameTree
from ...values.curve_frames import length_along_polyline
from ...values.pose import Pose
from ...values.rotations import matrix_from_axis_angle
from ...values.timeconv import parse_timestamp
from .._paths import regular_file_problem
from .._registry import detect_format, files_read, read, require_format
from ..limits import Limits, current_limits, exceeded, reader_with_limits
from ..reading import InputFile
from ..trajectory_files import read_joint_trajectory
from ..urdf import RobotDescription, mount_robot, parse_urdf
from ._geometry import add_geometry, read_geometry
from ._unit_check import UnitCheck

__all__ = ["SCENE_FORMAT_KEY", "SCENE_FORMAT_VERSION", "is_scene", "read_scene",
           "scene_files_read", "scene_without_key"]

SCENE_FORMAT_KEY = "pinframes_scene"
"""The top-level key that marks a scene file; its value is the format version."""

SCENE_FORMAT_VERSION = 1
"""The scene format version this module reads and writes."""

_LAYER_FORMATS = ("frames.yaml", "asdf")
"""Formats a scene layer may be in."""
_TOP_KEYS = {SCENE_FORMAT_KEY, "name", "root", "reference_time", "layers", "frames", "robots",
             "tools"}
_POSE_KEYS = {"xyz", "rpy", "quaternion"}
_ENTRY_KEYS = {
    "layers": {"file", "mount", "prefix", "key"},
    "frames": {"name", "parent", "keyframes", "curve", "weave", "reference_time",
               "geometry"} | _POSE_KEYS,
    "robots": {"name", "urdf", "parent", "prefix", "trajectory", "srdf", "package_dirs",
               "xacro_args"} | _POSE_KEYS,
    "tools": {"name", "parent", "geometry"} | _POSE_KEYS,
}
_FILE_KEYS = {"layers": ("file",), "robots": ("urdf", "trajectory", "srdf")}
"""The keys of entries that name files (relative to the scene's folder)."""
_KEYFRAME_KEYS = {"time"} | _POSE_KEYS
_CURVE_KEYS = {"points", "normals", "arc", "speed", "duration", "times"}
_CURVE_TIMINGS = ("speed", "duration", "times")
_ARC_KEYS = {"centre", "axis", "start", "angle", "count"}
_WEAVE_KEYS = {"amplitude", "frequency", "pattern", "dwell", "times", "duration", "step"}


@dataclass
class _Entry:
    """One item of a scene list, waiting for its parent frame to exist."""

    field: str
    label: str | None
    parent: str
    parent_field: str
    apply: Callable[[FrameTree], None]


@reader_with_limits
def read_scene(path: str | os.PathLike[str], *, limits: Limits | None = None,
               package_dirs: Iterable[str | os.PathLike[str]] = ()) -> FrameTree:
    """Read a scene file into a new :class:`FrameTree`.

    ``limits`` (:class:`pinframes.Limits`) bounds the scene file and every file it names.
    ``package_dirs`` are searched for every robot's ``$(find PKG)``, ``package://`` and
    ``model://`` names, after the folders its entry names (``package_dirs:``).

    Entries are added as soon as the frame they hang from exists, so their order in the
    file does not matter (a tool may name a robot link, a robot a frame of a layer).

    Raises
    ------
    FileFormatError
        Malformed scene; the message names the scene file, the entry and the field. Errors
        inside a referenced file name that file and say which scene entry referenced it.
    UnsupportedFeatureError
        A scene format version newer than this pinframes reads.
    ReadError
        The scene file (or a file it names) is missing, a folder, unreadable or not text.
    """
    scene = _Scene(InputFile.of(path), tuple(os.fspath(folder) for folder in package_dirs))
    return scene.build()


def is_scene(source: InputFile) -> bool:
    """Whether ``source`` holds a scene: a YAML mapping with the :data:`SCENE_FORMAT_KEY`
    key (the content test of the scene format)."""
    content = source.yaml()
    return isinstance(content, dict) and SCENE_FORMAT_KEY in content


def scene_without_key(source: InputFile) -> str | None:
    """What ``source`` is when it is a scene but for its :data:`SCENE_FORMAT_KEY` line: a
    YAML mapping of scene keys only, with robots, tools, layers or a list of frames."""
    content = source.yaml()
    if not isinstance(content, dict) or SCENE_FORMAT_KEY in content or not content or (
            not set(content) <= _TOP_KEYS):
        return None
    if not (isinstance(content.get("frames"), list)
            or any(key in content for key in ("robots", "tools", "layers"))):
        return None
    return (f"a pinframes scene without its first line '{SCENE_FORMAT_KEY}: "
            f"{SCENE_FORMAT_VERSION}' (add that line and it reads as a scene)")


def scene_files_read(source: InputFile) -> list[Path]:
    """The files reading the scene ``source`` opens: the files its entries name (those that
    exist or not, in the scene's order), with what a layer file reads in turn. Names that
    are not strings are left for the reader to refuse."""
    content = source.yaml()
    named = []
    for section, keys in _FILE_KEYS.items():
        entries = content.get(section) if isinstance(content, dict) else None
        for entry in entries if isinstance(entries, list) else []:
            for key in keys:
                value = entry.get(key) if isinstance(entry, dict) else None
                if isinstance(value, str):
                    path = source.path.parent / value
                    named += files_read(path, among=_LAYER_FORMATS) if section == "layers" \
                        else [path]
    return named


class _Scene:
    """The parsed content of one scene file, and how to build its tree.

    Each file the scene names is read once, however many entries name it (through YAML
    aliases, say): a trajectory, a URDF, a layer (with its key).
    """

    def __init__(self, source: InputFile, package_dirs: tuple[str, ...] = ()) -> None:
        path = source.path
        self.path = path
        self.package_dirs = package_dirs
        self._read: dict[tuple[str, Path, str], Any] = {}
        require_format(source, "scene")
        content = source.yaml()
        if not isinstance(content, dict) or SCENE_FORMAT_KEY not in content:
            raise FileFormatError(f"not a pinframes scene: the file must start with "
                                  f"'{SCENE_FORMAT_KEY}: {SCENE_FORMAT_VERSION}'", file=path)
        version = content[SCENE_FORMAT_KEY]
        if version != SCENE_FORMAT_VERSION:
            raise UnsupportedFeatureError(
                f"scene format version {version!r}; this pinframes reads version "
                f"{SCENE_FORMAT_VERSION}", file=path, field=SCENE_FORMAT_KEY)
        self._check_keys(content, _TOP_KEYS, None, "")
        self.content = content
        self._units = UnitCheck(path)
        self.root = self._name(content.get("root", "world"), None, "root")

    # -- building --------------------------------------------------------------------------
    def build(self) -> FrameTree:
        """A fresh tree with every entry added; nothing is returned half-built."""
        layers = [self._layer(index, item)
                  for index, item in enumerate(self._list("layers"))]
        tree = FrameTree(self.root, name=self._optional_str("name"),
                         reference_time=self._reference_time(layers))
        entries = [entry for entry, _ in layers]
        entries += [self._frame(index, item) for index, item in enumerate(self._list("frames"))]
        entries += [self._robot(index, item) for index, item in enumerate(self._list("robots"))]
        entries += [self._tool(index, item) for index, item in enumerate(self._list("tools"))]
        pending = entries
        while pending:
            ready = [entry for entry in pending if entry.parent in tree]
            if not ready:
                stuck = pending[0]
                raise FileFormatError(
                    f"frame {stuck.parent!r} is neither in the scene nor made by another "
                    "entry", file=self.path, frame=stuck.label, field=stuck.parent_field)
            for entry in ready:
                self._apply(entry, tree)
            pending = [entry for entry in pending if entry not in ready]
        self._units.warn()
        return tree

    def _apply(self, entry: _Entry, tree: FrameTree) -> None:
        try:
            entry.apply(tree)
        except PinframesError as exc:
            if exc.file is not None and Path(exc.file) != self.path:
                raise self._referenced(exc, entry.field) from None
            raise exc.located(file=self.path, frame=entry.label, field=entry.field) from None

    def _reference_time(self, layers: list[tuple[_Entry, FrameTree]]) -> np.datetime64 | None:
        """The scene's reference time, else the earliest reference time of its layers."""
        if "reference_time" in self.content:
            return self._timestamp(self.content["reference_time"], None, "reference_time")
        references = [layer.reference_time for _, layer in layers
                      if layer.reference_time is not None]
        return min(references) if references else None

    # -- entries ---------------------------------------------------------------------------
    def _layer(self, index: int, item: Any) -> tuple[_Entry, FrameTree]:
        field = f"layers[{index}]"
        self._check_keys(item, _ENTRY_KEYS["layers"], None, field)
        file = self._file(item, "file", None, field)
        mount = self._name(item.get("mount", self.root), None, f"{field}.mount")
        prefix = self._prefix(item, None, field)
        key = item.get("key")
        layer = self._read_layer(file, key, field)
        entry = _Entry(field, None, mount, f"{field}.mount",
                       lambda tree: _graft(tree, layer, mount, prefix))
        return entry, layer

    def _once(self, kind: str, file: Path, key: Any, read_file: Callable[[], Any]) -> Any:
        """What ``read_file()`` gives for ``file`` (and ``key``), read the first time only."""
        where = (kind, file.resolve(), repr(key))
        if where not in self._read:
            self._read[where] = read_file()
        return self._read[where]

    def _read_layer(self, file: Path, key: Any, field: str) -> FrameTree:
        layer: FrameTree = self._once("layer", file, key,
                                      lambda: self._read_new_layer(file, key, field))
        return layer

    def _read_new_layer(self, file: Path, key: Any, field: str) -> FrameTree:
        source = InputFile(file)  # read once, for telling its format and by the reader
        try:
            layer_format = detect_format(source, among=_LAYER_FORMATS)
        except FileFormatError:
            raise FileFormatError(f"a layer must be a frames.yaml (.yaml) or ASDF (.asdf) "
                                  f"file, got {file.name!r}", file=self.path,
                                  field=f"{field}.file") from None
        if key is not None and layer_format != "asdf":
            raise FileFormatError("'key' is only for ASDF layers", file=self.path,
                                  field=f"{field}.key")
        try:
            tree: FrameTree = read(source, layer_format,
                                   **({} if key is None else {"key": key}))
        except PinframesError as exc:
            raise self._referenced(exc, f"{field}.file") from None
        return tree

    def _frame(self, index: int, item: Any) -> _Entry:
        field = f"frames[{index}]"
        name, parent = self._frame_names(item, "frames", field)
        static = self._pose_parts(item, name, field)
        rotation, translation = static
        pose = Pose(translation, rotation)
        if "keyframes" in item and "curve" in item:
            raise FileFormatError("give either keyframes or curve, not both", file=self.path,
                                  frame=name, field=f"{field}.curve")
        if "weave" in item:
            if {"keyframes", "curve"} & set(item) or _POSE_KEYS & set(item):
                raise FileFormatError("a weave frame takes its pose from the weave: no "
                                      "keyframes, curve, xyz, rpy or quaternion",
                                      file=self.path, frame=name, field=f"{field}.weave")
            pose = self._weave(item, name, field)
        elif "curve" in item:
            if _POSE_KEYS & set(item):
                raise FileFormatError("a curve frame takes its pose from the curve: no xyz, "
                                      "rpy or quaternion", file=self.path, frame=name,
                                      field=f"{field}.curve")
            pose = self._curve(item, name, field)
        elif "keyframes" in item:
            pose = self._keyframes(item, static, name, field)
        elif "reference_time" in item:
            raise FileFormatError("a reference_time needs keyframes, a curve or a weave",
                                  file=self.path, frame=name, field=f"{field}.reference_time")
        return self._inline(item, name, parent, pose, field)

    def _tool(self, index: int, item: Any) -> _Entry:
        field = f"tools[{index}]"
        name, parent = self._frame_names(item, "tools", field)
        rotation, translation = self._pose_parts(item, name, field)
        return self._inline(item, name, parent, Pose(translation, rotation), field)

    def _inline(self, item: dict, name: str, parent: str, pose: Pose, field: str) -> _Entry:
        """The entry that adds frame ``name`` at ``pose`` with the shapes of its
        ``geometry``."""
        shapes = read_geometry(item.get("geometry", []), self.path, name, f"{field}.geometry")

        def add(tree: FrameTree) -> None:
            tree.add(name, parent, pose)
            add_geometry(tree, name, shapes)

        return _Entry(field, name, parent, f"{field}.parent", add)

    def _robot(self, index: int, item: Any) -> _Entry:
        field = f"robots[{index}]"
        self._check_keys(item, _ENTRY_KEYS["robots"], None, field)
        label = self._name(item["name"], None, f"{field}.name") if "name" in item else None
        urdf = self._file(item, "urdf", label, field)
        parent = self._name(item.get("parent", self.root), label, f"{field}.parent")
        prefix = self._prefix(item, label, field)
        rotation, translation = self._pose_parts(item, label, field)
        pose = Pose(translation, rotation)
        srdf = self._file(item, "srdf", label, field) if "srdf" in item else None
        package_dirs = [*self._folders(item, label, field), *self.package_dirs]
        xacro_args = self._xacro_args(item, label, field)
        trajectory, path = None, urdf
        if "trajectory" in item:
            path = self._file(item, "trajectory", label, field)
            try:
                trajectory = self._once("trajectory", path, None,
                                        lambda: read_joint_trajectory(path))
            except PinframesError as exc:
                raise self._referenced(exc, f"{field}.trajectory") from None

        def attach(tree: FrameTree) -> None:
            try:
                robot: RobotDescription = self._once(
                    "urdf", urdf, (srdf, package_dirs, xacro_args),
                    lambda: parse_urdf(str(urdf), package_dirs=package_dirs,
                                       xacro_args=xacro_args, srdf=srdf))
                mount_robot(tree, robot, parent, pose, prefix)  # FrameTree.attach_urdf
            except PinframesError as exc:
                if exc.file is None:
                    raise  # a clash with the scene, located at this entry by _apply
                named = "srdf" if srdf is not None and exc.file == str(srdf) else "urdf"
                raise self._referenced(exc, f"{field}.{named}") from None
            if trajectory is not None:
                self._drive(tree, trajectory, prefix, path, label, f"{field}.trajectory")

        return _Entry(field, label, parent, f"{field}.parent", attach)

    def _drive(self, tree: FrameTree, trajectory: tuple[np.ndarray, np.ndarray, list[str]],
               prefix: str, path: Path, label: str | None, field: str) -> None:
        times, positions, names = trajectory
        joints = tree.joints
        for name in names:
            if prefix + name not in joints:
                known = ", ".join(sorted(joints)) or "none"
                raise self._referenced(FileFormatError(
                    f"no joint {prefix + name!r} in the tree (joints: {known})", file=path,
                    joint=name, field="header"), field)
        try:
            tree.set_joint_trajectory(times, positions, [prefix + name for name in names])
        except PinframesError as exc:
            raise self._referenced(exc.located(file=path), field) from None

    # -- poses -----------------------------------------------------------------------------
    def _pose_parts(self, item: dict, frame: str | None, field: str
                    ) -> tuple[np.ndarray | None, np.ndarray]:
        """Rotation (a (3, 3) matrix, or None) and translation (3,) metres."""
        translation = self._numbers(item.get("xyz", (0.0, 0.0, 0.0)), 3, frame, f"{field}.xyz")
        self._units.lengths(translation, frame, f"{field}.xyz")
        if "rpy" in item and "quaternion" in item:
            raise FileFormatError("give either rpy or quaternion, not both", file=self.path,
                                  frame=frame, field=f"{field}.rpy")
        rotation = None
        if "rpy" in item:
            rpy = self._numbers(item["rpy"], 3, frame, f"{field}.rpy")
            self._units.angles(rpy, frame, f"{field}.rpy")
            rotation = Pose.from_xyz_rpy(0.0, 0.0, 0.0, *rpy).rotation
        elif "quaternion" in item:
            quaternion = self._numbers(item["quaternion"], 4, frame, f"{field}.quaternion")
            try:
                rotation = Pose(rotation=quaternion).rotation
            except PinframesError as exc:
                raise FileFormatError(exc.message, file=self.path, frame=frame,
                                      field=f"{field}.quaternion") from None
        return rotation, translation

    def _keyframes(self, item: dict, static: tuple[np.ndarray | None, np.ndarray],
                   frame: str, field: str) -> Pose:
        keyframes = item["keyframes"]
        if not isinstance(keyframes, list) or not keyframes:
            raise FileFormatError("expected a non-empty list of keyframes", file=self.path,
                                  frame=frame, field=f"{field}.keyframes")
        times, translations, rotations = [], [], []
        for position, keyframe in enumerate(keyframes):
            where = f"{field}.keyframes[{position}]"
            self._check_keys(keyframe, _KEYFRAME_KEYS, frame, where)
            if "time" not in keyframe:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.time")
            times.append(keyframe["time"])
            rotation, translation = self._pose_parts(
                {"xyz": static[1], **keyframe}, frame, where)
            translations.append(translation)
            if rotation is None:
                rotation = np.eye(3) if static[0] is None else static[0]
            rotations.append(rotation)
        reference = None
        if "reference_time" in item:
            reference = self._timestamp(item["reference_time"], frame,
                                        f"{field}.reference_time")
        try:
            return Pose(np.array(translations), np.array(rotations), times=times,
                        reference_time=reference)
        except PinframesError as exc:
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=f"{field}.keyframes.time") from None

    def _curve(self, item: dict, frame: str, field: str) -> Pose:
        """A frame moving along a polyline (``Pose.along_curve``), given as points or an arc."""
        where = f"{field}.curve"
        curve = item["curve"]
        self._check_keys(curve, _CURVE_KEYS, frame, where)
        if ("points" in curve) == ("arc" in curve):
            raise FileFormatError("give either points (with normals) or arc", file=self.path,
                                  frame=frame, field=where)
        if "points" in curve:
            points = self._vectors(curve["points"], frame, f"{where}.points")
            self._units.lengths(points, frame, f"{where}.points")
            if "normals" not in curve:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.normals")
            normals = curve["normals"]
            normals = (self._numbers(normals, 3, frame, f"{where}.normals")
                       if _is_flat(normals) else
                       self._vectors(normals, frame, f"{where}.normals"))
        else:
            if "normals" in curve:
                raise FileFormatError("an arc's normals point away from its centre; give "
                                      "points for others", file=self.path, frame=frame,
                                      field=f"{where}.normals")
            points, normals = self._arc(curve["arc"], frame, f"{where}.arc")
        timings = [key for key in _CURVE_TIMINGS if key in curve]
        if len(timings) != 1:
            raise FileFormatError("give one of speed (m/s), duration (s) or times",
                                  file=self.path, frame=frame, field=where)
        speed, times = None, curve.get("times")
        if "speed" in curve:
            speed = self._positive(curve["speed"], frame, f"{where}.speed")
        elif "duration" in curve:
            duration = self._positive(curve["duration"], frame, f"{where}.duration")
            speed = float(length_along_polyline(points)[-1]) / duration
        reference = None
        if "reference_time" in item:
            reference = self._timestamp(item["reference_time"], frame,
                                        f"{field}.reference_time")
        try:
            return Pose.along_curve(points, normals, speed=speed, times=times,
                                    reference_time=reference)
        except PinframesError as exc:
            inner = "" if exc.field is None else f".{exc.field}"
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=where + inner) from None

    def _weave(self, item: dict, frame: str, field: str) -> Pose:
        """A frame weaving across its parent's y axis (``Pose.weave``), sampled at ``times``
        or every ``step`` seconds from 0 through ``duration``."""
        where = f"{field}.weave"
        weave = item["weave"]
        self._check_keys(weave, _WEAVE_KEYS, frame, where)
        for key in ("amplitude", "frequency"):
            if key not in weave:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.{key}")
        if ("times" in weave) == ("duration" in weave or "step" in weave):
            raise FileFormatError("give either times or duration (s) with step (s)",
                                  file=self.path, frame=frame, field=where)
        times = weave.get("times")
        if times is None:
            times = self._time_grid(weave, frame, where)
        reference = None
        if "reference_time" in item:
            reference = self._timestamp(item["reference_time"], frame,
                                        f"{field}.reference_time")
        amplitude = self._positive(weave["amplitude"], frame, f"{where}.amplitude")
        frequency = self._positive(weave["frequency"], frame, f"{where}.frequency")
        try:
            return Pose.weave(amplitude, frequency, times=times,
                              pattern=weave.get("pattern", "triangle"),
                              dwell=weave.get("dwell"), reference_time=reference)
        except PinframesError as exc:
            inner = "" if exc.field is None else f".{exc.field}"
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=where + inner) from None

    def _time_grid(self, weave: dict, frame: str, where: str) -> np.ndarray:
        """Times (timedelta64[ns]) every ``step`` seconds from 0 through ``duration``."""
        for key in ("duration", "step"):
            if key not in weave:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.{key}")
        duration_ns = round(self._positive(weave["duration"], frame, f"{where}.duration") * 1e9)
        step_ns = round(self._positive(weave["step"], frame, f"{where}.step") * 1e9)
        if step_ns == 0:
            raise FileFormatError("the step is below a nanosecond", file=self.path,
                                  frame=frame, field=f"{where}.step")
        count = duration_ns // step_ns + 1
        if count > current_limits().max_samples:
            raise exceeded("max_samples", f"the weave has {count:,} samples",
                           field=f"{where}.step", frame=frame).located(file=self.path)
        return (step_ns * np.arange(count, dtype=np.int64)).astype("timedelta64[ns]")

    def _arc(self, arc: Any, frame: str, field: str) -> tuple[np.ndarray, np.ndarray]:
        """Points (count, 3) of a circular arc and their normals, away from its centre."""
        self._check_keys(arc, _ARC_KEYS, frame, field)
        missing = sorted(_ARC_KEYS - set(arc))
        if missing:
            raise FileFormatError("missing", file=self.path, frame=frame,
                                  field=f"{field}.{missing[0]}")
        centre = self._numbers(arc["centre"], 3, frame, f"{field}.centre")
        axis = self._numbers(arc["axis"], 3, frame, f"{field}.axis")
        start = self._numbers(arc["start"], 3, frame, f"{field}.start")
        self._units.lengths(np.stack([centre, start]), frame, field)
        angle = self._number(arc["angle"], frame, f"{field}.angle")
        count = arc["count"]
        if isinstance(count, bool) or not isinstance(count, int) or count < 2:
            raise FileFormatError(f"expected a whole number of points >= 2, got {count!r}",
                                  file=self.path, frame=frame, field=f"{field}.count")
        if count > current_limits().max_samples:
            raise exceeded("max_samples", f"an arc of {count:,} points", frame=frame,
                           field=f"{field}.count").located(file=self.path)
        if not np.linalg.norm(axis) > 0.0:
            raise FileFormatError("the axis must not be zero", file=self.path, frame=frame,
                                  field=f"{field}.axis")
        axis = axis / np.linalg.norm(axis)
        radial = (start - centre) - np.dot(start - centre, axis) * axis
        if not np.linalg.norm(radial) > 0.0 or angle == 0.0:
            raise FileFormatError("the arc has no length: start on the axis or angle 0",
                                  file=self.path, frame=frame, field=field)
        step = angle / (count - 1)
        if abs(step) >= np.pi:
            raise FileFormatError(
                f"the arc turns by {np.degrees(step):g} degrees from point to point, half a "
                "turn or more, so its points do not follow it (whole turns stand still): "
                "give more points (count)", file=self.path, frame=frame, field=field)
        turns = matrix_from_axis_angle(axis, np.linspace(0.0, angle, count))
        points = centre + turns @ (start - centre)
        return points, turns @ (radial / np.linalg.norm(radial))

    # -- field readers ---------------------------------------------------------------------
    def _list(self, key: str) -> list[Any]:
        value = self.content.get(key, [])
        if value is None:
            return []
        if not isinstance(value, list):
            raise FileFormatError(f"expected a list, got {type(value).__name__}",
                                  file=self.path, field=key)
        return value

    def _check_keys(self, item: Any, allowed: set[str], frame: str | None, field: str) -> None:
        if not isinstance(item, dict):
            raise FileFormatError(f"expected a mapping, got {type(item).__name__}",
                                  file=self.path, frame=frame, field=field or None)
        unknown = sorted(str(key) for key in item if key not in allowed)
        if unknown:
            raise FileFormatError(
                f"unknown key(s) {', '.join(unknown)}; expected {', '.join(sorted(allowed))}",
                file=self.path, frame=frame, field=field or None)

    def _frame_names(self, item: Any, kind: str, field: str) -> tuple[str, str]:
        self._check_keys(item, _ENTRY_KEYS[kind], None, field)
        if "name" not in item:
            raise FileFormatError("missing", file=self.path, field=f"{field}.name")
        name = self._name(item["name"], None, f"{field}.name")
        if "parent" not in item:
            raise FileFormatError("missing", file=self.path, frame=name,
                                  field=f"{field}.parent")
        return name, self._name(item["parent"], name, f"{field}.parent")

    def _name(self, value: Any, frame: str | None, field: str) -> str:
        if not isinstance(value, str) or not value:
            raise FileFormatError(f"expected a non-empty string, got {value!r}",
                                  file=self.path, frame=frame, field=field)
        return value

    def _optional_str(self, key: str) -> str | None:
        value = self.content.get(key)
        return None if value is None else self._name(value, None, key)

    def _prefix(self, item: dict, frame: str | None, field: str) -> str:
        prefix = item.get("prefix", "")
        if not isinstance(prefix, str):
            raise FileFormatError(f"expected a string, got {prefix!r}", file=self.path,
                                  frame=frame, field=f"{field}.prefix")
        return prefix

    def _folders(self, item: dict, frame: str | None, field: str) -> list[str]:
        """A robot's ``package_dirs``: folders relative to the scene's."""
        value = item.get("package_dirs", [])
        if not isinstance(value, list):
            raise FileFormatError(f"expected a list of folders, got {type(value).__name__}",
                                  file=self.path, frame=frame, field=f"{field}.package_dirs")
        folders = []
        for index, entry in enumerate(value):
            name = self._name(entry, frame, f"{field}.package_dirs[{index}]")
            folder = self.path.parent / name
            if not folder.is_dir():
                raise FileFormatError(f"no such folder: {folder}", file=self.path, frame=frame,
                                      field=f"{field}.package_dirs[{index}]")
            folders.append(str(folder))
        return folders

    def _xacro_args(self, item: dict, frame: str | None, field: str) -> dict[str, str] | None:
        """A robot's ``xacro_args``: names to text, numbers or booleans."""
        value = item.get("xacro_args")
        if value is None:
            return None
        if not isinstance(value, dict) or not all(
                isinstance(key, str) and isinstance(text, (str, int, float, bool))
                for key, text in value.items()):
            raise FileFormatError("expected a mapping of argument names to text, numbers or "
                                  "booleans", file=self.path, frame=frame,
                                  field=f"{field}.xacro_args")
        return {key: ("true" if text else "false") if isinstance(text, bool) else str(text)
                for key, text in value.items()}

    def _file(self, item: dict, key: str, frame: str | None, field: str) -> Path:
        if key not in item:
            raise FileFormatError("missing", file=self.path, frame=frame, field=f"{field}.{key}")
        value = self._name(item[key], frame, f"{field}.{key}")
        path = self.path.parent / value
        if (problem := regular_file_problem(path)) is not None:
            raise FileFormatError(f"{problem}: {path}", file=self.path, frame=frame,
                                  field=f"{field}.{key}")
        return path

    def _numbers(self, value: Any, count: int, frame: str | None, field: str) -> np.ndarray:
        values = value.tolist() if isinstance(value, np.ndarray) else value
        if (not isinstance(values, (list, tuple)) or len(values) != count
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                           for v in values)):
            raise FileFormatError(f"expected a list of {count} numbers, got {value!r}",
                                  file=self.path, frame=frame, field=field)
        try:
            array = np.array(values, dtype=float)
        except OverflowError:  # an integer too large for a float
            array = np.full(count, np.inf)
        if not np.all(np.isfinite(array)):
            raise FileFormatError("values must be finite", file=self.path, frame=frame,
                                  field=field)
        return array

    def _vectors(self, value: Any, frame: str | None, field: str) -> np.ndarray:
        """A list of [x, y, z] lists as an (N, 3) array."""
        if not isinstance(value, list) or not value:
            raise FileFormatError("expected a non-empty list of [x, y, z] lists",
                                  file=self.path, frame=frame, field=field)
        return np.array([self._numbers(row, 3, frame, f"{field}[{index}]")
                         for index, row in enumerate(value)])

    def _number(self, value: Any, frame: str | None, field: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise FileFormatError(f"expected a number, got {value!r}", file=self.path,
                                  frame=frame, field=field)
        try:
            number = float(value)
        except OverflowError:  # an integer too large for a float
            number = np.inf
        if not np.isfinite(number):
            raise FileFormatError("the value must be finite", file=self.path, frame=frame,
                                  field=field)
        return number

    def _positive(self, value: Any, frame: str | None, field: str) -> float:
        number = self._number(value, frame, field)
        if number <= 0.0:
            raise FileFormatError(f"expected a positive number, got {value!r}",
                                  file=self.path, frame=frame, field=field)
        return number

    def _timestamp(self, value: Any, frame: str | None, field: str) -> np.datetime64:
        try:
            return parse_timestamp(value, field=field)
        except PinframesError as exc:
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=field) from None

    def _referenced(self, exc: PinframesError, field: str) -> PinframesError:
        """``exc`` from a file this scene references, with a note saying which entry (once:
        an error this scene already noted keeps its note)."""
        note = f" (referenced by {self.path}: "
        if note in exc.message:
            return exc
        return type(exc)(f"{exc.message}{note}{field})", file=exc.file, frame=exc.frame,
                         field=exc.field, joint=exc.joint)


def _is_flat(value: Any) -> bool:
    """A list of numbers (one vector), not a list of lists."""
    return isinstance(value, list) and not any(isinstance(item, list) for item in value)


def _graft(tree: FrameTree, layer: FrameTree, mount: str, prefix: str) -> None:
    """Add every frame of ``layer`` to ``tree``; the layer's root becomes ``mount``
    (:meth:`FrameTree.graft`, without a subsystem record: layers need no unique names).

    Moving frames keep their absolute times: a frame that counted from the layer's
    reference time gets that reference time as its own. The layer's tree metadata (what its
    format keeps about the file itself: frames.yaml top-level keys) is not kept: the scene,
    not the layer file, is what the tree was read from (docs/scene-format.md).
    """
    if layer.joints:
        raise UnsupportedFeatureError("layers with robot joints; list robots under 'robots'")
    layer.metadata = {}
    tree.graft(layer, at=mount, prefix=prefix, record=False)
