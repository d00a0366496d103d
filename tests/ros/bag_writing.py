"""Bags written by rosbags' own writers, for the ROS bag tests (no pinframes code here).

``write_bag(path, storage, messages)`` writes ``messages`` (``Message`` tuples in receive
order) as a ROS 1 bag (``"ros1"``, a file) or a ROS 2 bag folder (``"sqlite3"``, ``"mcap"``)
and returns the path to read.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable, Iterator, Sequence
from functools import cache
from pathlib import Path
from types import SimpleNamespace
from typing import Any, NamedTuple

import pytest

rosbags = pytest.importorskip("rosbags")

from rosbags.rosbag1 import Writer as Ros1Writer  # noqa: E402
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin  # noqa: E402
from rosbags.rosbag2 import Writer as Ros2Writer  # noqa: E402
from rosbags.rosbag2 import writer as rosbag2_writer  # noqa: E402
from rosbags.typesys import Stores, get_types_from_msg, get_typestore  # noqa: E402

zstd = rosbag2_writer.zstd  # the zstd module rosbags writes with

TF = "tf2_msgs/msg/TFMessage"
JOINT_STATE = "sensor_msgs/msg/JointState"
STRING = "std_msgs/msg/String"
STORAGES = ("ros1", "sqlite3", "mcap")


class Transform(NamedTuple):
    """One TransformStamped: ``parent`` in ``header.frame_id``, stamp in ns since the epoch,
    translation in metres, quaternion (x, y, z, w)."""

    parent: str
    child: str
    stamp_ns: int
    translation: Sequence[float] = (0.0, 0.0, 0.0)
    quaternion: Sequence[float] = (0.0, 0.0, 0.0, 1.0)


class Message(NamedTuple):
    """A message to write: topic, type, receive time (ns) and the message object."""

    topic: str
    msgtype: str
    received_ns: int
    message: Any


@cache
def typestore(ros_version: int) -> Any:
    """rosbags' ROS 2 (latest) store, or its ROS 1 Noetic store with tf2_msgs/TFMessage
    added from its .msg definition (Noetic's store lacks it)."""
    if ros_version == 2:
        return get_typestore(Stores.LATEST)
    store = get_typestore(Stores.ROS1_NOETIC)
    store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", TF))
    return store


def _time(store: Any, stamp_ns: int) -> Any:
    kind = store.types["builtin_interfaces/msg/Time"]
    return kind(sec=stamp_ns // 1_000_000_000, nanosec=stamp_ns % 1_000_000_000)


def _header(store: Any, frame: str, stamp_ns: int) -> Any:
    header = store.types["std_msgs/msg/Header"]
    fields = {"stamp": _time(store, stamp_ns), "frame_id": frame}
    if "seq" in header.__dataclass_fields__:
        fields["seq"] = 0
    return header(**fields)


def tf_message(ros_version: int, transforms: Iterable[Transform]) -> Any:
    """A tf2_msgs/TFMessage object of ``transforms``."""
    store = typestore(ros_version)
    types = store.types
    stamped = [
        types["geometry_msgs/msg/TransformStamped"](
            header=_header(store, t.parent, t.stamp_ns), child_frame_id=t.child,
            transform=types["geometry_msgs/msg/Transform"](
                translation=types["geometry_msgs/msg/Vector3"](*map(float, t.translation)),
                rotation=types["geometry_msgs/msg/Quaternion"](*map(float, t.quaternion))))
        for t in transforms]
    return types[TF](transforms=stamped)


def joint_state(ros_version: int, stamp_ns: int, names: Sequence[str],
                positions: Sequence[float]) -> Any:
    """A sensor_msgs/JointState object (no velocities or efforts)."""
    import numpy as np

    store = typestore(ros_version)
    return store.types[JOINT_STATE](
        header=_header(store, "", stamp_ns), name=list(names),
        position=np.asarray(positions, float), velocity=np.zeros(0), effort=np.zeros(0))


def string(ros_version: int, text: str) -> Any:
    """A std_msgs/String object."""
    return typestore(ros_version).types[STRING](data=text)


def serialise(ros_version: int, message: Any, msgtype: str, little_endian: bool = True
              ) -> bytes:
    """The message's bytes as a bag stores them."""
    store = typestore(ros_version)
    if ros_version == 1:
        return bytes(store.serialize_ros1(message, msgtype))
    return bytes(store.serialize_cdr(message, msgtype, little_endian=little_endian))


def ros_version_of(storage: str) -> int:
    return 1 if storage == "ros1" else 2


def write_bag(path: Path, storage: str, messages: Iterable[Message],
              compression: str | None = None, padding: int = 0) -> Path:
    """Write ``messages`` with rosbags' writer for ``storage``; the bag's path.
    ``compression``: ROS 1 ``"bz2"`` or ``"lz4"`` chunks; ROS 2 zstd by ``"file"``,
    ``"message"`` or (MCAP) ``"storage"``. ``padding`` makes a hostile bag: each compressed
    part (chunk, message, file) holds that many zero bytes after its content, which its
    header does not count, compressed by the writer's own compressor."""
    version = ros_version_of(storage)
    store = typestore(version)
    messages = list(messages)
    if storage == "ros1":
        path = path.with_suffix(".bag")
        writer: Any = Ros1Writer(path)
        if compression:
            writer.set_compression(Ros1Writer.CompressionFormat[compression.upper()])
            writer.compressor = _padded(writer.compressor, padding)
    else:
        plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
        writer = Ros2Writer(path, version=9, storage_plugin=plugin)
        if compression:
            writer.set_compression(CompressionMode[compression.upper()],
                                   CompressionFormat.ZSTD)
    with writer, _padded_messages(padding if compression == "message" else 0):
        if compression == "storage":
            writer.storage.compressor = _padded(writer.storage.compressor, padding)
        connections: dict[str, Any] = {}
        for message in messages:
            if message.topic not in connections:
                connections[message.topic] = writer.add_connection(
                    message.topic, message.msgtype, typestore=store)
            writer.write(connections[message.topic], message.received_ns,
                         serialise(version, message.message, message.msgtype))
    if compression == "file" and padding:
        for part in path.glob("*.zstd"):
            part.write_bytes(zstd.compress(zstd.decompress(part.read_bytes()) + bytes(padding)))
    return path


def _padded(compress: Any, padding: int) -> Any:
    return lambda data: compress(bytes(data) + bytes(padding)) if padding else compress(data)


@contextlib.contextmanager
def _padded_messages(padding: int) -> Iterator[None]:
    """rosbags' ROS 2 writer compresses each message with ``padding`` zero bytes added."""
    if not padding:
        yield
        return
    real = rosbag2_writer.zstd
    rosbag2_writer.zstd = SimpleNamespace(
        compress=lambda data: real.compress(bytes(data) + bytes(padding)), open=real.open)
    try:
        yield
    finally:
        rosbag2_writer.zstd = real


def tf_messages(ros_version: int, transforms: Iterable[Transform], topic: str = "/tf",
                received_ns: int | None = None) -> list[Message]:
    """One TFMessage per transform, received at its stamp (or at ``received_ns``)."""
    return [Message(topic, TF, t.stamp_ns if received_ns is None else received_ns,
                    tf_message(ros_version, [t])) for t in transforms]
