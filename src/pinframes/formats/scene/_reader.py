"""Reading scene files: one YAML file that puts a whole cell together.

A scene combines frame layers (``frames.yaml`` files and ASDF hierarchies), inline frames,
robots (URDF files with joint trajectories) and tool frames into one :class:`FrameTree`.
The format is described in ``docs/scene-format.md``; in short::

    pinframes_scene: 1
    root: world
    layers:  [{file: cell.frames.yaml, mount: world}]
    frames:  [{name: table, parent: world, xyz: [1, 0, 0.8], rpy: [0, 0, 0],
               geometry: [{box: {size: [1.2, 0.8, 0.05]}}]}]
    robots:  [{urdf: ur.urdf.xacro, parent: table, prefix: "robot/", trajectory: motion.csv,
               srdf: robot.srdf, package_dirs: [meshes], xacro: true,
               xacro_args: {ur_type: ur5e}}]
    tools:   [{name: tcp, parent: robot/flange, xyz: [0, 0, 0.2]}]
    program: {tool: tcp, limits: {joint_1: {acceleration: 5}, ...},
              moves: [{move_joints: home}, {weld: seam_point, torch: torch_target}]}

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
from ...values.pose import Pose
from .._registry import detect_format, read, require_format
from ..joint_trajectory import read_joint_trajectory
from ..limits import Limits, reader_with_limits
from ..reading import InputFile
from ..urdf import RobotDescription, mount_robot, parse_urdf
from ._fields import SceneFields
from ._geometry import add_geometry, read_geometry
from ._motion import POSE_KEYS, SceneMotion
from ._recognise import LAYER_FORMATS, SCENE_FORMAT_KEY, SCENE_FORMAT_VERSION, TOP_KEYS
from ._unit_check import UnitCheck
from .program_section import PROGRAM_METADATA_KEY, read_program_section

__all__ = ["read_scene"]

_ENTRY_KEYS = {
    "layers": {"file", "mount", "prefix", "key"},
    "frames": {"name", "parent", "keyframes", "curve", "weave", "reference_time",
               "geometry"} | POSE_KEYS,
    "robots": {"name", "urdf", "parent", "prefix", "trajectory", "srdf", "package_dirs",
               "xacro_args", "xacro"} | POSE_KEYS,
    "tools": {"name", "parent", "geometry"} | POSE_KEYS,
}


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
               package_dirs: Iterable[str | os.PathLike[str]] = (),
               xacro: bool | None = None) -> FrameTree:
    """Read a scene file into a new :class:`FrameTree`.

    ``limits`` (:class:`pinframes.Limits`) bounds the scene file and every file it names.
    ``package_dirs`` are searched for every robot's ``$(find PKG)``, ``package://`` and
    ``model://`` names, after the folders its entry names (``package_dirs:``).

    A robot's xacro file (and xacro SRDF) is expanded, which runs the file's code, only when
    its entry says ``xacro: true`` or ``xacro=True`` is given here (``--xacro``); with
    ``xacro=False`` no entry is expanded, whatever it says. Xacro content not expanded is a
    ``FileFormatError`` naming the entry.

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
    scene = _Scene(InputFile.of(path), tuple(os.fspath(folder) for folder in package_dirs),
                   xacro)
    return scene.build()


