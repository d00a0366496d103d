"""A robot in a bag: /robot_description (or a URDF path) mounted at its root link's frame,
/joint_states driving its joints; poses against Pinocchio called directly on the URDF."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes.errors import BagWarning

from ros.bag_writing import (
    JOINT_STATE,
    STORAGES,
    STRING,
    Message,
    Transform,
    joint_state,
    ros_version_of,
    string,
    tf_messages,
    write_bag,
)

URDF = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
SECOND = 1_000_000_000
START = 1_700_000_000 * SECOND
JOINTS = [f"joint_{i}" for i in range(1, 7)]


def _robot_bag(tmp_path: Path, storage: str, rng: np.random.Generator,
               with_description: bool = True):
    """world -> base_link static; joint states: joints 1-3 every 0.1 s, joints 4-6 every
    0.25 s in separate (partial) messages; /tf carries a republished link_1 too."""
    version = ros_version_of(storage)
    samples: dict[str, tuple[list[int], list[float]]] = {name: ([], []) for name in JOINTS}
    messages = tf_messages(version, [Transform("world", "base_link", START, (0.5, -0.2, 0.3),
                                               (0.0, 0.0, np.sin(0.4), np.cos(0.4)))],
                           topic="/tf_static")
    if with_description:
        messages.append(Message("/robot_description", STRING, START,
                                string(version, URDF.read_text())))
    for step, period, names in ((0, 0.1, JOINTS[:3]), (1, 0.25, JOINTS[3:])):
        for tick in range(int(2.0 / period) + 1):
            stamp = START + int(tick * period * SECOND) + step
            values = rng.uniform(-1.0, 1.0, len(names))
            for name, value in zip(names, values, strict=True):
                samples[name][0].append(stamp)
                samples[name][1].append(float(value))
            messages.append(Message("/joint_states", JOINT_STATE, stamp,
                                    joint_state(version, stamp, names, values)))
    messages += tf_messages(version, [Transform("base_link", "link_1", START + SECOND)])
    messages.sort(key=lambda message: message.received_ns)
    return write_bag(tmp_path / "robot", storage, messages), samples


def _pinocchio_flange_in_world(samples, times_ns: np.ndarray) -> np.ndarray:
    """The flange in world at ``times_ns``: each joint interpolated linearly between its own
    samples here, Pinocchio's forward kinematics, the static base pose composed by hand."""
    model = pin.buildModelFromUrdf(str(URDF))
    data = model.createData()
    flange = model.getFrameId("flange")
    base = np.eye(4)
    base[:3, :3] = pin.Quaternion(np.cos(0.4), 0.0, 0.0, np.sin(0.4)).toRotationMatrix()
    base[:3, 3] = [0.5, -0.2, 0.3]
    result = []
    for time in times_ns:
        q = pin.neutral(model)
        for name in JOINTS:
            stamps, values = samples[name]
            index = model.joints[model.getJointId(name)].idx_q
            # offsets from START: float ns since the epoch would be 256 ns coarse
            q[index] = np.interp(time - START, np.array(stamps) - START, values)
        pin.framesForwardKinematics(model, data, q)
        result.append(base @ data.oMf[flange].homogeneous)
    return np.array(result)


@pytest.mark.parametrize("storage", STORAGES)
def test_joint_states_drive_the_recorded_description(tmp_path, rng, storage):
    bag, samples = _robot_bag(tmp_path, storage, rng)
    with pytest.warns(BagWarning, match="ignored the tf transforms of 1 links"):
        tree = pinframes.read_rosbag(bag)
    assert tree.parent("base_link") == "world" and tree.parent("link_1") == "base_link"
    assert sorted(tree.joints) == JOINTS
    assert len(tree.joint_trajectory("joint_1").times) == 21
    assert len(tree.joint_trajectory("joint_4").times) == 9
    times_ns = START + np.array([0, 37, 125, 260, 999, 1_600, 2_000]) * 1_000_000 + 3
    pose = tree.pose("flange", relative_to="world", times=(times_ns - START) / 1e9)
    expected = _pinocchio_flange_in_world(samples, times_ns)
    np.testing.assert_allclose(pose.rotation, expected[:, :3, :3], atol=1e-9)
    np.testing.assert_allclose(pose.translation, expected[:, :3, 3], atol=1e-9)


def test_a_urdf_path_replaces_the_topic_and_without_it_joint_states_are_listed(tmp_path, rng):
    bag, samples = _robot_bag(tmp_path, "mcap", rng, with_description=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BagWarning)
        tree = pinframes.read_rosbag(bag, robot_description=URDF)
        times_ns = START + np.array([150, 1_900]) * 1_000_000
        pose = tree.pose("flange", relative_to="world", times=(times_ns - START) / 1e9)
        np.testing.assert_allclose(pose.translation,
                                   _pinocchio_flange_in_world(samples, times_ns)[:, :3, 3],
                                   atol=1e-9)
        bare = pinframes.read_rosbag(bag)
    assert bare.joints == {} and bare.frames == ["world", "base_link", "link_1"]
    assert bare.metadata["rosbag"]["joint_states_not_used"] == JOINTS


def test_the_root_link_becomes_the_root_without_tf(tmp_path, rng):
    version = 2
    messages = [Message("/robot_description", STRING, START, string(version, URDF.read_text())),
                Message("/joint_states", JOINT_STATE, START,
                        joint_state(version, START, ["joint_2", "gripper"], [0.3, 0.01]))]
    bag = write_bag(tmp_path / "robot", "mcap", messages)
    with pytest.warns(BagWarning, match="1 joints the robot description does not drive"):
        tree = pinframes.read_rosbag(bag)
    assert tree.root == "base_link"
    assert tree.joint_trajectory("joint_2").values.tolist() == [0.3]


@pytest.mark.parametrize("storage", ["mcap", "ros1"])
def test_nan_positions_and_repeated_stamps_of_joints(tmp_path, storage):
    version = ros_version_of(storage)
    states = [(START, [0.1, np.nan]), (START + SECOND, [0.2, 0.5]), (START + SECOND, [0.3, 0.6])]
    messages = [Message("/joint_states", JOINT_STATE, START + i,
                        joint_state(version, stamp, ["joint_1", "joint_2"], values))
                for i, (stamp, values) in enumerate(states)]
    bag = write_bag(tmp_path / "robot", storage, messages)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tree = pinframes.read_rosbag(bag, robot_description=URDF)
    texts = [str(w.message) for w in caught if issubclass(w.category, BagWarning)]
    assert len(texts) == 2
    assert "1 joint positions that are NaN or infinite (first: joint 'joint_2')" in texts[0]
    assert "2 joints with two samples at one stamp" in texts[1]
    # at the repeated stamp, the transforms robot_state_publisher makes: ROS 1's tf2 keeps
    # the first received, ROS 2's looks up the later
    later = version == 2
    assert tree.joint_trajectory("joint_1").values.tolist() == [0.1, 0.3 if later else 0.2]
    assert tree.joint_trajectory("joint_2").values.tolist() == [0.6 if later else 0.5]
