"""Answering ``FrameTree.pose`` from a :class:`TreeDescription`: compile once, evaluate per call.

A query between two frames whose nearest joints coincide has nothing moving between them
and is one cached static transform. Otherwise the frames between them and their lowest
common ancestor are compiled into a :class:`~pinframes.kinematics._model.CompiledModel`
rooted at that ancestor, so the cost of a query depends on its path, not on the tree.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ExtrapolationError, InvalidTimeError, JointWithoutSamplesWarning
from ..values._interpolation import Keyframes, segment_positions
from ..values._se3 import IDENTITY, Transform, compose, inverse, to_stacks
from ..values._timeline import QueryTimeline, TimedSource, plan_query_timeline
from ..values.joint import Joint, mimic_chain
from ..values.pose import Pose, trusted_pose
from ..values.timeconv import TimeAxis, parse_time_axis, timestamp_ns
from ._description import TreeDescription, paths_to_common_ancestor
from ._model import CompiledModel, compile_model
from ._one_time import one_time_plan, takes_few_times

__all__ = [
    "CHUNK",
    "Evaluation",
    "basis_shifts",
    "checked_timeline",
    "default_times",
    "evaluate_pose",
    "model_sources",
    "plan_timeline",
    "prepare_evaluation",
    "sample_joint_values",
    "sample_joints",
]

_EXTRAPOLATION_POLICIES = ("clamp", "error")
CHUNK = 1 << 12
"""Samples evaluated at once: the temporaries of a chunk (under 300 kB each) stay in the
CPU caches; 2,048-8,192 ran alike, 16,384 1.8x slower (Panda, 10^5 samples, one thread)."""


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
    tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
    extrapolation: str,
) -> Pose:
    """``tree.pose(frame, relative_to, times, time_ref)``; arguments already checked."""
    evaluation = prepare_evaluation(tree, frame, relative_to)
    sources = list(evaluation.sources)
    timeline = checked_timeline(tree, evaluation, times, time_ref, extrapolation)
    offsets = timeline.result_offsets
    if evaluation.static is not None:
        if offsets is None:
            return trusted_pose(*evaluation.static)
        rotation, translation = to_stacks(evaluation.static, offsets.shape[0])
    elif evaluation.model is not None and takes_few_times(timeline, evaluation.model):
        # Pinocchio's own kinematics, time by time
        plan = one_time_plan(tree, evaluation.model, frame, relative_to)
        if plan.holds_rest_values:
            _warn_joints_without_samples(tree)
        rotation, translation = plan.poses(timeline.evaluation_times,
                                           basis_shifts(sources, timeline))
    else:
        rotation, translation = _evaluate_in_chunks(tree, evaluation, sources, timeline)
    if offsets is None:
        return trusted_pose(rotation[0], translation[0])
    return trusted_pose(rotation, translation, offsets, timeline.reference)


def checked_timeline(
    tree: TreeDescription, evaluation: Evaluation, times: Any, time_ref: Any,
    extrapolation: str,
) -> QueryTimeline:
    """The timeline of a query, with its ``extrapolation`` policy checked and applied."""
    if extrapolation not in _EXTRAPOLATION_POLICIES:
        raise ExtrapolationError(f"expected one of {', '.join(_EXTRAPOLATION_POLICIES)}, "
                                 f"got {extrapolation!r}", field="extrapolation")
    sources = list(evaluation.sources)
    timeline = plan_timeline(tree, sources, times, time_ref)
    if extrapolation == "error" and timeline.evaluation_times is not None:
        _check_within_keyframes(sources, timeline)
    return timeline


def default_times(tree: TreeDescription, frame: str, relative_to: str) -> TimeAxis | None:
    """The times ``tree.pose(frame, relative_to)`` evaluates at when given none."""
    evaluation = prepare_evaluation(tree, frame, relative_to)
    timeline = plan_timeline(tree, list(evaluation.sources), None, None)
    offsets = timeline.result_offsets
    if offsets is None:
        return None
    return TimeAxis(offsets, timeline.reference)


def prepare_evaluation(tree: TreeDescription, frame: str, relative_to: str) -> Evaluation:
    """The query path from ``frame`` to ``relative_to``, compiled once per tree version."""
    key = (frame, relative_to)
    cached = tree.cached(key)
    if cached is not None:
        return cached
    anchor, placement = tree.anchor(frame)
    reference_anchor, reference_placement = tree.anchor(relative_to)
    if anchor == reference_anchor:
        evaluation = Evaluation(frame, relative_to, compose(inverse(reference_placement),
                                                            placement))
    else:
        up, _ = paths_to_common_ancestor(tree.parents, tree.depths, frame, relative_to)
        model = compile_model(tree, up[-1], [frame, relative_to])
        keyframes = tuple(
            None if joint.joint is not None else _placed_keyframes(
                tree.local_poses[joint.frame].keyframes, model.joint_placements[position])
            for position, joint in enumerate(model.joints))
        evaluation = Evaluation(frame, relative_to, None, model, keyframes,
                                tuple(model_sources(tree, model)))
    tree.store(key, evaluation)
    return evaluation


def _placed_keyframes(keyframes: Keyframes, placement: Transform) -> Keyframes:
    """Keyframes of ``placement @ pose``: a static factor on the left commutes with
    linear interpolation and SLERP, so it can be applied to the keyframes once."""
    if placement is IDENTITY:
        return keyframes
    rotation, translation = placement
    return Keyframes(keyframes.times, rotation @ keyframes.rotations,
                     keyframes.translations @ rotation.T + translation)


def plan_timeline(
    tree: TreeDescription, sources: list[TimedSource], times: Any, time_ref: Any
) -> QueryTimeline:
    """The evaluation times of a query on ``sources`` (SPEC section 4)."""
    return plan_query_timeline(sources, _requested_times(tree, times), time_ref,
                               tree.reference_time, tree.has_frame_references)


def model_sources(tree: TreeDescription, model: CompiledModel) -> list[TimedSource]:
    """The moving frames and driven joints whose values a compiled model needs."""
    sources: dict[str, TimedSource] = {}
    for joint in model.joints:
        if joint.joint is None:
            pose = tree.local_poses[joint.frame]
            reference = pose.reference_time if pose.reference_time is not None else (
                tree.reference_time)
            sources[joint.frame] = TimedSource(joint.frame, pose.keyframes.times, reference)
            continue
        for name in _driving_joints(tree, joint.joint):
            trajectory = tree.joint_trajectories.get(name)
            if trajectory is not None:
                reference = trajectory.reference if trajectory.reference is not None else (
                    tree.reference_time)
                sources[name] = TimedSource(name, trajectory.times, reference)
    return list(sources.values())


def _driving_joints(tree: TreeDescription, joint: Joint) -> list[str]:
    """``joint`` and, for a mimic joint, the chain of joints it follows."""
    return [link.name for link in mimic_chain(joint, tree.joints_by_name)]


def _requested_times(tree: TreeDescription, times: Any) -> TimeAxis | None:
    if times is None:
        return None
    if isinstance(times, str) and times in tree.depths:
        if not tree.is_moving(times):
            raise InvalidTimeError(f"frame {times!r} does not move, so it has no times to "
                                   "take (a string naming a frame means that frame's "
                                   "keyframe times; pass seconds as a number or as '5s')",
                                   field="times")
        pose = tree.local_poses[times]
        reference = pose.reference_time if pose.reference_time is not None else (
            tree.reference_time)
        return TimeAxis(pose.keyframes.times, reference)
    return parse_time_axis(times, field="times")


def _check_within_keyframes(sources: list[TimedSource], timeline: QueryTimeline) -> None:
    requested = timeline.evaluation_times
    assert requested is not None  # checked only for queries at times
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
    tree: TreeDescription, evaluation: Evaluation, sources: list[TimedSource],
    timeline: QueryTimeline,
) -> Transform:
    """:func:`_evaluate_model` over slices of the timeline, so that the temporary arrays of
    a long query stay small (and cache-friendly); the result, ``(N, 3, 3)`` rotations and
    ``(N, 3)`` translations, is filled in place."""
    times = timeline.evaluation_times
    if times is None:  # nothing on the path is sampled: one static pose
        return to_stacks(_evaluate_model(tree, evaluation, sources, times, timeline), 1)
    count = times.shape[0]
    rotation, translation = np.empty((count, 3, 3)), np.empty((count, 3))
    for start in range(0, count, CHUNK):
        part = slice(start, start + CHUNK)
        rotation[part], translation[part] = to_stacks(
            _evaluate_model(tree, evaluation, sources, times[part], timeline),
            min(count, start + CHUNK) - start)
    return rotation, translation


def _evaluate_model(
    tree: TreeDescription, evaluation: Evaluation, sources: list[TimedSource],
    times: NDArray[np.int64] | None, timeline: QueryTimeline,
) -> Transform:
    """The pose of the query frame in the reference frame at ``times`` (timeline basis),
    samples last (see :mod:`pinframes.values._se3`)."""
    model = evaluation.model
    assert model is not None
    samples = sample_joints(tree, model, evaluation.placed_keyframes, times,
                            basis_shifts(sources, timeline))
    frame_pose, reference_pose = model.forward_kinematics(
        samples, [evaluation.frame, evaluation.relative_to])
    return compose(inverse(reference_pose), frame_pose)


def sample_joints(
    tree: TreeDescription, model: CompiledModel, keyframes: Sequence[Keyframes | None],
    times: NDArray[np.int64] | None, shifts: dict[str, int],
) -> list[Any]:
    """Every joint of ``model`` at ``times`` (timeline basis): the one sampling step of a
    query and of :meth:`PinocchioTree.configurations`.

    A free-flyer gets its moving frame's ``(rotation, translation)`` from ``keyframes[i]``,
    samples last (``(3, 3, N)``, ``(3, N)``); a robot joint its value(s) (radians or metres):
    its trajectory, its mimic primary's, or 0.
    """
    cache: dict[str, NDArray[np.float64] | float] = {}
    segments: dict[str, tuple[NDArray[np.intp], NDArray[np.float64]]] = {}
    samples: list[Any] = []
    for joint, frames in zip(model.joints, keyframes, strict=True):
        if joint.joint is None:
            assert frames is not None and times is not None
            samples.append(frames.transform_at(times - shifts[joint.frame]))
        else:
            samples.append(sample_joint_values(tree, joint.joint, times, shifts, cache,
                                               segments))
    return samples


def basis_shifts(sources: list[TimedSource], timeline: QueryTimeline) -> dict[str, int]:
    """Per source, what to subtract from timeline times to land on its own time basis."""
    return {
        s.name: timestamp_ns(s.reference)
        if timeline.absolute and s.reference is not None else 0
        for s in sources
    }


def sample_joint_values(
    tree: TreeDescription, joint: Joint, times: NDArray[np.int64] | None,
    shifts: dict[str, int], cache: dict[str, NDArray[np.float64] | float],
    segments: dict[str, tuple[NDArray[np.intp], NDArray[np.float64]]] | None = None,
) -> NDArray[np.float64] | float:
    """Values of ``joint`` at ``times``: its trajectory, its mimic primary's, or its rest
    value.

    ``cache`` keeps the values per joint name, ``segments`` the segment positions per
    trajectory times array, for the other joints sampled at the same ``times``.
    """
    if joint.name in cache:
        return cache[joint.name]
    trajectory = tree.joint_trajectories.get(joint.name)
    if joint.mimic is not None:
        primary = sample_joint_values(tree, tree.joints_by_name[joint.mimic.joint], times, shifts,
                                      cache, segments)
        value = joint.mimic.multiplier * primary + joint.mimic.offset
    elif trajectory is not None:
        assert times is not None  # a driven joint is a source: the query has times
        shifted = times - shifts[joint.name]
        # joints driven together have equal times: search their segments once
        key = f"segments {tree.time_group(joint.name)} {shifts[joint.name]}"
        positions = segments.get(key) if segments is not None else None
        if positions is None:
            positions = segment_positions(trajectory.times, shifted)
            if segments is not None:
                segments[key] = positions
        value = trajectory.sample(shifted, positions)
    else:
        value = joint.rest_value
        _warn_joints_without_samples(tree)
    cache[joint.name] = value
    return value


def _warn_joints_without_samples(tree: TreeDescription) -> None:
    """One :class:`JointWithoutSamplesWarning` per version of a tree, naming its joints
    without samples."""
    if tree._warned_joints_without_samples:
        return
    tree._warned_joints_without_samples.append(True)
    idle = [name for name, joint in tree.joints_by_name.items()
            if joint.is_actuated and name not in tree.joint_trajectories]
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