class _Scene:
    """The parsed content of one scene file, and how to build its tree.

    Each file the scene names is read once, however many entries name it (through YAML
    aliases, say): a trajectory, a URDF, a layer (with its key).
    """

    def __init__(self, source: InputFile, package_dirs: tuple[str, ...] = (),
                 xacro: bool | None = None) -> None:
        path = source.path
        self.path = path
        self.package_dirs = package_dirs
        self.xacro = xacro
        self._read: dict[tuple[str, Path, str], Any] = {}
        # trajectory columns no robot took: (name, prefix, file, field), checked at the end
        self._left: list[tuple[str, str, Path, str]] = []
        self._taken: set[tuple[Path, str]] = set()  # (file, column) some robot took
        self.fields = SceneFields(path)
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
        self.fields.check_keys(content, TOP_KEYS, None, "")
        self.content = content
        self._units = UnitCheck(path)
        self.motion = SceneMotion(self.fields, self._units)
        self.root = self.fields.name(content.get("root", "world"), None, "root")

    # -- building --------------------------------------------------------------------------
    def build(self) -> FrameTree:
        """A fresh tree with every entry added; nothing is returned half-built."""
        program = (read_program_section(self.content["program"], self.fields)
                   if "program" in self.content else None)
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
        self._check_left(tree)
        self._units.warn()
        if program is not None:
            tree.metadata[PROGRAM_METADATA_KEY] = program
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
            return self.fields.timestamp(self.content["reference_time"], None, "reference_time")
        references = [layer.reference_time for _, layer in layers
                      if layer.reference_time is not None]
        return min(references) if references else None

    # -- entries ---------------------------------------------------------------------------
    def _layer(self, index: int, item: Any) -> tuple[_Entry, FrameTree]:
        field = f"layers[{index}]"
        self.fields.check_keys(item, _ENTRY_KEYS["layers"], None, field)
        file = self.fields.file(item, "file", None, field)
        mount = self.fields.name(item.get("mount", self.root), None, f"{field}.mount")
        prefix = self.fields.prefix(item, None, field)
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
            layer_format = detect_format(source, among=LAYER_FORMATS)
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
        static = self.motion.pose_parts(item, name, field)
        rotation, translation = static
        pose = Pose(translation, rotation)
        if "keyframes" in item and "curve" in item:
            raise FileFormatError("give either keyframes or curve, not both", file=self.path,
                                  frame=name, field=f"{field}.curve")
        if "weave" in item:
            if {"keyframes", "curve"} & set(item) or POSE_KEYS & set(item):
                raise FileFormatError("a weave frame takes its pose from the weave: no "
                                      "keyframes, curve, xyz, rpy or quaternion",
                                      file=self.path, frame=name, field=f"{field}.weave")
            pose = self.motion.weave(item, name, field)
        elif "curve" in item:
            if POSE_KEYS & set(item):
                raise FileFormatError("a curve frame takes its pose from the curve: no xyz, "
                                      "rpy or quaternion", file=self.path, frame=name,
                                      field=f"{field}.curve")
            pose = self.motion.curve(item, name, field)
        elif "keyframes" in item:
            pose = self.motion.keyframes(item, static, name, field)
        elif "reference_time" in item:
            raise FileFormatError("a reference_time needs keyframes, a curve or a weave",
                                  file=self.path, frame=name, field=f"{field}.reference_time")
        return self._inline(item, name, parent, pose, field)

    def _tool(self, index: int, item: Any) -> _Entry:
        field = f"tools[{index}]"
        name, parent = self._frame_names(item, "tools", field)
        rotation, translation = self.motion.pose_parts(item, name, field)
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
        self.fields.check_keys(item, _ENTRY_KEYS["robots"], None, field)
        label = self.fields.name(item["name"], None, f"{field}.name") if "name" in item else None
        urdf = self.fields.file(item, "urdf", label, field)
        parent = self.fields.name(item.get("parent", self.root), label, f"{field}.parent")
        prefix = self.fields.prefix(item, label, field)
        rotation, translation = self.motion.pose_parts(item, label, field)
        pose = Pose(translation, rotation)
        srdf = self.fields.file(item, "srdf", label, field) if "srdf" in item else None
        package_dirs = [*self.fields.folders(item, label, field), *self.package_dirs]
        xacro_args = self.fields.xacro_args(item, label, field)
        xacro = self.xacro if self.xacro is not None else self.fields.flag(item, "xacro",
                                                                           label, field)
        trajectory, path = None, urdf
        if "trajectory" in item:
            path = self.fields.file(item, "trajectory", label, field)
            try:
                trajectory = self._once("trajectory", path, None,
                                        lambda: read_joint_trajectory(path))
            except PinframesError as exc:
                raise self._referenced(exc, f"{field}.trajectory") from None

        def attach(tree: FrameTree) -> None:
            try:
                robot: RobotDescription = self._once(
                    "urdf", urdf, (srdf, package_dirs, xacro_args, xacro),
                    lambda: parse_urdf(str(urdf), package_dirs=package_dirs,
                                       xacro_args=xacro_args, srdf=srdf, xacro=xacro))
                mount_robot(tree, robot, parent, pose, prefix)  # FrameTree.attach_urdf
            except PinframesError as exc:
                if exc.file is None:
                    raise  # a clash with the scene, located at this entry by _apply
                named = "srdf" if srdf is not None and exc.file == str(srdf) else "urdf"
                raise self._referenced(exc, f"{field}.{named}") from None
            if trajectory is not None:
                self._drive(tree, trajectory, prefix, {joint.name for joint in robot.joints},
                            path, f"{field}.trajectory")

        return _Entry(field, label, parent, f"{field}.parent", attach)

    def _drive(self, tree: FrameTree, trajectory: tuple[np.ndarray, np.ndarray, list[str]],
               prefix: str, own: set[str], path: Path, field: str) -> None:
        """Drive the robot of ``prefix`` (its joints ``own``, unprefixed) by the columns of
        ``trajectory`` that name its joints, with or without the prefix; the other columns
        are left to other robots (a file ``solve`` wrote for a robot and a positioner,
        which each robot's ``trajectory`` may name), checked once the scene is built."""
        times, positions, names = trajectory
        columns = [column for column, name in enumerate(names)
                   if name in own or (name.startswith(prefix) and name[len(prefix):] in own)]
        self._left.extend((name, prefix, path, field) for column, name in enumerate(names)
                          if column not in columns)
        self._taken.update((path, names[column]) for column in columns)
        if not columns:
            return
        taken = [prefix + names[column] if names[column] in own else names[column]
                 for column in columns]
        try:
            tree.set_joint_trajectory(times, positions[:, columns], taken)
        except PinframesError as exc:
            raise self._referenced(exc.located(file=path), field) from None

    def _check_left(self, tree: FrameTree) -> None:
        """Every trajectory column that a robot left is another robot's or names a joint of
        the built tree."""
        joints = tree.joints
        for name, prefix, path, field in self._left:
            if (path, name) not in self._taken and name not in joints:
                known = ", ".join(sorted(joints)) or "none"
                also = f" nor {name!r}" if prefix else ""
                raise self._referenced(FileFormatError(
                    f"no joint {prefix + name!r}{also} in the tree (joints: {known})",
                    file=path, joint=name, field="header"), field)

    # -- the scene's own fields ------------------------------------------------------------
    def _list(self, key: str) -> list[Any]:
        value = self.content.get(key, [])
        if value is None:
            return []
        if not isinstance(value, list):
            raise FileFormatError(f"expected a list, got {type(value).__name__}",
                                  file=self.path, field=key)
        return value

    def _frame_names(self, item: Any, kind: str, field: str) -> tuple[str, str]:
        self.fields.check_keys(item, _ENTRY_KEYS[kind], None, field)
        if "name" not in item:
            raise FileFormatError("missing", file=self.path, field=f"{field}.name")
        name = self.fields.name(item["name"], None, f"{field}.name")
        if "parent" not in item:
            raise FileFormatError("missing", file=self.path, frame=name,
                                  field=f"{field}.parent")
        return name, self.fields.name(item["parent"], name, f"{field}.parent")

    def _optional_str(self, key: str) -> str | None:
        value = self.content.get(key)
        return None if value is None else self.fields.name(value, None, key)

    def _referenced(self, exc: PinframesError, field: str) -> PinframesError:
        """``exc`` from a file this scene references, with a note saying which entry (once:
        an error this scene already noted keeps its note)."""
        note = f" (referenced by {self.path}: "
        if note in exc.message:
            return exc
        return type(exc)(f"{exc.message}{note}{field})", file=exc.file, frame=exc.frame,
                         field=exc.field, joint=exc.joint)


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
