"""URDF in and out: robots as frames and joints of a :class:`~pinframes.FrameTree`, and
the URDF format of the registry (a URDF with its joint values beside it)."""

from ._format import URDF_FORMAT, read_urdf
from ._mount import DRIVEN_JOINT_TYPES, URDF_METADATA_KEY, mount_robot, mount_urdf
from ._parse import JointDescription, RobotDescription, is_urdf, parse_urdf
from ._read_write import joint_state_path, read_robot, write_urdf

__all__ = [
    "DRIVEN_JOINT_TYPES",
    "URDF_FORMAT",
    "URDF_METADATA_KEY",
    "JointDescription",
    "RobotDescription",
    "is_urdf",
    "joint_state_path",
    "mount_robot",
    "mount_urdf",
    "parse_urdf",
    "read_robot",
    "read_urdf",
    "write_urdf",
]
