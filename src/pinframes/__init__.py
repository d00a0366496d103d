"""pinframes: coordinate-frame hierarchies that move in time, backed by Pinocchio."""

from .errors import (
    ArgumentTypeError,
    BagWarning,
    BrokenMimicWarning,
    CollisionError,
    DataNotFoundError,
    ExtrapolationError,
    ExtrapolationWarning,
    FileFormatError,
    FrameExistsError,
    FrameNotFoundError,
    FramesYamlWarning,
    GeometryError,
    GeometryWarning,
    InvalidDataError,
    InvalidPoseError,
    InvalidTimeError,
    JointError,
    JointJumpError,
    JointLimitWarning,
    JointNotFoundError,
    JointSpeedError,
    JointWithoutSamplesWarning,
    NameNotFoundError,
    PinframesError,
    ReadError,
    ReferenceTimeError,
    SrdfWarning,
    TargetNotReachedError,
    TreeStructureError,
    UnitWarning,
    UnsupportedFeatureError,
    WriteError,
)
from .formats import read, read_joint_trajectory, write
from .formats.frames_yaml import read_frames_yaml, write_frames_yaml
from .formats.joint_limits import read_joint_limits
from .formats.joint_trajectory_writer import write_joint_trajectory
from .formats.limits import Limits
from .formats.rosbag import read_rosbag
from .formats.scene import read_program, read_scene, write_scene
from .formats.tables import write_poses
from .formats.urdf import read_urdf, write_urdf
from .kinematics import (
    Clearance,
    FrameJacobian,
    IkSolutions,
    JointSolution,
    PinocchioTree,
    Snapshot,
    Velocity,
    WeldProcess,
)
from .program import WeldProgram
from .tree import FrameTree
from .values.geometry import FrameGeometry, Shape
from .values.joint import Joint, Mimic
from .values.joint_rate_limits import JointRateLimits
from .values.joint_trajectory import JointTrack, JointTrajectory
from .values.motion import CollisionRecord, Motion, MoveRecord
from .values.pose import Pose
from .values.pose_stack import PoseStack
from .values.shapes import Box, Cylinder, Mesh, Sphere
from .values.spatial_data import SpatialData
from .values.subsystem import Subsystem
from .values.timeconv import TimeAxis
from .values.weave import Weave

__version__ = "0.1.0"

__all__ = [
    "ArgumentTypeError",
    "BagWarning",
    "Box",
    "BrokenMimicWarning",
    "Clearance",
    "CollisionError",
    "CollisionRecord",
    "Cylinder",
    "DataNotFoundError",
    "ExtrapolationError",
    "ExtrapolationWarning",
    "FileFormatError",
    "FrameExistsError",
    "FrameGeometry",
    "FrameJacobian",
    "FrameNotFoundError",
    "FrameTree",
    "FramesYamlWarning",
    "GeometryError",
    "GeometryWarning",
    "IkSolutions",
    "InvalidDataError",
    "InvalidPoseError",
    "InvalidTimeError",
    "Joint",
    "JointError",
    "JointJumpError",
    "JointLimitWarning",
    "JointNotFoundError",
    "JointRateLimits",
    "JointSolution",
    "JointSpeedError",
    "JointTrack",
    "JointTrajectory",
    "JointWithoutSamplesWarning",
    "Limits",
    "Mesh",
    "Mimic",
    "Motion",
    "MoveRecord",
    "NameNotFoundError",
    "PinframesError",
    "PinocchioTree",
    "Pose",
    "PoseStack",
    "ReadError",
    "ReferenceTimeError",
    "Shape",
    "Snapshot",
    "SpatialData",
    "Sphere",
    "SrdfWarning",
    "Subsystem",
    "TargetNotReachedError",
    "TimeAxis",
    "TreeStructureError",
    "UnitWarning",
    "UnsupportedFeatureError",
    "Velocity",
    "Weave",
    "WeldProcess",
    "WeldProgram",
    "WriteError",
    "__version__",
    "read",
    "read_frames_yaml",
    "read_joint_limits",
    "read_joint_trajectory",
    "read_program",
    "read_rosbag",
    "read_scene",
    "read_urdf",
    "write",
    "write_frames_yaml",
    "write_joint_trajectory",
    "write_poses",
    "write_scene",
    "write_urdf",
]

# The ASDF functions load the asdf package: they are imported on first use.
_ASDF_FUNCTIONS = ("read_asdf", "write_asdf")
__all__ += list(_ASDF_FUNCTIONS)


def __getattr__(name: str) -> object:
    if name in _ASDF_FUNCTIONS:
        from .formats import asdf as _asdf_format

        return getattr(_asdf_format, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
