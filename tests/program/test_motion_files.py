"""A planned motion on the tree (``set_motion``) and in files: CSV and NPZ read back, a ROS
bag's ``JointTrajectory`` with velocities and accelerations (read with rosbags directly)."""

from __future__ import annotations

import numpy as np
import pytest

import pinframes
from program_cells import START, cell, limits, tool_origins


@pytest.fixture(scope="module")
def planned() -> tuple[pinframes.FrameTree, pinframes.Motion]:
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.move_joints([0.3, 0.4, -0.2, 0.1, 0.7, 0.2], name="air")
    program.wait(0.1, name="hold")
    return tree, program.plan(step=0.008)


def test_set_motion_drives_the_tree(planned):
    tree, motion = planned
    driven = tree.copy()
    driven.set_motion(motion)
    pose = driven.pose("tcp", "world", times=motion.seconds)
    np.testing.assert_allclose(pose.translation, tool_origins(motion.positions), atol=1e-9)
    with pytest.raises(pinframes.ArgumentTypeError):
        driven.set_motion(motion.positions)


def test_csv_and_npz_read_back(planned, tmp_path):
    _, motion = planned
    assert motion.urdf_joint_names == tuple(f"joint_{i}" for i in range(1, 7))
    for name in ("run.csv", "run.npz"):
        pinframes.write_joint_trajectory(motion, tmp_path / name)  # the motion's URDF names
        times, positions, names = pinframes.read_joint_trajectory(tmp_path / name)
        assert names == [f"joint_{i}" for i in range(1, 7)]
        seconds = (times.astype(np.int64) / 1e9 if times.dtype.kind == "m"  # NPZ
                   else times)  # CSV: float seconds
        np.testing.assert_allclose(seconds, motion.seconds, atol=1e-9)
        np.testing.assert_allclose(positions, motion.positions, atol=1e-9)
    with np.load(tmp_path / "run.npz") as arrays:
        np.testing.assert_array_equal(arrays["velocities"], motion.velocities)
        np.testing.assert_array_equal(arrays["accelerations"], motion.accelerations)


def test_bag_joint_trajectory_has_velocities_and_accelerations(planned, tmp_path):
    rosbags_reader = pytest.importorskip("rosbags.highlevel")
    tree, motion = planned
    bag = tmp_path / "run.mcap"
    pinframes.write_joint_trajectory(motion, bag, tree=tree)
    with rosbags_reader.AnyReader([bag]) as reader:
        connections = [c for c in reader.connections if c.topic == "/joint_trajectory"]
        (message,) = [reader.deserialize(raw, connection.msgtype)
                      for connection, _, raw in reader.messages(connections=connections)]
    assert list(message.joint_names) == [f"joint_{i}" for i in range(1, 7)]
    assert len(message.points) == len(motion)
    velocities = np.array([point.velocities for point in message.points])
    accelerations = np.array([point.accelerations for point in message.points])
    np.testing.assert_array_equal(velocities, motion.velocities)
    np.testing.assert_array_equal(accelerations, motion.accelerations)
    last = message.points[-1].time_from_start
    assert last.sec + last.nanosec / 1e9 == pytest.approx(motion.cycle_time)
