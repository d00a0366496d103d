"""URDF in and out: robots as frames and joints of a :class:`~pinframes.FrameTree`, from
URDF or xacro files with their SRDF, and the URDF format of the registry (a URDF with its
joint values beside it)."""

from ...tree.urdf_names import URDF_METADATA_KEY
from ._format import URDF_FORMAT, read_urdf
from ._mount import DRIVEN_JOINT_TYPES, mount_robot, mount_urdf
from ._parse import is_urdf, parse_urdf
from ._read_write import (
    joint_state_path,
    read_robot,
    robot_links,
    robot_urdf,
    shapes_urdf,
    write_urdf,
)
from ._robot_description import JointDescription, RobotDescription
from ._srdf import read_srdf
from ._xacro import expand_xacro, is_xacro

__all__ = [
    "DRIVEN_JOINT_TYPES",
    "URDF_FORMAT",
    "URDF_METADATA_KEY",
    "JointDescription",
    "RobotDescription",
    "expand_xacro",
    "is_urdf",
    "is_xacro",
    "joint_state_path",
    "mount_robot",
    "mount_urdf",
    "parse_urdf",
    "read_robot",
    "read_srdf",
    "read_urdf",
    "robot_links",
    "robot_urdf",
    "shapes_urdf",
    "write_urdf",
]
