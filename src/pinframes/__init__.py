"""pinframes: coordinate-frame hierarchies that move in time, backed by Pinocchio."""

from .errors import (
    ArgumentTypeError,
    ExtrapolationError,
    FileFormatError,
    FrameExistsError,
    FrameNotFoundError,
    InvalidPoseError,
    InvalidTimeError,
    JointError,
    JointWithoutSamplesWarning,
    PinframesError,
    ReadError,
    ReferenceTimeError,
    TreeStructureError,
    UnsupportedFeatureError,
    WriteError,
)
from .joint import Joint, Mimic
from .joint_track import JointTrack
from .pinocchio_tree import PinocchioTree
from .pose import Pose
from .pose_files import write_poses
from .scene import read_scene
from .scene_writer import write_scene
from .subsystem import Subsystem
from .trajectory_io import read_joint_trajectory
from .tree import FrameTree
from .urdf import BrokenMimicWarning, read_urdf, write_urdf

__version__ = "0.1.0"

__all__ = [
    "ArgumentTypeError",
    "BrokenMimicWarning",
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
    "JointWithoutSamplesWarning",
    "Mimic",
    "PinframesError",
    "PinocchioTree",
    "Pose",
    "ReadError",
    "ReferenceTimeError",
    "Subsystem",
    "TreeStructureError",
    "UnsupportedFeatureError",
    "WriteError",
    "__version__",
    "read_joint_trajectory",
    "read_scene",
    "read_urdf",
    "write_poses",
    "write_scene",
    "write_urdf",
]

from .frames_yaml import FramesYamlWarning, read_frames_yaml, write_frames_yaml

__all__ += ["FramesYamlWarning", "read_frames_yaml", "write_frames_yaml"]

# The ASDF functions load the asdf package: they are imported on first use.
_ASDF_FUNCTIONS = ("read_asdf", "write_asdf")
__all__ += list(_ASDF_FUNCTIONS)


def __getattr__(name: str) -> object:
    if name in _ASDF_FUNCTIONS:
        from . import asdf as _asdf_format

        return getattr(_asdf_format, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
