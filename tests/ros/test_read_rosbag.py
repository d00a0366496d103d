"""read_rosbag on bags written by rosbags' writers (ROS 1, ROS 2 SQLite, ROS 2 MCAP): poses
between stamps against lerp + SLERP computed here in numpy, and tf2's rules."""

from __future__ import annotations

import itertools
import warnings

import numpy as np
import pytest

import pinframes
from pinframes.errors import BagWarning, TreeStructureError

from ros.bag_writing import STORAGES, Message, Transform, ros_version_of, tf_messages, write_bag

SECOND = 1_000_000_000
START = 1_700_000_000 * SECOND  # stamps in ns since the epoch


def _quaternion_about_z(angle: float) -> np.ndarray:
    return np.array([0.0, 0.0, np.sin(angle / 2), np.cos(angle / 2)])


def _slerp(q0: np.ndarray, q1: np.ndarray, fraction: float) -> np.ndarray:
    """Spherical interpolation along the shorter arc, written out."""
    dot = float(q0 @ q1)
    if dot < 0:
        q1, dot = -q1, -dot
    angle = np.arccos(min(dot, 1.0))
    if angle < 1e-12:
        return q0
    return (np.sin((1 - fraction) * angle) * q0 + np.sin(fraction * angle) * q1) / np.sin(angle)


def _matrix(q: np.ndarray) -> np.ndarray:
    x, y, z, w = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


@pytest.fixture(params=STORAGES)
def storage(request):
    return request.param


def _moving_tool(storage, tmp_path, rng):
    """world -> base static, base -> tool keyframed at 6 stamps received out of order."""
    version = ros_version_of(storage)
    stamps = START + np.sort(rng.choice(10 * SECOND, 6, replace=False))
    keyframes = [Transform("base", "tool", int(s), rng.normal(size=3),
                           _quaternion_about_z(a) * (1 if i % 2 else -1))  # sign flips too
                 for i, (s, a) in enumerate(zip(stamps, np.linspace(0, 4, 6), strict=True))]
    received = keyframes[::2] + keyframes[1::2]  # receive order is not stamp order
    messages = tf_messages(version, [Transform("/world", "base", 0, (1.0, 2.0, 3.0),
                                               _quaternion_about_z(0.3))],
                           topic="/tf_static", received_ns=START)
    messages += [Message(*m[:2], START + i, m[3])
                 for i, m in enumerate(tf_messages(version, received))]
    return write_bag(tmp_path / "run", storage, messages), keyframes


def test_poses_between_stamps_are_lerp_and_slerp(storage, tmp_path, rng):
    bag, keyframes = _moving_tool(storage, tmp_path, rng)
    tree = pinframes.read_rosbag(bag)
    assert tree.root == "world"
    assert tree.reference_time == np.datetime64(keyframes[0].stamp_ns, "ns")
    assert tree.is_moving("tool") and not tree.is_moving("base")
    fractions = np.array([0.0, 0.25, 0.5, 0.9])
    for before, after in itertools.pairwise(keyframes):
        seconds = (before.stamp_ns - keyframes[0].stamp_ns
                   + fractions * (after.stamp_ns - before.stamp_ns)) / 1e9
        pose = tree.pose("tool", relative_to="world", times=seconds)
        base_rotation = _matrix(_quaternion_about_z(0.3))
        for row, fraction in enumerate(fractions):
            t_local = (1 - fraction) * np.asarray(before.translation) + fraction * np.asarray(
                after.translation)
            r_local = _matrix(_slerp(np.asarray(before.quaternion, float),
                                     np.asarray(after.quaternion, float), fraction))
            np.testing.assert_allclose(pose.rotation[row], base_rotation @ r_local, atol=1e-9)
            np.testing.assert_allclose(pose.translation[row],
                                       base_rotation @ t_local + [1, 2, 3], atol=1e-9)


def test_keyframes_are_at_the_stamps_not_the_receive_times(storage, tmp_path, rng):
    bag, keyframes = _moving_tool(storage, tmp_path, rng)
    tree = pinframes.read_rosbag(bag)
    pose = tree.local_pose("tool")
    expected = np.array([k.stamp_ns for k in keyframes]) - keyframes[0].stamp_ns
    assert pose.times.astype(np.int64).tolist() == expected.tolist()
    assert tree.metadata["rosbag"]["topics"] == [
        {"name": "/tf", "type": "tf2_msgs/msg/TFMessage", "messages": 6, "use": "tf"},
        {"name": "/tf_static", "type": "tf2_msgs/msg/TFMessage", "messages": 1,
         "use": "tf static"}]


