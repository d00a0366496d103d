"""The tree: :class:`FrameTree`, which owns the frames and hands queries to the kinematics."""

from ._robot_formats import register_robot_format
from .frame_tree import FrameTree

__all__ = ["FrameTree", "register_robot_format"]
