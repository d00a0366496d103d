"""A joint trajectory as a bag: what a ``joint_trajectory_controller`` takes, and what the
robot's joint state publisher would have published while it ran.

- ``/joint_trajectory``: one ``trajectory_msgs/JointTrajectory``, one point per sample,
  ``time_from_start`` counted from the first sample, ``header.stamp`` zero ("start on
  receipt", as controllers read it); stored at the first sample's stamp.
- ``/joint_states``: one ``sensor_msgs/JointState`` per sample, stamped at the sample.

Stamps: absolute times as they are, relative times counted from 0 (1970-01-01).
"""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import NDArray

from ...errors import PinframesError
from .._paths import path_argument
from . import _outgoing as outgoing
from ._bag_writer import BagWriter, check_stamps, output_kind
from ._storage import ROS1

__all__ = ["JOINT_TRAJECTORY_TOPIC", "write_trajectory_bag"]

JOINT_TRAJECTORY_TOPIC = "/joint_trajectory"
JOINT_STATES_TOPIC = "/joint_states"


def write_trajectory_bag(times: NDArray[np.datetime64] | NDArray[np.timedelta64],
                         positions: NDArray[np.float64], joint_names: list[str],
                         path: str | os.PathLike[str], *,
                         rates: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
                         ) -> None:
    """Write T samples of ``joint_names`` (``positions`` (T, n), radians or metres, at
    strictly increasing ``times``: ``datetime64[ns]`` or ``timedelta64[ns]``) to the bag
    ``path`` (its kind told by the name, as :func:`write_rosbag` does), atomically; with
    ``rates`` (velocities and accelerations, (T, n) each, per s and s^2), the
    ``JointTrajectory``'s points carry them."""
    stamps = np.asarray(times).astype(np.int64)
    try:
        check_stamps(int(stamps[0]), int(stamps[-1]), output_kind(path) == ROS1,
                     "the trajectory")
    except PinframesError as exc:
        raise exc.located(file=path_argument(path)) from None
    with BagWriter(path) as bag:
        bag.topic(JOINT_TRAJECTORY_TOPIC, "trajectory_msgs/msg/JointTrajectory")
        bag.topic(JOINT_STATES_TOPIC, "sensor_msgs/msg/JointState")
        bag.write(JOINT_TRAJECTORY_TOPIC, int(stamps[0]), outgoing.joint_trajectory(
            bag.types, joint_names, stamps - stamps[0], positions, rates))
        for stamp, row in zip(stamps.tolist(), positions.tolist(), strict=True):
            bag.write(JOINT_STATES_TOPIC, stamp,
                      outgoing.joint_state(bag.types, stamp, joint_names, row))
