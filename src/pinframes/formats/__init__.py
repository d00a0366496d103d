"""Formats: reading and writing trees (and joint trajectories) in files, through one table.

:func:`read` and :func:`write` pick the format from the file (:func:`detect_format`); each
format (a folder each: ``asdf/``, ``urdf/``, ``joint_trajectory/``, ``tables/``...) is
registered below; what every format stands on is here. ASDF is loaded on first use (it
imports the asdf package).
The URDF mounter is registered with the tree, so that ``FrameTree.attach_urdf`` works
without the tree importing this layer.
"""

from __future__ import annotations

from ..tree import register_robot_format
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
from .asdf import ASDF_FORMAT
from .frames_yaml import FRAMES_YAML_FORMAT
from .joint_trajectory import CSV_TRAJECTORY_FORMAT, NPZ_TRAJECTORY_FORMAT, read_joint_trajectory
from .reading import InputFile
from .rosbag import ROSBAG_FORMAT
from .scene import SCENE_FORMAT
from .tables import POINT_TABLE_FORMAT, POSE_FORMATS
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


# Content tests are asked in this order: a pose file's and a point table's before a joint
# trajectory's.
for _format in (
    ASDF_FORMAT,
    URDF_FORMAT,
    SCENE_FORMAT,
    FRAMES_YAML_FORMAT,
    ROSBAG_FORMAT,
    *POSE_FORMATS,
    POINT_TABLE_FORMAT,
    CSV_TRAJECTORY_FORMAT,
    NPZ_TRAJECTORY_FORMAT,
):
    register_format(_format)
register_robot_format("urdf", mount_urdf)
