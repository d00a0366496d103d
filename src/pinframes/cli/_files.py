"""Reading and writing the CLI's tree files through the format registry (``pinframes.read`` /
``pinframes.write``), with errors that name the command-line options."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..errors import FileFormatError, FrameNotFoundError, near_misses
from ..formats import detect_format, file_format, formats_taking, read, write
from ..formats.rosbag import ROSBAG_METADATA_KEY
from ..formats.urdf import URDF_METADATA_KEY
from ..tree import FrameTree

__all__ = ["read_tree", "require_frames", "write_tree"]


def read_tree(path: str | Path, robot_description: str | None = None) -> FrameTree:
    """Read the tree in ``path``, in the format told from the file; ``robot_description``
    (``--robot-description``) is the URDF of the robot in a ROS bag."""
    if robot_description is None:
        tree: FrameTree = read(path)
        return tree
    if detect_format(path) != "rosbag":
        raise FileFormatError("--robot-description is for ROS bags", file=path)
    tree = read(path, robot_description=robot_description)
    return tree


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
