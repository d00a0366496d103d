"""The file readers the malformed-input corpus runs, and the file name each one reads.

Adding a format is one line here plus its cases in ``file_cases.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pinframes import (
    FrameTree,
    read_asdf,
    read_frames_yaml,
    read_joint_trajectory,
    read_rosbag,
    read_scene,
    read_urdf,
)


@dataclass(frozen=True)
class Reader:
    """A function that reads one file, and the name the corpus gives that file."""

    read: Callable[[Path], Any]
    file_name: str


def _attach_urdf(path: Path) -> FrameTree:
    tree = FrameTree()
    tree.attach_urdf(path, "world")
    return tree


READERS = {
    "frames.yaml": Reader(read_frames_yaml, "frames.yaml"),
    "urdf": Reader(read_urdf, "robot.urdf"),
    "attach_urdf": Reader(_attach_urdf, "robot.urdf"),
    "scene": Reader(read_scene, "scene.yaml"),
    "csv": Reader(read_joint_trajectory, "motion.csv"),
    "npz": Reader(read_joint_trajectory, "motion.npz"),
    "asdf": Reader(read_asdf, "tree.asdf"),
    "rosbag": Reader(read_rosbag, "run.bag"),
}
