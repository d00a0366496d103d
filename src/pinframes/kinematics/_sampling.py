"""How a compiled path's joints are sampled at times: the one sampling step of every query
and of :meth:`PinocchioTree.configurations`.

A path is planned once with a sampler per joint (:func:`path_samplers`): a free-flyer is a
:class:`MovingFrame` (its frame's keyframes), a robot joint a :class:`DrivenJoint` (the
joint whose trajectory drives it, itself or its mimic primary, and the mimic links out to
it). Sampling then reads the samplers alone: a free-flyer gets its moving frame's
interpolated pose, a robot joint its value (radians or metres) from its driver's trajectory
or its rest value (with one warning per tree version naming the joints without samples).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InvalidTimeError, JointWithoutSamplesWarning, warn_at_caller
from ..values.interpolation import Keyframes, SegmentSearches
from ..values.joint import Joint, mimic_chain
from ..values.joint_trajectory import JointTrajectory
from ..values.se3 import samples_first
from ..values.timeconv import TimeAxis
from ..values.timeline import TimedSource, source_reference
from ._description import TreeDescription
from ._model import CompiledModel

__all__ = [
    "KERNEL_CHUNK",
    "DrivenJoint",
    "JointSampler",
    "MovingFrame",
    "frame_source",
    "frame_times",
    "joint_sampler",
    "joint_source",
    "path_samplers",
    "sample_configurations",
    "sample_joints",
    "warn_joints_without_samples",
]

KERNEL_CHUNK = 1 << 12
"""Samples the numpy kernels evaluate at once: the temporaries of a chunk (under 300 kB
each) stay in the CPU caches; 2,048-8,192 ran alike, 16,384 1.8x slower (Panda, 10^5
samples, one thread)."""


@dataclass(frozen=True)
class MovingFrame:
    """A free-flyer: the moving frame ``frame``, its keyframes in its parent (for Pinocchio's
    configuration, whose model holds the joint's placement) and ``placed``, the same with
    that placement folded in (:meth:`Keyframes.placed`, for the batched kernels)."""

    frame: str
    keyframes: Keyframes
    placed: Keyframes


@dataclass(frozen=True)
class DrivenJoint:
    """A robot joint: its value is that of ``primary`` (itself unless it mimics one) from
    ``trajectory``, whose times it shares with the joints of ``time_group`` (see
    :attr:`TreeDescription.time_groups`), or, without one, ``rest`` (radians or metres);
    then each mimic link's ``(multiplier, offset)`` from the primary out to the joint."""

    name: str
    primary: str
    trajectory: JointTrajectory | None
    time_group: str
    rest: float
    mimics: tuple[tuple[float, float], ...]

    @property
    def multiplier(self) -> float:
        """How fast the joint moves per unit velocity of its primary."""
        return math.prod(multiplier for multiplier, _ in self.mimics)


JointSampler = MovingFrame | DrivenJoint


def path_samplers(tree: TreeDescription, model: CompiledModel
                  ) -> tuple[tuple[JointSampler, ...], tuple[TimedSource, ...], frozenset[str]]:
    """Per joint of ``model`` its sampler, the moving frames and driven joints (a mimic
    joint's chain of primaries included) whose samples they read, and the joints without
    samples that drive them (held at their rest value)."""
    samplers: list[JointSampler] = []
    moving: dict[str, tuple[Any, np.datetime64 | None]] = {}  # times and own reference
    for position, joint in enumerate(model.joints):
        if joint.joint is not None:
            samplers.append(joint_sampler(tree, joint.joint))
            for link in mimic_chain(joint.joint, tree.joints_by_name):
                driven = tree.joint_trajectories.get(link.name)
                if driven is not None:
                    moving[link.name] = (driven.times, driven.reference)
            continue
        pose = tree.local_poses[joint.frame]
        keyframes = pose.keyframes
        samplers.append(MovingFrame(joint.frame, keyframes,
                                    keyframes.placed(model.joint_placements[position])))
        moving[joint.frame] = (keyframes.times, pose.reference_time)
    sources = tuple(TimedSource(name, times, source_reference(own, tree.reference_time))
                    for name, (times, own) in moving.items())
    resting = frozenset(sampler.primary for sampler in samplers
                        if isinstance(sampler, DrivenJoint) and sampler.trajectory is None)
    return tuple(samplers), sources, resting


def joint_sampler(tree: TreeDescription, joint: Joint) -> DrivenJoint:
    """The sampler of one robot joint of ``tree``."""
    chain = mimic_chain(joint, tree.joints_by_name)
    primary = chain[-1]
    trajectory = tree.joint_trajectories.get(primary.name)
    return DrivenJoint(
        joint.name, primary.name, trajectory,
        "" if trajectory is None else tree.time_groups[primary.name], primary.rest_value,
        tuple((link.mimic.multiplier, link.mimic.offset)
              for link in reversed(chain[:-1]) if link.mimic is not None))


def frame_times(tree: TreeDescription, frame: str) -> TimeAxis:
    """The keyframe times of the moving frame ``frame``, for a query's ``times=frame``."""
    if not tree.is_moving(frame):
        raise InvalidTimeError(f"frame {frame!r} does not move, so it has no times to take "
                               "(a string naming a frame means that frame's keyframe times; "
                               "pass seconds as a number or as '5s')", field="times")
    source = frame_source(tree, frame)
    return TimeAxis(source.times, source.reference)


def frame_source(tree: TreeDescription, frame: str) -> TimedSource:
    """The keyframe times of the moving frame ``frame`` and what they count from."""
    pose = tree.local_poses[frame]
    return TimedSource(frame, pose.keyframes.times,
                       source_reference(pose.reference_time, tree.reference_time))


def joint_source(tree: TreeDescription, joint_name: str) -> TimedSource:
    """The sample times of the driven joint ``joint_name`` and what they count from."""
    trajectory = tree.joint_trajectories[joint_name]
    return TimedSource(joint_name, trajectory.times,
                       source_reference(trajectory.reference, tree.reference_time))


def sample_joints(
    samplers: Sequence[JointSampler], times: NDArray[np.int64] | None,
    shifts: Mapping[str, int], searches: SegmentSearches | None = None,
    held: Mapping[str, NDArray[np.float64] | float] | None = None, placed: bool = True,
) -> list[Any]:
    """Every joint of a path at ``times`` (timeline basis, ns).

    A free-flyer gets its moving frame's ``(rotation, translation)``, samples last (``(3,
    3, N)``, ``(3, N)``), with its placement folded in (``placed``) or in its parent; a
    robot joint its value(s) (radians or metres). ``shifts`` holds, per source, what to
    subtract from a timeline time to land on its own time basis; ``searches`` may pass the
    caller's :class:`SegmentSearches` of ``times`` (to reuse them for rates). ``held`` gives
    joints (by name) values (one, or one per time) instead of their samples; their mimic
    joints follow them.
    """
    if searches is None:
        searches = SegmentSearches(times, shifts)
    values: dict[str, NDArray[np.float64] | float] = dict(held or {})
    samples: list[Any] = []
    for sampler in samplers:
        if isinstance(sampler, MovingFrame):
            keyframes = sampler.placed if placed else sampler.keyframes
            segments = searches.of_frame(sampler.frame, keyframes.times)
            samples.append(keyframes.transform_at(segments.times, segments))
            continue
        value = values.get(sampler.primary)
        if value is None:
            trajectory = sampler.trajectory
            if trajectory is None:
                value = sampler.rest
            else:
                segments = searches.of_joints(sampler.time_group, sampler.primary,
                                              trajectory.times)
                value = trajectory.sample(segments.times, segments)
            values[sampler.primary] = value
        for multiplier, offset in sampler.mimics:  # from the primary out to the joint
            value = multiplier * value + offset
        samples.append(value)
    return samples


def sample_configurations(
    model: CompiledModel, samplers: Sequence[JointSampler], times: NDArray[np.int64],
    shifts: Mapping[str, int], held: Mapping[str, NDArray[np.float64] | float] | None = None,
) -> NDArray[np.float64]:
    """Pinocchio configurations ``q`` of ``model``, shape ``(N, nq)``, at ``times`` (timeline
    basis, ns): each free-flyer the interpolated pose of its moving frame in the frame's
    parent (``x y z qx qy qz qw``; the model holds the joint's placement), each robot joint
    its value as :func:`sample_joints` gives it (with ``held``)."""
    if not model.joints:
        return np.zeros((times.shape[0], 0))
    samples = sample_joints(samplers, times, shifts, held=held, placed=False)
    motions = [samples_first(sample) if isinstance(sampler, MovingFrame) else None
               for sampler, sample in zip(samplers, samples, strict=True)]
    values = [None if isinstance(sampler, MovingFrame) else sample
              for sampler, sample in zip(samplers, samples, strict=True)]
    return model.configuration(motions, values, times.shape[0])


def warn_joints_without_samples(tree: TreeDescription, resting: Collection[str],
                                held: Collection[str] = ()) -> None:
    """One :class:`JointWithoutSamplesWarning` per version of a tree, naming its joints
    without samples, when one of the ``resting`` joints (without samples, held at their
    rest value) is not ``held`` (given its values by the caller)."""
    if all(name in held for name in resting):
        return
    if not tree.first_warning("joints without samples"):
        return
    idle = [name for name, joint in tree.joints_by_name.items()
            if joint.is_actuated and name not in tree.joint_trajectories]
    named = ", ".join(repr(name) for name in idle[:4]) + (
        f" and {len(idle) - 4} more" if len(idle) > 4 else "")
    many = len(idle) > 1
    subject = f"joints {named} have" if many else f"joint {named} has"
    warn_at_caller(
        f"{subject} no samples and {'hold' if many else 'holds'} the rest value (0, or the "
        "limit nearest to 0); give values with FrameTree.set_joint_trajectory(times, "
        "positions, joint_names) or a scene robot's 'trajectory' file",
        JointWithoutSamplesWarning)
