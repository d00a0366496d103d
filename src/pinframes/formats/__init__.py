"""Formats: reading and writing trees (and joint trajectories) in files, through one table.

:func:`read` and :func:`write` pick the format from the file (:func:`detect_format`); each
format registers itself below. ASDF is loaded on first use (it imports the asdf package).
The URDF mounter is registered with the tree, so that ``FrameTree.attach_urdf`` works
without the tree importing this layer.
"""

from __future__ import annotations

import os
from typing import Any

from ..tree import FrameTree, register_robot_format
from ._registry import (
    FileFormat,
    detect_format,
    file_format,
    files_read,
    formats_taking,
    is_tree_folder,
    read,
    register_format,
    registered_formats,
    write,
)
from .frames_yaml import FRAMES_YAML_FORMAT
from .pose_files import POSE_FORMATS
from .reading import InputFile
from .rosbag import ROSBAG_FORMAT
from .scene import SCENE_FORMAT
from .trajectory_files import CSV_TRAJECTORY_FORMAT, NPZ_TRAJECTORY_FORMAT, read_joint_trajectory
from .urdf import URDF_FORMAT, mount_urdf

__all__ = [
    "FileFormat",
    "InputFile",
    "detect_format",
    "file_format",
    "files_read",
    "formats_taking",
    "is_tree_folder",
    "read",
    "read_joint_trajectory",
    "register_format",
    "registered_formats",
    "write",
]


def _read_asdf(path: str | os.PathLike[str], **options: Any) -> FrameTree:
    from .asdf import read_asdf

    return read_asdf(path, **options)


def _write_asdf(tree: FrameTree, path: str | os.PathLike[str], **options: Any) -> None:
    from .asdf import write_asdf

    write_asdf(tree, path, **options)


def _is_asdf(source: InputFile) -> bool:
    """ASDF's content test: the file starts with ``#ASDF`` (here, so that telling a file's
    format does not import asdf)."""
    return source.start().startswith(b"#ASDF")


def _is_point_table(source: InputFile) -> bool:
    """A CSV table of points as ``pinframes transform`` reads and writes them: a header of
    ``x``, ``y``, ``z`` columns (each may name its unit: ``x_mm``), perhaps after a time
    and a point column."""
    lines = [line for line in source.start().split(b"\n") if line.strip()]
    if not lines:
        return False
    cells = [cell.strip().decode("utf-8", "replace") for cell in lines[0].split(b",")]
    data = [cell for cell in cells if cell not in ("time_s", "time", "point")]
    return len(data) == 3 and all(cell == axis or cell.startswith(axis + "_")
                                  for cell, axis in zip(data, "xyz", strict=True))


# Content tests are asked in this order: a pose file's and a point table's before a joint
# trajectory's.
for _format in (
    FileFormat("asdf", "ASDF", (".asdf",), _read_asdf, _write_asdf, ("schema", "key"),
               head_test=_is_asdf, looks_like="an ASDF file"),
    URDF_FORMAT,
    SCENE_FORMAT,
    FRAMES_YAML_FORMAT,
    ROSBAG_FORMAT,
    *POSE_FORMATS,
    FileFormat("csv", "CSV", (".csv",), kind="points", head_test=_is_point_table,
               looks_like="a CSV table of points (x, y, z columns), which 'pinframes "
               "transform' takes"),
    CSV_TRAJECTORY_FORMAT,
    NPZ_TRAJECTORY_FORMAT,
):
    register_format(_format)
register_robot_format("urdf", mount_urdf)
