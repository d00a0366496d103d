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

__version__ = "0.1.0"

__all__ = [
    "ExtrapolationError",
    "FileFormatError",
    "FrameExistsError",
    "FrameNotFoundError",
    "InvalidPoseError",
    "InvalidTimeError",
    "JointError",
    "PinframesError",
    "ReferenceTimeError",
    "TreeStructureError",
    "UnsupportedFeatureError",
    "WriteError",
    "__version__",
]
