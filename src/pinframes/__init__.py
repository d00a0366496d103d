"""pinframes: coordinate-frame hierarchies that move in time, backed by Pinocchio."""

from .errors import (
    ExtrapolationError,
    FileFormatError,
    FrameExistsError,
    FrameNotFoundError,
    InvalidPoseError,
    InvalidTimeError,
    JointError,
    PinframesError,
    ReferenceTimeError,
    TreeStructureError,
    UnsupportedFeatureError,
    WriteError,
)
from .joint import Joint, Mimic
from .joint_track import JointTrack
from .pinocchio_tree import PinocchioTree
from .pose import Pose
from .subsystem import Subsystem
from .tree import FrameTree

__version__ = "0.1.0"

__all__ = [
    "ExtrapolationError",
    "FileFormatError",
    "FrameExistsError",
    "FrameNotFoundError",
    "FrameTree",
    "InvalidPoseError",
    "InvalidTimeError",
    "Joint",
    "JointError",
    "JointTrack",
    "Mimic",
    "PinframesError",
    "PinocchioTree",
    "Pose",
    "ReferenceTimeError",
    "Subsystem",
    "TreeStructureError",
    "UnsupportedFeatureError",
    "WriteError",
    "__version__",
]

from .frames_yaml import FramesYamlWarning, read_frames_yaml, write_frames_yaml

__all__ += ["FramesYamlWarning", "read_frames_yaml", "write_frames_yaml"]
