"""Bags decoded by two independent readers, rosbags and the ``mcap`` library (with
``mcap-ros2-support``), into the same plain records (no pinframes code here).

``decode(path, reader)`` gives ``{topic: [record, ...]}`` in log-time order, a record being
a dict of plain Python values: ``tf`` records per transform (``parent``, ``child``,
``stamp_ns``, ``translation``, ``quaternion``), joint states (``stamp_ns``, ``names``,
``positions``), strings (``text``), joint trajectories (``names``, ``points`` of
``(time_from_start_ns, positions)``, ``stamp_ns``); every record has ``log_ns``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

pytest.importorskip("rosbags")

from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

READERS = ("rosbags", "mcap")
NS = 1_000_000_000


def decode(path: Path, reader: str) -> dict[str, list[dict[str, Any]]]:
    """Every message of the bag at ``path`` as plain records, by ``reader``."""
    if reader == "rosbags":
        return _with_rosbags(path)
    return _with_mcap(path)


def mcap_file(path: Path) -> Path:
    """The MCAP file of a bag: the file itself, or the one in a ROS 2 bag folder."""
    return path if path.is_file() else next(path.glob("*.mcap"))


def _with_rosbags(path: Path) -> dict[str, list[dict[str, Any]]]:
    store = get_typestore(Stores.LATEST)
    ros1 = path.suffix == ".bag"
    if ros1:
        store = get_typestore(Stores.ROS1_NOETIC)
        store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms",
                                          "tf2_msgs/msg/TFMessage"))
    records: dict[str, list[dict[str, Any]]] = {}
    with AnyReader([path], default_typestore=store) as reader:
        for connection, log_ns, raw in reader.messages():
            message = reader.deserialize(raw, connection.msgtype)
            records.setdefault(connection.topic, []).extend(
                _records(connection.msgtype, message, log_ns))
    return records


def _with_mcap(path: Path) -> dict[str, list[dict[str, Any]]]:
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    records: dict[str, list[dict[str, Any]]] = {}
    with open(mcap_file(path), "rb") as handle:
        reader = make_reader(handle, decoder_factories=[DecoderFactory()])
        for schema, channel, message, decoded in reader.iter_decoded_messages(
                log_time_order=True):
            records.setdefault(channel.topic, []).extend(
                _records(schema.name, decoded, message.log_time))
    return records


def _stamp(stamp: Any) -> int:
    return int(stamp.sec) * NS + int(stamp.nanosec)


def _records(message_type: str, message: Any, log_ns: int) -> list[dict[str, Any]]:
    if message_type == "tf2_msgs/msg/TFMessage":
        return [{"log_ns": log_ns, "parent": t.header.frame_id, "child": t.child_frame_id,
                 "stamp_ns": _stamp(t.header.stamp),
                 "translation": [t.transform.translation.x, t.transform.translation.y,
                                 t.transform.translation.z],
                 "quaternion": [t.transform.rotation.x, t.transform.rotation.y,
                                t.transform.rotation.z, t.transform.rotation.w]}
                for t in message.transforms]
    if message_type == "sensor_msgs/msg/JointState":
        return [{"log_ns": log_ns, "stamp_ns": _stamp(message.header.stamp),
                 "names": list(message.name),
                 "positions": [float(value) for value in message.position]}]
    if message_type == "std_msgs/msg/String":
        return [{"log_ns": log_ns, "text": message.data}]
    if message_type == "trajectory_msgs/msg/JointTrajectory":
        return [{"log_ns": log_ns, "stamp_ns": _stamp(message.header.stamp),
                 "names": list(message.joint_names),
                 "points": [(_stamp(point.time_from_start),
                             [float(value) for value in point.positions])
                            for point in message.points]}]
    raise AssertionError(f"unexpected message type {message_type}")


def matrix_from_quaternion(quaternion: Any) -> np.ndarray:
    """The rotation matrix of a unit quaternion (x, y, z, w), written out by hand."""
    x, y, z, w = np.asarray(quaternion, float) / np.linalg.norm(quaternion)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
