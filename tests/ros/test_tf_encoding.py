"""TFMessages encoded in bulk (``formats/rosbag/_tf_encoding.py``) are byte for byte what
rosbags serialises for the same messages, ROS 1 and CDR, whatever the names' lengths (every
alignment padding) and characters, and at the ends of the stamp fields."""

from __future__ import annotations

import numpy as np
import pytest

from pinframes.formats.rosbag._tf_encoding import encode_tf_messages

from ros.bag_writing import TF, Transform, serialise, tf_message

NAMES = ["a", "bc", "def", "ghij", "klmno", "é", "中文", "frame_with_a_long_name_7"]


@pytest.mark.parametrize("ros_version", [1, 2])
@pytest.mark.parametrize("offset", range(4))
def test_every_message_equals_rosbags_serialisation(rng, ros_version, offset):
    children = NAMES[offset:offset + 5]
    parents = ["world", *children[:-1]]
    frames, times = len(children), 6
    stamps = np.array([0, 1, 999_999_999, 10**9, 1_709_280_000 * 10**9 + 123,
                       (2**31 - 1) * 10**9 + 999_999_999], np.int64)
    translations = rng.normal(size=(frames, times, 3)) * 10.0 ** rng.integers(-300, 300)
    quaternions = rng.normal(size=(frames, times, 4))
    quaternions /= np.linalg.norm(quaternions, axis=2, keepdims=True)

    def rosbags_bytes(index: int) -> bytes:
        message = tf_message(ros_version, [
            Transform(parent, child, int(stamps[index]),
                      tuple(translations[frame, index]), tuple(quaternions[frame, index]))
            for frame, (parent, child) in enumerate(zip(parents, children, strict=True))])
        return serialise(ros_version, message, TF)

    rows = encode_tf_messages(rosbags_bytes(0), ros_version, parents, children, stamps,
                              translations, quaternions)
    for index in range(times):
        assert rows[index].tobytes() == rosbags_bytes(index)
