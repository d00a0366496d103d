"""``write_rosbag``: a tree recorded as a ROS system publishes it, in a ROS 1 bag, an MCAP
file or a ROS 2 bag folder, written with rosbags' writers (see :mod:`._tree_topics` for
which part goes on which topic, :mod:`._bag_writer` for the kinds of bags).

Stamps: the tree's reference time plus the times (else the earliest reference time of its
moving frames; a tree without any counts from ``time_ref`` when given, else from 0, i.e.
1970-01-01; bags hold no stamp before that). ``/tf_static`` and the robot descriptions are
written once, at the first stamp; ``/tf`` holds one ``TFMessage`` per time with every
moving frame (robot links on joints that are not fixed included), and each robot's joint
states one ``JointState`` per time with each of its driven joints (its rest value where it
has no samples).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import InvalidTimeError, PinframesError
from ...tree import FrameTree
from ...values.timeconv import TimeAxis, parse_time_axis, parse_timestamp, timestamp_ns
from .._paths import path_argument
from .._writable import check_writable_tree, refuse_attached_data
from . import _outgoing as outgoing
from ._bag_writer import TF_TYPE, BagWriter, check_stamps, output_kind
from ._storage import ROS1
from ._tf_encoding import encode_tf_messages
from ._tree_topics import TreeTopics, tree_topics

__all__ = ["write_rosbag"]

JOINT_STATE_TYPE = "sensor_msgs/msg/JointState"
STRING_TYPE = "std_msgs/msg/String"


def write_rosbag(tree: FrameTree, path: str | os.PathLike[str], *, times: Any = None,
                 time_ref: Any = None) -> None:
    """Write ``tree`` as a ROS bag, atomically: ``name.bag`` (ROS 1), ``name.mcap`` (one
    MCAP file), ``name.db3`` (one ROS 2 SQLite file), or any other name (a ROS 2 bag folder
    with MCAP storage).

    Parameters
    ----------
    tree : FrameTree
    path : path
    times : None or times
        When to take the moving frames and joints (relative times count from ``time_ref``,
        else from the tree's reference time). None: every keyframe and joint sample of the
        tree (``tree.time_union()``); a tree in which nothing moves: one time.
    time_ref : None or timestamp
        What relative ``times`` count from; for a tree without any reference time, also
        where its own times start on the bag's clock (else at 1970-01-01).

    Static frames go on ``/tf_static``, moving ones on ``/tf``, robots' URDFs and joint
    values on their description and joint-state topics (their links on tf as
    ``robot_state_publisher`` publishes them). Reading the bag back
    (:func:`pinframes.read`) gives the same poses at the written times. Data attached to
    frames cannot go into a bag, nor a frame name with a leading ``/`` (tf2 drops it): both
    are an :class:`~pinframes.errors.UnsupportedFeatureError`. Subsystems are not written.
    """
    check_writable_tree(tree, path)
    refuse_attached_data(tree, path, "a ROS bag")
    try:  # everything that can be refused is, before the bag is opened
        topics = tree_topics(tree)
        stamps, query = _stamps(tree, times, time_ref)
        check_stamps(int(stamps[0]), int(stamps[-1]), output_kind(path) == ROS1, "the tree")
        translations, quaternions = _moving_poses(tree, topics.moving, query,
                                                  stamps.shape[0])
        joints = [name for robot in topics.robots for name in robot.joints]
        values = _joint_values(tree, joints, query, stamps.shape[0])
    except PinframesError as exc:
        raise exc.located(file=path_argument(path)) from None
    with BagWriter(path) as bag:
        _write(bag, tree, topics, stamps, translations, quaternions, dict(zip(joints, values,
                                                                             strict=True)))


def _write(bag: BagWriter, tree: FrameTree, topics: TreeTopics, stamps: NDArray[np.int64],
           translations: NDArray[np.float64], quaternions: NDArray[np.float64],
           values: dict[str, NDArray[np.float64]]) -> None:
    first = int(stamps[0])
    if topics.static:
        bag.topic("/tf_static", TF_TYPE, latched=True)
        static = [tree.local_pose(frame) for frame in topics.static]
        message = next(outgoing.transforms(
            bag.types, _parents(tree, topics.static), topics.static, stamps[:1],
            np.array([pose.translation for pose in static])[:, None],
            np.array([pose.quaternion for pose in static])[:, None]))
        bag.write("/tf_static", first, message)
    for robot in topics.robots:
        bag.topic(robot.description_topic, STRING_TYPE, latched=True)
        bag.write(robot.description_topic, first, outgoing.text(bag.types, robot.description))
        if robot.joints:
            bag.topic(robot.joint_states_topic, JOINT_STATE_TYPE)
    moving = _moving_messages(bag, tree, topics.moving, stamps, translations, quaternions)
    for index, stamp in enumerate(stamps.tolist()):
        if moving is not None:
            bag.write_raw("/tf", stamp, moving[index].data)
        for robot in topics.robots:
            if robot.joints:
                bag.write(robot.joint_states_topic, stamp, outgoing.joint_state(
                    bag.types, stamp, robot.joints,
                    [float(values[name][index]) for name in robot.joints]))


def _moving_messages(bag: BagWriter, tree: FrameTree, frames: tuple[str, ...],
                     stamps: NDArray[np.int64], translations: NDArray[np.float64],
                     quaternions: NDArray[np.float64]) -> NDArray[np.uint8] | None:
    """The ``/tf`` messages, serialised: the first by rosbags, the others in bulk from it
    (:mod:`._tf_encoding`); None without moving frames."""
    if not frames:
        return None
    bag.topic("/tf", TF_TYPE)
    parents = _parents(tree, frames)
    first = next(outgoing.transforms(bag.types, parents, frames, stamps[:1],
                                     translations[:, :1], quaternions[:, :1]))
    return encode_tf_messages(bag.serialise(first, TF_TYPE), bag.ros_version, parents, frames,
                              stamps, translations, quaternions)


def _parents(tree: FrameTree, frames: tuple[str, ...]) -> list[str]:
    return [str(tree.parent(frame)) for frame in frames]


def _stamps(tree: FrameTree, times: Any, time_ref: Any
            ) -> tuple[NDArray[np.int64], NDArray[Any] | None]:
    """The stamps (ns since the epoch) and the times to query the tree at (None: nothing
    moves and no times were given)."""
    union = tree.time_union()
    basis = tree.reference_time if tree.reference_time is not None else (
        None if union is None else union.reference)
    anchor = None if time_ref is None else parse_timestamp(time_ref, field="time_ref")
    if times is None:
        start = basis if basis is not None else anchor
        start_ns = 0 if start is None else timestamp_ns(start)
        if union is None:
            return np.array([start_ns], np.int64), None
        return _checked(union.offsets) + start_ns, union.as_numpy()
    axis = parse_time_axis(times)
    if axis.is_absolute:
        assert axis.reference is not None
        return _checked(axis.offsets) + timestamp_ns(axis.reference), axis.as_numpy()
    start = anchor if anchor is not None else basis
    query = TimeAxis(axis.offsets, anchor if anchor is not None and basis is not None
                     else None)
    return (_checked(axis.offsets) + (0 if start is None else timestamp_ns(start)),
            query.as_numpy())


def _checked(offsets: NDArray[np.int64]) -> NDArray[np.int64]:
    if offsets.shape[0] == 0:
        raise InvalidTimeError("no times given", field="times")
    if np.any(np.diff(offsets) <= 0):
        raise InvalidTimeError("times must be strictly increasing", field="times")
    return offsets


def _moving_poses(tree: FrameTree, frames: tuple[str, ...], query: NDArray[Any] | None,
                  count: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Translations (F, T, 3) and quaternions (F, T, 4) of the moving ``frames`` in their
    parents at the ``count`` times of ``query``."""
    if not frames:
        return np.empty((0, count, 3)), np.empty((0, count, 4))
    stack = tree.poses(frames, None, times=query)
    translations, quaternions = stack.translation, stack.quaternion
    if translations.ndim == 2:  # nothing moved: one static pose each
        translations, quaternions = translations[:, None], quaternions[:, None]
    return translations, quaternions


def _joint_values(tree: FrameTree, joints: list[str], query: NDArray[Any] | None,
                  count: int) -> list[NDArray[np.float64]]:
    """The values of ``joints`` at the ``count`` times of ``query``: sampled as the tree
    samples them, or the rest value of a joint without samples."""
    sampled = tree.resampled(query) if query is not None and joints else None
    values = []
    for name in joints:
        trajectory = None if sampled is None else sampled.joint_trajectory(name)
        if trajectory is None:
            values.append(np.full(count, tree.joints[name].rest_value))
        else:
            values.append(np.asarray(trajectory.values, np.float64))
    return values