def test_read_recognises_every_kind_of_bag(storage, tmp_path, rng):
    bag, _ = _moving_tool(storage, tmp_path, rng)
    assert pinframes.read(bag).frames == ["world", "base", "tool"]
    if storage != "ros1":  # the storage file alone, and under another name
        (storage_file,) = [f for f in bag.iterdir() if f.name != "metadata.yaml"]
        assert pinframes.read(storage_file).frames == ["world", "base", "tool"]
        renamed = tmp_path / "renamed.bin"
        renamed.write_bytes(storage_file.read_bytes())
        assert pinframes.read_rosbag(renamed).frames == ["world", "base", "tool"]


def test_reparenting_names_frame_both_parents_and_first_times(storage, tmp_path):
    version = ros_version_of(storage)
    bag = write_bag(tmp_path / "run", storage, tf_messages(version, [
        Transform("world", "tool", START + 3 * SECOND), Transform("world", "tool", START),
        Transform("changer", "tool", START + 7 * SECOND), Transform("world", "changer", START)]))
    with pytest.raises(TreeStructureError) as caught:
        pinframes.read_rosbag(bag)
    error = caught.value
    assert error.frame == "tool" and error.file == str(bag)
    assert "'world' (first at 2023-11-14T22:13:20" in error.message
    assert "'changer' (first at 2023-11-14T22:13:27" in error.message


def test_several_roots_are_named(storage, tmp_path):
    version = ros_version_of(storage)
    bag = write_bag(tmp_path / "run", storage, tf_messages(version, [
        Transform("map", "robot", START), Transform("odom", "base", START),
        Transform("base", "tool", START)]))
    with pytest.raises(TreeStructureError, match="'map', 'odom'"):
        pinframes.read_rosbag(bag)


def test_same_frame_twice_at_one_stamp_keeps_what_tf2_keeps_with_one_warning(storage,
                                                                             tmp_path):
    # ROS 1's tf2 refuses the second transform at a stored stamp (TF_REPEATED_DATA); ROS 2's
    # stores both and looks up the later received
    version = ros_version_of(storage)
    bag = write_bag(tmp_path / "run", storage, tf_messages(version, [
        Transform("world", "a", START, (1, 0, 0)), Transform("world", "a", START, (2, 0, 0)),
        Transform("world", "b", START, (1, 0, 0)), Transform("world", "b", START, (3, 0, 0)),
        Transform("world", "b", START, (4, 0, 0)),
        Transform("world", "a", START + SECOND, (5, 0, 0))], received_ns=START))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tree = pinframes.read_rosbag(bag)
    bag_warnings = [str(w.message) for w in caught if issubclass(w.category, BagWarning)]
    assert len(bag_warnings) == 1 and "'a', 'b'" in bag_warnings[0]
    kept = "first" if version == 1 else "later"
    assert f"the {kept} received is kept" in bag_warnings[0]
    first_a, first_b = (1.0, 1.0) if version == 1 else (2.0, 4.0)
    assert tree.local_pose("a").translation[:, 0].tolist() == [first_a, 5.0]
    assert tree.local_pose("b").translation[:, 0].tolist() == [first_b]


def test_transforms_tf2_refuses_are_skipped_with_one_warning(tmp_path):
    bag = write_bag(tmp_path / "run", "mcap", tf_messages(2, [
        Transform("world", "a", START), Transform("world", "a", START + SECOND,
                                                  quaternion=(0, 0, 0, 2)),
        Transform("world", "b", START, (np.nan, 0, 0)), Transform("b", "b", START),
        Transform("world", "b", START + SECOND)]))
    with pytest.warns(BagWarning, match="skipped transforms that tf2 refuses") as caught:
        tree = pinframes.read_rosbag(bag)
    assert len(caught) == 1
    assert len(tree.local_pose("a")) == 1 and len(tree.local_pose("b")) == 1


def test_a_frame_on_both_a_static_and_a_dynamic_topic_is_refused(tmp_path):
    messages = tf_messages(2, [Transform("world", "a", START)], topic="/tf_static")
    messages += tf_messages(2, [Transform("world", "a", START + SECOND)])
    bag = write_bag(tmp_path / "run", "mcap", messages)
    with pytest.raises(TreeStructureError, match="both a static and a dynamic") as caught:
        pinframes.read_rosbag(bag)
    assert caught.value.frame == "a"
    tree = pinframes.read_rosbag(bag, tf_topics=["/tf_static"])
    assert not tree.is_moving("a")


@pytest.mark.parametrize(("storage", "compression"), [
    ("ros1", "bz2"), ("ros1", "lz4"), ("sqlite3", "file"), ("sqlite3", "message"),
    ("mcap", "message"), ("mcap", "storage")])
def test_compressed_bags(tmp_path, storage, compression):
    version = ros_version_of(storage)
    transforms = [Transform("world", "tool", START + k * SECOND, (k, 0, 0)) for k in range(5)]
    bag = write_bag(tmp_path / "run", storage, tf_messages(version, transforms), compression)
    tree = pinframes.read(bag)
    assert tree.local_pose("tool").translation[:, 0].tolist() == [0, 1, 2, 3, 4]
