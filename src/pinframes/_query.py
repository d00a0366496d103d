"""Answering ``FrameTree.pose``: compile the query path once, then evaluate it per call.

A query between two frames whose nearest joints coincide has nothing moving between them
and is one cached static transform. Otherwise the frames between them and their lowest
common ancestor are compiled into a :class:`~pinframes.pinocchio_model.CompiledModel`
rooted at that ancestor, so the cost of a query depends on its path, not on the tree.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ._interpolation import Keyframes
from ._se3 import IDENTITY, Transform, compose, inverse
from ._timeline import QueryTimeline, TimedSource, plan_query_timeline
from .errors import ExtrapolationError, InvalidTimeError, JointWithoutSamplesWarning
from .joint import Joint, mimic_chain
from .pinocchio_model import CompiledJoint, CompiledModel
from .pose import Pose
from .timeconv import TimeAxis, parse_time_axis, timestamp_ns

if TYPE_CHECKING:
    from .tree import FrameTree

__all__ = [
    "Evaluation",
    "basis_shifts",
    "compile_model",
    "default_times",
    "evaluate_pose",
    "model_sources",
    "plan_timeline",
    "sample_joint_values",
]

_EXTRAPOLATION_POLICIES = ("clamp", "error")
_CHUNK = 1 << 15
"""Samples evaluated at once: bounds the temporaries of long queries (about 2 MB each)."""


@dataclass(frozen=True)
class Evaluation:
    """A query path prepared for repeated evaluation.

    Either ``static`` (the pose of the frame in the reference frame, when nothing between
    them can move) or ``model`` with, per joint, the moving frame's keyframes with the
    joint placement folded in (None for robot joints).
    """

    frame: str
    relative_to: str
    static: Transform | None
    model: CompiledModel | None = None
    placed_keyframes: tuple[Keyframes | None, ...] = ()
    sources: tuple[TimedSource, ...] = ()


def evaluate_pose(
    tree: FrameTree, frame: str, relative_to: str, times: Any, time_ref: Any,
    extrapolation: str,
) -> Pose:
    """``tree.pose(frame, relative_to, times, time_ref)``; arguments already checked."""
    if extrapolation not in _EXTRAPOLATION_POLICIES:
        raise ExtrapolationError(f"expected one of {', '.join(_EXTRAPOLATION_POLICIES)}, "
                                 f"got {extrapolation!r}", field="extrapolation")
    evaluation = _evaluation(tree, frame, relative_to)
    sources = list(evaluation.sources)
    timeline = plan_timeline(tree, sources, times, time_ref)
    if extrapolation == "error" and timeline.evaluation_times is not None:
        _check_within_keyframes(sources, timeline)
    if evaluation.static is not None:
        rotation, translation = evaluation.static
    else:
        rotation, translation = _evaluate_in_chunks(tree, evaluation, sources, timeline)
    offsets = timeline.result_offsets
    if offsets is None:
        return Pose._trusted(translation, rotation)
    count = offsets.shape[0]
    if rotation.ndim == 2:
        rotation = np.broadcast_to(rotation, (count, 3, 3)).copy()
    if translation.ndim == 1:
        translation = np.broadcast_to(translation, (count, 3)).copy()
    return Pose._trusted(translation, rotation, offsets, timeline.reference)


def default_times(tree: FrameTree, frame: str, relative_to: str) -> TimeAxis | None:
    """The times ``tree.pose(frame, relative_to)`` evaluates at when given none."""
    evaluation = _evaluation(tree, frame, relative_to)
    timeline = plan_timeline(tree, list(evaluation.sources), None, None)
    if timeline.evaluation_times is None:
        return None
    return TimeAxis(timeline.result_offsets, timeline.reference)


def compile_model(tree: FrameTree, root: str, frames: list[str]) -> CompiledModel:
    """A Pinocchio model rooted at ``root`` holding ``frames`` and every joint above them.

    Every frame in ``frames`` must be ``root`` or below it.
    """
    root_anchor, root_placement = tree._anchor(root)
    root_depth = tree._depth[root]
    from_root_anchor = inverse(root_placement)
    joint_frames: set[str] = set()
    for frame in frames:
        anchor = tree._anchor(frame)[0]
        while tree._depth[anchor] > root_depth and anchor not in joint_frames:
            joint_frames.add(anchor)
            anchor = tree._anchor(tree._parent[anchor])[0]
    # by depth (parents first), then name: the same joint order in every process
    ordered = sorted(joint_frames, key=lambda frame: (tree._depth[frame], frame))
    index = {frame: position for position, frame in enumerate(ordered)}

    def placed(anchor: str, placement: Transform) -> tuple[int, Transform]:
        if anchor in index:
            return index[anchor], placement
        if anchor != root_anchor:
            raise AssertionError(f"{anchor!r} is not below {root!r}")
        return -1, compose(from_root_anchor, placement)

    joints = []
    for frame in ordered:
        parent, placement = placed(*tree._anchor(tree._parent[frame]))
        joint = tree._joints.get(frame)
        if joint is not None:
            origin = tree._local[frame]
            placement = compose(placement, (origin.rotation, origin.translation))
        joints.append(CompiledJoint(frame, parent, placement, joint))
    placements = {frame: placed(*tree._anchor(frame)) for frame in frames}
    return CompiledModel(root, joints, placements)


def _evaluation(tree: FrameTree, frame: str, relative_to: str) -> Evaluation:
    key = (frame, relative_to)
    cached = tree._cached_evaluation(key)
    if cached is not None:
        return cached
    anchor, placement = tree._anchor(frame)
    reference_anchor, reference_placement = tree._anchor(relative_to)
    if anchor == reference_anchor:
        evaluation = Evaluation(frame, relative_to, compose(inverse(reference_placement),
                                                            placement))
    else:
        up, _ = tree._paths_to_common_ancestor(frame, relative_to)
        model = compile_model(tree, up[-1], [frame, relative_to])
        keyframes = tuple(
            None if joint.joint is not None else _placed_keyframes(
                tree._local[joint.frame].keyframes, model.joint_placements[position])
            for position, joint in enumerate(model.joints))
        evaluation = Evaluation(frame, relative_to, None, model, keyframes,
                                tuple(model_sources(tree, model)))
    tree._store_evaluation(key, evaluation)
    return evaluation


def _placed_keyframes(keyframes: Keyframes, placement: Transform) -> Keyframes:
    """Keyframes of ``placement @ pose``: a static factor on the left commutes with
    linear interpolation and SLERP, so it can be applied to the keyframes once."""
    if placement is IDENTITY:
        return keyframes
    rotations, translations = compose(placement, (keyframes.rotations, keyframes.translations))
    return Keyframes(keyframes.times, translations, rotations)


def plan_timeline(
    tree: FrameTree, sources: list[TimedSource], times: Any, time_ref: Any
) -> QueryTimeline:
    """The evaluation times of a query on ``sources`` (SPEC section 4)."""
    return plan_query_timeline(sources, _requested_times(tree, times), time_ref,
                               tree.reference_time, tree._has_frame_references)


def model_sources(tree: FrameTree, model: CompiledModel) -> list[TimedSource]:
    """The moving frames and tracked joints whose values a compiled model needs."""
    sources: dict[str, TimedSource] = {}
    for joint in model.joints:
        if joint.joint is None:
            pose = tree._local[joint.frame]
            reference = pose.reference_time if pose.reference_time is not None else (
                tree.reference_time)
            sources[joint.frame] = TimedSource(joint.frame, pose._times, reference)
            continue
        for name in _driving_joints(tree, joint.joint):
            track = tree.joint_track(name)
            if track is not None:
                reference = track.reference if track.reference is not None else (
                    tree.reference_time)
                sources[name] = TimedSource(name, track.times, reference)
    return list(sources.values())


def _driving_joints(tree: FrameTree, joint: Joint) -> list[str]:
    """``joint`` and, for a mimic joint, the chain of joints it follows."""
    return [link.name for link in mimic_chain(joint, tree.joints)]


def _requested_times(tree: FrameTree, times: Any) -> TimeAxis | None:
    if times is None:
        return None
    if isinstance(times, str) and times in tree:
        if times == tree.root or not tree.is_moving(times):
            raise InvalidTimeError(f"frame {times!r} does not move, so it has no times to "
                                   "take", field="times")
        pose = tree.local_pose(times)
        reference = pose.reference_time if pose.reference_time is not None else (
            tree.reference_time)
        return TimeAxis(pose._times, reference)
    return parse_time_axis(times, field="times")


def _check_within_keyframes(sources: list[TimedSource], timeline: QueryTimeline) -> None:
    requested = timeline.evaluation_times
    first, last = requested.min(), requested.max()
    for source in sources:
        keyframes = source.on_basis(timeline.absolute)
        early, late = keyframes[0] - first, last - keyframes[-1]
        if early > 0 or late > 0:
            sides = ([f"{early / 1e9:.9g} s before its first keyframe"] if early > 0 else []) + (
                [f"{late / 1e9:.9g} s after its last keyframe"] if late > 0 else [])
            raise ExtrapolationError(
                f"requested times reach {' and '.join(sides)} (extrapolation='error')",
                frame=source.name, field="times")


def _evaluate_in_chunks(
    tree: FrameTree, evaluation: Evaluation, sources: list[TimedSource],
    timeline: QueryTimeline,
) -> Transform:
    """:func:`_evaluate_model` over slices of the timeline, so that the temporary arrays of
    a long query stay small (and cache-friendly) while the result is filled in place."""
    times = timeline.evaluation_times
    if times is None or times.shape[0] <= _CHUNK:
        return _evaluate_model(tree, evaluation, sources, times, timeline)
    count = times.shape[0]
    rotation, translation = np.empty((count, 3, 3)), np.empty((count, 3))
    for start in range(0, count, _CHUNK):
        part = slice(start, start + _CHUNK)
        rotation[part], translation[part] = _evaluate_model(
            tree, evaluation, sources, times[part], timeline)
    return rotation, translation


def _evaluate_model(
    tree: FrameTree, evaluation: Evaluation, sources: list[TimedSource],
    times: NDArray[np.int64] | None, timeline: QueryTimeline,
) -> Transform:
    """The pose of the query frame in the reference frame at ``times`` (timeline basis)."""
    model = evaluation.model
    shifts = basis_shifts(sources, timeline)
    local: list[Transform] = []
    values_cache: dict[str, NDArray[np.float64] | float] = {}
    for position, joint in enumerate(model.joints):
        keyframes = evaluation.placed_keyframes[position]
        if keyframes is not None:
            shift = shifts[joint.frame]
            sampled = keyframes.sample(times - shift)
            local.append((sampled[1], sampled[0]))
            continue
        values = sample_joint_values(tree, joint.joint, times, shifts, values_cache)
        rotation, translation = joint.joint.placed_motion(
            model.joint_placements[position], np.atleast_1d(values))
        local.append((rotation, translation) if np.ndim(values) else (rotation[0], translation[0]))
    frame_pose, reference_pose = model.forward_kinematics(
        local, [evaluation.frame, evaluation.relative_to])
    return compose(inverse(reference_pose), frame_pose)


def basis_shifts(sources: list[TimedSource], timeline: QueryTimeline) -> dict[str, int]:
    """Per source, what to subtract from timeline times to land on its own time basis."""
    return {
        s.name: timestamp_ns(s.reference)
        if timeline.absolute and s.reference is not None else 0
        for s in sources
    }


def sample_joint_values(
    tree: FrameTree, joint: Joint, times: NDArray[np.int64] | None,
    shifts: dict[str, int], cache: dict[str, NDArray[np.float64] | float],
) -> NDArray[np.float64] | float:
    """Values of ``joint`` at ``times``: its track, its mimic primary's, or its rest value."""
    if joint.name in cache:
        return cache[joint.name]
    track = tree.joint_track(joint.name)
    if joint.mimic is not None:
        primary = sample_joint_values(tree, tree.joints[joint.mimic.joint], times, shifts,
                                      cache)
        value = joint.mimic.multiplier * primary + joint.mimic.offset
    elif track is not None:
        value = track.sample(times - shifts[joint.name])
    else:
        value = joint.rest_value
        _warn_joints_without_samples(tree)
    cache[joint.name] = value
    return value


def _warn_joints_without_samples(tree: FrameTree) -> None:
    """One :class:`JointWithoutSamplesWarning` per tree, naming its joints without samples."""
    if tree._warned_joints_without_samples:
        return
    tree._warned_joints_without_samples = True
    idle = [name for name, joint in tree.joints.items()
            if joint.is_actuated and tree.joint_track(name) is None]
    named = ", ".join(repr(name) for name in idle[:4]) + (
        f" and {len(idle) - 4} more" if len(idle) > 4 else "")
    many = len(idle) > 1
    subject = f"joints {named} have" if many else f"joint {named} has"
    warnings.warn(
        f"{subject} no samples and {'hold' if many else 'holds'} the rest value (0, or the "
        "limit nearest to 0); give values with FrameTree.set_joint_trajectory(times, "
        "positions, joint_names) or a scene robot's 'trajectory' file",
        JointWithoutSamplesWarning,
        stacklevel=2)
