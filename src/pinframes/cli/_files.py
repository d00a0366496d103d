"""Reading and writing the CLI's tree files through the format registry (``pinframes.read`` /
``pinframes.write``), with errors that name the command-line options."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from ..errors import FileFormatError, FrameNotFoundError, near_misses
from ..formats import detect_format, file_format, formats_taking, read, write
from ..formats.rosbag import ROSBAG_METADATA_KEY
from ..formats.urdf import URDF_METADATA_KEY, parse_urdf
from ..tree import FrameTree

__all__ = ["read_tree", "require_frames", "write_tree", "xacro_argument"]

_ROBOT_FILE_FORMATS = ("urdf",)
"""Formats whose reader takes ``--srdf`` and ``--xacro-arg`` (a scene names them per robot)."""
_PACKAGE_DIR_FORMATS = ("urdf", "scene")
"""Formats whose reader takes ``--package-dir`` and ``--xacro`` (and remembers the folders
with the robots)."""
_ROBOT_OPTIONS = ("package_dirs", "xacro_args", "srdf", "xacro")
"""Options that go with ``--robot-description`` to the robot file it names."""


def read_tree(path: str | Path, options: argparse.Namespace | None = None) -> FrameTree:
    """Read the tree in ``path``, in the format told from the file, with the command line's
    reading options: ``--robot-description`` (the robot file of a ROS bag),
    ``--package-dir``, ``--xacro-arg``, ``--srdf`` and ``--xacro`` (for URDF and xacro
    files, the robot description, and ``--package-dir`` and ``--xacro`` for scenes)."""
    given: dict[str, Any] = {"robot_description": getattr(options, "robot_description", None),
             "package_dirs": getattr(options, "package_dir", None) or [],
             "xacro_args": dict(getattr(options, "xacro_arg", None) or []),
             "srdf": getattr(options, "srdf", None),
             "xacro": True if getattr(options, "xacro", None) else None}
    taken = {name: value for name, value in given.items() if value}
    if not taken:
        tree: FrameTree = read(path)
        return tree
    fmt = detect_format(path)
    if "robot_description" in taken:
        if fmt != "rosbag":
            raise FileFormatError("--robot-description is for ROS bags", file=path)
        robot = {name: taken.pop(name) for name in _ROBOT_OPTIONS if name in taken}
        taken["robot_description"] = parse_urdf(taken["robot_description"], **robot)
    for name in ("xacro_args", "srdf", "xacro"):
        takers = _PACKAGE_DIR_FORMATS if name == "xacro" else _ROBOT_FILE_FORMATS
        if name in taken and fmt not in takers:
            flag = {"xacro_args": "--xacro-arg", "srdf": "--srdf", "xacro": "--xacro"}[name]
            raise FileFormatError(f"{flag} is for URDF and xacro files and --robot-description"
                                  + (", and scenes" if name == "xacro" else
                                     f" (a scene names it in its robots' entries: {name})"),
                                  file=path)
    if fmt not in _PACKAGE_DIR_FORMATS:
        taken.pop("package_dirs", None)
    tree = read(path, **taken)
    return tree


def xacro_argument(text: str) -> tuple[str, str]:
    """``NAME:=VALUE`` (``--xacro-arg``) as ``(NAME, VALUE)``."""
    name, separator, value = text.partition(":=")
    if not separator or not name:
        raise argparse.ArgumentTypeError(f"expected NAME:=VALUE, got {text!r}")
    return name, value


def require_frames(tree: FrameTree, path: str | Path, *names: str | None) -> None:
    """Raise a :class:`FrameNotFoundError` naming ``path`` for a name not in ``tree``; for
    a ROS bag read without a robot, it says how to give one."""
    for name in names:
        if name is not None and name not in tree:
            robot = ""
            if ROSBAG_METADATA_KEY in tree.metadata and URDF_METADATA_KEY not in tree.metadata:
                robot = ("; the bag has no robot description (/robot_description), so only "
                         "the frames of its tf messages are here: give the robot's URDF with "
                         "--robot-description URDF for its links")
            raise FrameNotFoundError("no frame of this name in the file"
                                     + near_misses(name, tree.frames) + robot, file=path,
                                     frame=name)


def write_tree(tree: FrameTree, path: str | Path, fmt: str | None = None, **flags: Any
               ) -> None:
    """Write ``tree`` to ``path`` in ``fmt`` (default: told from the name), atomically.

    ``flags`` are the command line's options by name (``schema``, ``time``); those not given
    are None. An option the format does not take names the flag and the formats that do.
    """
    fmt = fmt or detect_format(path, writing=True)
    options = {name: value for name, value in flags.items() if value is not None}
    taken = file_format(fmt).write_options
    for name in options:
        if name not in taken:
            takers = ", ".join(entry.title for entry in formats_taking(name))
            flag = "--" + name.replace("_", "-")
            raise FileFormatError(f"{flag} is for {takers} files, not {fmt}", file=path)
    write(tree, path, fmt, **options)
