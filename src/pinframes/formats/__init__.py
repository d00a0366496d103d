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
    Peek,
    detect_format,
    file_format,
    formats_taking,
    read,
    register_format,
    registered_formats,
    write,
)
from .frames_yaml import read_frames_yaml, write_frames_yaml
from .rosbag import read_rosbag
from .scene import SCENE_FORMAT_KEY, read_scene, write_scene
from .trajectory_files import (
    JOINT_TRAJECTORY,
    read_csv_trajectory,
    read_joint_trajectory,
    read_npz_trajectory,
)
from .urdf import mount_urdf, write_urdf
from .urdf_files import read_urdf

__all__ = [
    "FileFormat",
    "Peek",
    "detect_format",
    "file_format",
    "formats_taking",
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


def _named_frames(peek: Peek) -> bool:
    return peek.path.name.lower().startswith("frames")


def _is_scene(peek: Peek, writing: bool) -> bool:
    if writing:
        return not _named_frames(peek)
    content = peek.yaml()
    return isinstance(content, dict) and SCENE_FORMAT_KEY in content


def _is_frames_yaml(peek: Peek, writing: bool) -> bool:
    if writing or _named_frames(peek):
        return _named_frames(peek)
    content = peek.yaml()
    return isinstance(content, dict) and "frames" in content


def _is_bag(peek: Peek, writing: bool) -> bool:
    """A ROS 2 bag folder has its metadata.yaml (bag files are told by content)."""
    return not peek.path.is_dir() or (peek.path / "metadata.yaml").is_file()


register_format(FileFormat("asdf", "ASDF", (".asdf",), _read_asdf, _write_asdf,
                           ("schema", "key")))
register_format(FileFormat("urdf", "URDF", (".urdf",), read_urdf, write_urdf,
                           ("time", "freeze_joints")))
# .yaml: a scene when it has the scene key; else a frames.yaml ('frames' key or name)
register_format(FileFormat("scene", "scene", (".yaml", ".yml"), read_scene, write_scene,
                           ("time",), _is_scene, f"no '{SCENE_FORMAT_KEY}' key"))
register_format(FileFormat("frames.yaml", "frames.yaml", (".yaml", ".yml"), read_frames_yaml,
                           write_frames_yaml, ("time", "slash_replacement"), _is_frames_yaml,
                           "no 'frames' key"))
register_format(FileFormat("csv", "CSV", (".csv",), read_csv_trajectory,
                           kind=JOINT_TRAJECTORY))
register_format(FileFormat("npz", "NPZ", (".npz",), read_npz_trajectory,
                           kind=JOINT_TRAJECTORY))
# ROS bags: files told by their magic bytes (formats/_content.py), ROS 2 bag folders by
# their metadata.yaml; read with rosbags (the [ros] extra), never written
register_format(FileFormat("rosbag", "ROS bag", (".bag", ".mcap", ".db3"), read_rosbag,
                           recognise=_is_bag, folders=True,
                           unrecognised="a ROS 2 bag folder holds a metadata.yaml"))
register_robot_format("urdf", mount_urdf)
