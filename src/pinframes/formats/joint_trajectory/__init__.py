"""Joint trajectories in files: joint values over time, read from CSV or NPZ
(``_files``: the two registry formats and the one joint CSV writer) and written to CSV, NPZ
or a ROS bag (:mod:`.writer`).

The writer is a public module of its own, not named here: it reads the URDF robots' joint
names (``formats.urdf``), whose writer in turn writes joint values with
:func:`joint_trajectory_csv`.
"""

from ._files import (
    CSV_TRAJECTORY_FORMAT,
    NPZ_TRAJECTORY_FORMAT,
    joint_trajectory_csv,
    read_joint_trajectory,
)

__all__ = ["CSV_TRAJECTORY_FORMAT", "NPZ_TRAJECTORY_FORMAT",
           "joint_trajectory_csv", "read_joint_trajectory"]
