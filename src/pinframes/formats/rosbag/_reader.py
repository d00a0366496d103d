"""``read_rosbag``: a ROS 1, ROS 2 or MCAP bag as a frame tree, with tf2's semantics."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...errors import ArgumentTypeError, BagWarning, FileFormatError, PinframesError, warn_at_caller
from ...tree import FrameTree
from ..limits import Limits, current_limits, exceeded, using_limits
from ..urdf import RobotDescription, parse_urdf
from ._assembly import assemble_tree, reference_stamp
from ._joint_states import JointSamples, joint_samples
from ._messages import DESCRIPTION_TYPES, JOINT_STATE_TYPES, TF_TYPES, check_type, deserialise
from ._storage import OpenBag
from ._tf_messages import CorruptMessage, TransformColumns, decode_tf_messages
from ._tf_tracks import FrameTrack, frame_tracks, stamp_iso

__all__ = ["ROSBAG_METADATA_KEY", "read_rosbag"]

ROSBAG_METADATA_KEY = "rosbag"
"""Key of the tree metadata that says what was read from the bag (``pinframes info``)."""


def read_rosbag(
    path: str | os.PathLike[str], *,
    robot_description: str | os.PathLike[str] | RobotDescription | None = None,
    tf_topics: Sequence[str] = ("/tf", "/tf_static"),
    joint_states_topic: str | None = "/joint_states",
    description_topic: str | None = "/robot_description", limits: Limits | None = None,
) -> FrameTree:
    """Read the frame tree recorded in a ROS bag, as tf2 would see it.

    Parameters
    ----------
    path : path
        A ROS 1 ``.bag``, an MCAP file, a ROS 2 bag folder (with ``metadata.yaml``) or its
        ``.db3`` file; told by content, not by name.
    robot_description : path or str or RobotDescription or None
        A URDF file or its XML text (a ``*.xacro`` file is expanded, which runs its code),
        or a robot already read (:func:`pinframes.formats.urdf.parse_urdf`, for a xacro
        file with its arguments); None: the last message on ``description_topic``.
    tf_topics : sequence of str
        Topics of ``tf2_msgs/TFMessage``; those whose names end in ``_static`` hold static
        transforms (they hold for all time), the others keyframes at ``header.stamp``. Of
        two transforms of a frame at one stamp, a ROS 1 bag keeps the first received and a
        ROS 2 bag the later, as their versions of tf2 do (one ``BagWarning``).
    joint_states_topic : str or None
        ``sensor_msgs/JointState`` that drive the robot's joints (radians, metres).
    description_topic : str or None
        ``std_msgs/String`` holding the robot's URDF as XML text (never taken for a path:
        other text is an error). Robots in namespaces are read too: every
        ``<namespace>/robot_description`` with its ``<namespace>/joint_states`` (the last
        parts of ``description_topic`` and ``joint_states_topic``), as several
        ``robot_state_publisher`` nodes publish them.
    limits : pinframes.Limits or None
        ``max_samples`` bounds the keyframes of a frame and the samples of a joint,
        ``max_decompressed_bytes`` the bytes of the messages read; the URDF is read
        under the XML limits.

    Returns
    -------
    FrameTree
        Named after the bag; its reference time is the earliest stamp used (ns since the
        epoch, UTC); ``tree.metadata["rosbag"]`` says which topics were used and ignored and
        which joint states no joint took.

    Raises
    ------
    FileFormatError
        A truncated or corrupt bag, an unknown storage, a folder without metadata, a topic
        of the wrong type, or no tf messages and no robot description at all.
    TreeStructureError
        A frame published under two parents (named with the first time of each), or the
        frames form several trees (their roots named).
    UnsupportedFeatureError
        The ``rosbags`` package is not installed (``pip install 'pinframes[ros]'``).
    """
    if isinstance(tf_topics, str):
        raise ArgumentTypeError(f"expected a list of topics, got the string {tf_topics!r}",
                                field="tf_topics")
    with using_limits(limits):
        with OpenBag(path) as bag:
            return _read(bag, robot_description, tuple(tf_topics), joint_states_topic,
                         description_topic)


def _read(bag: OpenBag, robot_description: str | os.PathLike[str] | RobotDescription | None,
          tf_topics: tuple[str, ...], joint_states_topic: str | None,
          description_topic: str | None) -> FrameTree:
    uses: dict[str, str] = {}
    for topic in tf_topics:
        if topic in bag.topics:
            check_type(bag, bag.topics[topic], TF_TYPES)
            uses[topic] = "tf static" if topic.endswith("_static") else "tf"
    if joint_states_topic in bag.topics:
        check_type(bag, bag.topics[joint_states_topic], JOINT_STATE_TYPES)
        uses[joint_states_topic] = "joint states"
    if robot_description is None and description_topic in bag.topics:
        check_type(bag, bag.topics[description_topic], DESCRIPTION_TYPES)
        uses[description_topic] = "robot description"
    for described, states_topic in _namespaced_robots(bag, description_topic,
                                                      joint_states_topic).items():
        check_type(bag, bag.topics[described], DESCRIPTION_TYPES)
        uses[described] = "robot description"
        if states_topic in bag.topics:
            check_type(bag, bag.topics[states_topic], JOINT_STATE_TYPES)
            uses[states_topic] = "joint states"
    raw = _raw_messages(bag, list(uses))
    tf_raw = [(topic, received, data) for topic, received, data in raw
              if uses[topic] in ("tf", "tf static")]
    columns = _decoded(bag, tf_raw)
    static_messages = np.array([uses[topic] == "tf static" for topic, _, _ in tf_raw], bool)
    tracks = frame_tracks(columns, static_messages[columns.message_index], bag.path,
                          bag.ros_version)
    descriptions = [(topic, received, data) for topic, received, data in raw
                    if uses[topic] == "robot description"]
    robot = _robot(bag, robot_description, [message for message in descriptions
                                            if message[0] == description_topic])
    robots = [robot] if robot is not None else []
    for topic in dict.fromkeys(message[0] for message in descriptions
                               if message[0] != description_topic):
        namespaced = _robot(bag, None, [message for message in descriptions
                                        if message[0] == topic])
        if namespaced is None:
            continue
        if any(link in known.links for known in robots for link in namespaced.links):
            warn_at_caller(f"{bag.path}: the robot description on {topic} names links "
                           "another description has (the same robot twice?); not used",
                           BagWarning)
            continue
        robots.append(namespaced)
    if not tracks and not robots:
        raise FileFormatError(
            f"no tf messages on {', '.join(tf_topics) or 'no topic'} and no robot "
            f"description; the bag's topics: {', '.join(bag.topics) or 'none'}", file=bag.path)
    states = [_deserialised(bag, topic, received, data) for topic, received, data in raw
              if uses[topic] == "joint states"]
    joints = joint_samples(states, bag.path, bag.ros_version)
    tree = assemble_tree(bag.path.stem if bag.path.suffix else bag.path.name, tracks, robots,
                         joints if robots else {}, bag.path)
    tree.metadata[ROSBAG_METADATA_KEY] = _summary(bag, uses, tracks, joints, tree,
                                                  bool(robots))
    return tree


def _namespaced_robots(bag: OpenBag, description_topic: str | None,
                       joint_states_topic: str | None) -> dict[str, str | None]:
    """Robots published in namespaces, one ``robot_state_publisher`` each (what
    ``pinframes.write`` writes for several robots): every ``<namespace>/robot_description``
    topic (the last part of ``description_topic``) with its ``<namespace>/joint_states``
    (the last part of ``joint_states_topic``)."""
    if description_topic is None:
        return {}
    ending = "/" + description_topic.rsplit("/", 1)[-1]
    states = None if joint_states_topic is None else joint_states_topic.rsplit("/", 1)[-1]
    return {topic: None if states is None else topic[:-len(ending)] + "/" + states
            for topic in bag.topics
            if topic.endswith(ending) and topic != description_topic and len(topic) > len(ending)}


def _raw_messages(bag: OpenBag, topics: list[str]) -> list[tuple[str, int, bytes]]:
    """The messages of ``topics`` in receive order, within ``max_decompressed_bytes``."""
    budget = current_limits().max_decompressed_bytes
    messages, total = [], 0
    for message in bag.messages(topics):
        total += len(message[2])
        if total > budget:
            raise exceeded("max_decompressed_bytes", f"the messages of {', '.join(topics)} "
                           f"take more than {total:,} bytes").located(file=bag.path)
        messages.append(message)
    return messages


def _decoded(bag: OpenBag, tf_raw: list[tuple[str, int, bytes]]) -> TransformColumns:
    try:
        return decode_tf_messages([data for _, _, data in tf_raw], bag.ros_version)
    except CorruptMessage as exc:
        topic, received, _ = tf_raw[exc.index]
        raise FileFormatError(f"a corrupt tf message received at {stamp_iso(received)}: "
                              f"{exc.reason}", file=bag.path, field=topic) from None


def _deserialised(bag: OpenBag, topic: str, received: int, data: bytes) -> Any:
    """A JointState or String message; a corrupt one names the topic and time."""
    try:
        return deserialise(bag.ros_version, data, bag.topics[topic].message_type)
    except Exception as exc:  # rosbags' SerdeError and what its generated code raises
        raise FileFormatError(f"a corrupt message received at {stamp_iso(received)}: {exc}",
                              file=bag.path, field=topic) from None


def _robot(bag: OpenBag, given: str | os.PathLike[str] | RobotDescription | None,
           recorded: list[tuple[str, int, bytes]]) -> RobotDescription | None:
    """The robot description given, or the last one recorded (None without either)."""
    if isinstance(given, RobotDescription):
        return given
    if given is not None:
        return parse_urdf(given)
    if not recorded:
        return None
    topic, received, data = recorded[-1]
    text = _deserialised(bag, topic, received, data).data
    if not text.lstrip().startswith("<"):  # parse_urdf would take the text for a path
        shown = text.strip()[:60] + ("..." if len(text.strip()) > 60 else "")
        raise FileFormatError(f"the robot description is not a URDF: expected its XML text, "
                              f"got {shown!r}", file=bag.path, field=topic)
    try:
        return parse_urdf(text)
    except PinframesError as exc:
        raise FileFormatError(f"the robot description is not a URDF: {exc.message}",
                              file=bag.path, field=topic) from None


def _summary(bag: OpenBag, uses: dict[str, str], tracks: dict[str, FrameTrack],
             joints: dict[str, JointSamples], tree: FrameTree, with_robot: bool
             ) -> dict[str, Any]:
    """What ``pinframes info`` shows of a bag besides the tree."""
    first = reference_stamp(tracks, joints if with_robot else {})
    stamps = [int(t.stamps_ns[-1]) for t in tracks.values() if not t.static]
    stamps += [int(s.stamps_ns[-1]) for s in joints.values()] if with_robot else []
    return {
        "file": os.fspath(bag.path), "kind": bag.kind,
        "topics": [{"name": topic.name, "type": topic.message_type, "messages": topic.count,
                    "use": uses.get(topic.name)} for topic in bag.topics.values()],
        "time_span": None if first is None else [stamp_iso(first), stamp_iso(max(stamps))],
        "joint_states_not_used": [name for name in joints
                                  if name not in tree.joints or not with_robot
                                  or tree.joint_trajectory(name) is None],
    }


