"""The bulk TFMessage decoder against rosbags' own deserialiser, on the same bytes."""

from __future__ import annotations

import numpy as np
import pytest

from pinframes.formats.rosbag._tf_messages import CorruptMessage, decode_tf_messages

from ros.bag_writing import TF, Transform, serialise, tf_message, typestore

NAMES = ["world", "/map", "base_link", "tool0", "", "kamera_ä", "a" * 37, "b"]


def _random_messages(rng: np.random.Generator, ros_version: int, count: int
                     ) -> list[list[Transform]]:
    messages = []
    for _ in range(count):
        transforms = []
        for _ in range(int(rng.integers(0, 5))):
            parent, child = rng.choice(NAMES, 2)
            stamp = int(rng.integers(0, 2**31 - 1)) * 1_000_000_000 + int(rng.integers(0, 10**9))
            transforms.append(Transform(str(parent), str(child), stamp,
                                        rng.normal(size=3) * 10, rng.normal(size=4)))
        messages.append(transforms)
    return messages


def _rosbags_columns(ros_version: int, raw: list[bytes]) -> list[tuple]:
    store = typestore(ros_version)
    rows = []
    for data in raw:
        message = (store.deserialize_ros1(data, TF) if ros_version == 1
                   else store.deserialize_cdr(data, TF))
        for t in message.transforms:
            stamp = t.header.stamp
            rows.append((t.header.frame_id, t.child_frame_id,
                         stamp.sec * 1_000_000_000 + stamp.nanosec,
                         (t.transform.translation.x, t.transform.translation.y,
                          t.transform.translation.z),
                         (t.transform.rotation.x, t.transform.rotation.y,
                          t.transform.rotation.z, t.transform.rotation.w)))
    return rows


def _our_columns(ros_version: int, raw: list[bytes]) -> list[tuple]:
    columns = decode_tf_messages(raw, ros_version)
    return [(columns.names[p], columns.names[c], int(s), tuple(t.tolist()), tuple(q.tolist()))
            for p, c, s, t, q in zip(columns.parents, columns.children, columns.stamps_ns,
                                     columns.translations, columns.quaternions, strict=True)]


@pytest.mark.parametrize(("ros_version", "little_endian"), [(1, True), (2, True), (2, False)])
def test_decoded_as_rosbags_deserialises(rng, ros_version, little_endian):
    messages = _random_messages(rng, ros_version, 300)
    raw = [serialise(ros_version, tf_message(ros_version, m), TF, little_endian)
           for m in messages]
    assert _our_columns(ros_version, raw) == _rosbags_columns(ros_version, raw)
    columns = decode_tf_messages(raw, ros_version)
    expected_index = [i for i, m in enumerate(messages) for _ in m]
    assert columns.message_index.tolist() == expected_index


@pytest.mark.parametrize(("ros_version", "seconds"), [(1, 4_000_000_000), (2, -5)])
def test_stamp_seconds_are_unsigned_in_ros1_and_signed_in_ros2(ros_version, seconds):
    # ROS 1 time is two uint32 (rosbags reads them as int32: 2038 and later differ); ROS 2's
    # builtin_interfaces/Time.sec is an int32
    store = typestore(ros_version)
    message = tf_message(ros_version, [Transform("a", "b", 0)])
    as_int32 = (seconds + 2**31) % 2**32 - 2**31
    message.transforms[0].header.stamp = store.types["builtin_interfaces/msg/Time"](
        sec=as_int32, nanosec=7)
    raw = [serialise(ros_version, message, TF)]
    assert decode_tf_messages(raw, ros_version).stamps_ns.tolist() == [
        seconds * 1_000_000_000 + 7]


@pytest.mark.parametrize("ros_version", [1, 2])
def test_no_messages_and_empty_messages(ros_version):
    assert decode_tf_messages([], ros_version).stamps_ns.shape == (0,)
    raw = [serialise(ros_version, tf_message(ros_version, []), TF)]
    assert decode_tf_messages(raw, ros_version).names == []


@pytest.mark.parametrize("ros_version", [1, 2])
def test_every_truncation_is_refused_as_rosbags_refuses_it(rng, ros_version):
    good = serialise(ros_version, tf_message(ros_version, [
        Transform("world", "tool", 5, (1, 2, 3)), Transform("tool", "tip", 6)]), TF)
    store = typestore(ros_version)
    for cut in range(len(good)):
        raw = [good, good[:cut]]
        with pytest.raises(Exception):  # noqa: B017 (rosbags' exception types may change)
            (store.deserialize_ros1 if ros_version == 1 else store.deserialize_cdr)(
                raw[1], TF)
        if ros_version == 2 and len(good) - cut <= 3 and cut % 4 == 0:
            continue  # a padded CDR end: rosbags accepts it too
        with pytest.raises(CorruptMessage) as caught:
            decode_tf_messages(raw, ros_version)
        assert caught.value.index == 1


def test_unknown_encapsulation_and_trailing_bytes():
    good = serialise(2, tf_message(2, [Transform("a", "b", 1)]), TF)
    with pytest.raises(CorruptMessage, match="encapsulation"):
        decode_tf_messages([b"\x00\x03" + good[2:]], 2)
    with pytest.raises(CorruptMessage, match="bytes left"):
        decode_tf_messages([good + b"\x00" * 8], 2)
    ros1 = serialise(1, tf_message(1, [Transform("a", "b", 1)]), TF)
    with pytest.raises(CorruptMessage, match="bytes left"):
        decode_tf_messages([ros1 + b"\x00"], 1)


def test_a_huge_count_is_refused_before_any_work():
    raw = b"\x00\x01\x00\x00" + (10**9).to_bytes(4, "little") + bytes(80)
    with pytest.raises(CorruptMessage, match="do not fit"):
        decode_tf_messages([raw], 2)
