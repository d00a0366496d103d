"""Whole-tree time helpers, as weldx's ``time_union`` and ``interp_time`` of a hierarchy.

Keyframes of a moving frame without a reference time of its own, and joint samples likewise,
count from the tree's reference time (docs/time-semantics.md).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentTypeError, InvalidTimeError, ReferenceTimeError
from ..values.joint import mimic_chain
from ..values.joint_trajectory import JointTrajectory
from ..values.pose import Pose
from ..values.timeconv import TimeAxis, parse_time_axis, parse_timestamp, shift_ns, timestamp_ns
from ..values.timeline import TimedSource, plan_query_timeline, source_reference
from ._structure import EditableTree
from .grafting import Tree, copy_tree

__all__ = ["resampled", "time_union"]

_Samples = tuple[NDArray[np.int64], "np.datetime64 | None"]


def time_union(tree: EditableTree, frames: Iterable[str] | None = None) -> TimeAxis | None:
    """Every keyframe and joint sample time of ``frames`` (default: all); see
    :meth:`pinframes.FrameTree.time_union`."""
    if isinstance(frames, str):
        raise ArgumentTypeError(f"expected a list of frame names, got the string {frames!r}",
                                field="frames")
    chosen = tree.frames[1:] if frames is None else list(frames)
    sources: list[TimedSource] = []
    for frame in chosen:
        tree.parent(frame)  # a FrameNotFoundError for unknown names
        if frame != tree.root:
            sources.extend(
                TimedSource(frame, times, source_reference(own, tree.reference_time))
                for times, own in _frame_samples(tree, frame))
    # the default times of a query through all of them (docs/time-semantics.md, values.timeline)
    timeline = plan_query_timeline(sources, None, None, tree.reference_time, False)
    offsets = timeline.result_offsets
    return None if offsets is None else TimeAxis(offsets, timeline.reference)


def resampled(tree: Tree, times: Any, time_ref: Any = None) -> Tree:
    """A copy of ``tree`` whose moving frames and joint trajectories are sampled at ``times``
    only; see :meth:`pinframes.FrameTree.resampled`."""
    axis = parse_time_axis(times)
    if axis.offsets.shape[0] > 1 and np.any(np.diff(axis.offsets) <= 0):
        raise InvalidTimeError("times must be strictly increasing", field="times")
    basis = axis.reference if axis.is_absolute else (
        parse_timestamp(time_ref, field="time_ref") if time_ref is not None
        else tree.reference_time)
    instants = None if basis is None else shift_ns(axis.offsets, timestamp_ns(basis))
    copy = copy_tree(tree)
    for frame in copy.frames[1:]:
        joint = copy.joint_of(frame)
        if joint is not None:
            trajectory = copy.joint_trajectory(joint.name)
            if trajectory is not None:
                own = _own_basis(axis, instants, trajectory.reference, tree, frame)
                copy.replace_joint_trajectory(joint.name, JointTrajectory(
                    own, trajectory.reference, trajectory.sample(own), trajectory.interpolation))
            continue
        pose = copy.local_pose(frame)
        if pose.is_time_dependent:
            own = _own_basis(axis, instants, pose.reference_time, tree, frame)
            sampled = pose.at(own.astype("timedelta64[ns]"))
            copy.set_local_pose(frame, Pose(sampled.translation, sampled.rotation,
                                            times=own.astype("timedelta64[ns]"),
                                            reference_time=pose.reference_time))
    return copy


def _frame_samples(tree: EditableTree, frame: str) -> list[_Samples]:
    joint = tree.joint_of(frame)
    if joint is None:
        pose = tree.local_pose(frame)
        times = pose.times
        return [] if times is None else [(times.astype(np.int64), pose.reference_time)]
    driver = mimic_chain(joint, tree.joints)[-1]
    trajectory = tree.joint_trajectory(driver.name)
    return [] if trajectory is None else [(trajectory.times, trajectory.reference)]


def _own_basis(axis: TimeAxis, instants: NDArray[np.int64] | None,
               own: np.datetime64 | None, tree: EditableTree, frame: str) -> NDArray[np.int64]:
    """The requested times as ns on the basis of a pose or trajectory (its own reference time,
    else the tree's, else plain offsets)."""
    reference = source_reference(own, tree.reference_time)
    if instants is None:
        if reference is not None:
            raise ReferenceTimeError("relative times were given, but neither time_ref nor a "
                                     "tree reference time says what they count from",
                                     frame=frame, field="times")
        return axis.offsets
    if reference is None:
        raise ReferenceTimeError("absolute times or a time_ref were given, but this moving "
                                 "frame has no reference time", frame=frame, field="times")
    return shift_ns(instants, -timestamp_ns(reference))
