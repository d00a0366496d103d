"""The message types a bag's tree is read from, and the standard ones decoded by rosbags.

``tf2_msgs/TFMessage`` (ROS 1's older ``tf/tfMessage`` has the same fields) is decoded in
bulk by :mod:`._tf_messages`; ``sensor_msgs/JointState`` and ``std_msgs/String`` by
rosbags' deserialiser, with its ROS 2 store (CDR) or its ROS 1 Noetic store. A ROS 1 bag
says the MD5 sum of each type's definition: a type of the right name but another definition
is refused rather than misread.
"""

from __future__ import annotations

from functools import cache
from typing import Any

from ...errors import FileFormatError
from ._storage import BagTopic, OpenBag, rosbags_missing

__all__ = ["DESCRIPTION_TYPES", "JOINT_STATE_TYPES", "TF_TYPES", "check_type", "deserialise"]

TF_TYPES = ("tf2_msgs/msg/TFMessage", "tf/msg/tfMessage")
JOINT_STATE_TYPES = ("sensor_msgs/msg/JointState",)
DESCRIPTION_TYPES = ("std_msgs/msg/String",)
_TF_MD5 = "94810edda583a504dfda3829e70d7eec"  # ROS 1 TFMessage and tfMessage alike


def check_type(bag: OpenBag, topic: BagTopic, expected: tuple[str, ...]) -> None:
    """A :class:`FileFormatError` unless ``topic`` carries one of the ``expected`` types
    with their standard definition."""
    if topic.message_type not in expected:
        raise FileFormatError(f"messages of type {topic.message_type}, expected "
                              f"{' or '.join(expected)}", file=bag.path, field=topic.name)
    if bag.ros_version != 1 or not topic.md5sum or topic.md5sum == "*":
        return
    standard = _TF_MD5 if expected == TF_TYPES else _ros1_md5(topic.message_type)
    if topic.md5sum != standard:
        raise FileFormatError(f"{topic.message_type} with a definition other than the "
                              f"standard one (MD5 {topic.md5sum}, expected {standard})",
                              file=bag.path, field=topic.name)


def deserialise(ros_version: int, raw: bytes, message_type: str) -> Any:
    """A standard message object from its bytes (rosbags' exceptions pass through)."""
    store = _store(ros_version)
    if ros_version == 1:
        return store.deserialize_ros1(raw, message_type)
    return store.deserialize_cdr(raw, message_type)


@cache
def _store(ros_version: int) -> Any:
    try:
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise rosbags_missing() from None
    return get_typestore(Stores.ROS1_NOETIC if ros_version == 1 else Stores.LATEST)


def _ros1_md5(message_type: str) -> str:
    md5: str = _store(1).generate_msgdef(message_type)[1]
    return md5
