"""Joint trajectories in files: joint values over time, read from CSV or NPZ
(``_files``: the two registry formats and the one joint CSV writer, which the URDF writer
uses too). ``formats.joint_trajectory_writer`` writes them, or a ROS bag.
"""

from ._files import (
    CSV_TRAJECTORY_FORMAT,
    NPZ_TRAJECTORY_FORMAT,
    joint_trajectory_csv,
    read_joint_trajectory,
)

__all__ = ["CSV_TRAJECTORY_FORMAT", "NPZ_TRAJECTORY_FORMAT",
           "joint_trajectory_csv", "read_joint_trajectory"]
