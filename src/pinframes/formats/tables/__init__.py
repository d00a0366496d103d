"""Tables of results: poses (with their velocities) in CSV, JSON or NPZ (``pose_files``),
a clearance in CSV or JSON (``clearance_files``), and the point tables of ``pinframes
transform`` (``_points``, a content test only)."""

from ._points import POINT_TABLE_FORMAT
from .clearance_files import CLEARANCE_FILE_FORMATS, clearance_text
from .pose_files import (
    COLUMNS,
    POSE_FILE_FORMATS,
    POSE_FORMATS,
    VELOCITY_COLUMNS,
    pose_file_format,
    poses_text,
    write_poses,
)

__all__ = ["CLEARANCE_FILE_FORMATS", "COLUMNS", "POINT_TABLE_FORMAT", "POSE_FILE_FORMATS",
           "POSE_FORMATS", "VELOCITY_COLUMNS", "clearance_text", "pose_file_format",
           "poses_text", "write_poses"]
