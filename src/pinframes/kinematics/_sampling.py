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

from ..errors import JointWithoutSamplesWarning, warn_at_caller
from ..values.interpolation import Keyframes, Segments
from ..values.joint import Joint, mimic_chain
from ..values.joint_trajectory import JointTrajectory
from ..values.se3 import samples_first
from ..values.timeline import TimedSource, source_reference
from ._description import TreeDescription
from ._model import CompiledModel

__all__ = ["KERNEL_CHUNK", "DrivenJoint", "JointSampler", "MovingFrame", "SegmentSearches",
           "frame_source", "joint_sampler", "joint_source", "path_samplers",
           "sample_configurations", "sample_joints", "warn_joints_without_samples"]

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

    def follow(self, primary: Any) -> Any:
        """The joint's value(s) from its primary's."""
        for multiplier, offset in self.mimics:
            primary = multiplier * primary + offset
        return primary


JointSampler = MovingFrame | DrivenJoint


def path_samplers(tree: TreeDescription, model: CompiledModel
                  ) -> tuple[tuple[JointSampler, ...], tuple[TimedSource, ...]]:
    """Per joint of ``model`` its sampler, and the moving frames and driven joints (a mimic
    joint's chain of primaries included) whose samples they read."""
    samplers: list[JointSampler] = []
    sources: dict[str, TimedSource] = {}
    for position, joint in enumerate(model.joints):
        if joint.joint is None:
            keyframes = tree.local_poses[joint.frame].keyframes
            samplers.append(MovingFrame(joint.frame, keyframes,
                                        keyframes.placed(model.joint_placements[position])))
            sources[joint.frame] = frame_source(tree, joint.frame)
            continue
        chain = mimic_chain(joint.joint, tree.joints_by_name)
        for link in chain:
            if link.name in tree.joint_trajectories:
                sources[link.name] = joint_source(tree, link.name)
        samplers.append(_driven(tree, chain))
    return tuple(samplers), tuple(sources.values())


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


def joint_sampler(tree: TreeDescription, joint: Joint) -> DrivenJoint:
    """The sampler of one robot joint of ``tree``."""
    return _driven(tree, mimic_chain(joint, tree.joints_by_name))


def _driven(tree: TreeDescription, chain: list[Joint]) -> DrivenJoint:
    """The sampler of ``chain[0]``, driven by ``chain[-1]`` (see :func:`mimic_chain`)."""
    primary = chain[-1]
    trajectory = tree.joint_trajectories.get(primary.name)
    return DrivenJoint(
        chain[0].name, primary.name, trajectory,
        "" if trajectory is None else tree.time_groups[primary.name], primary.rest_value,
        tuple((link.mimic.multiplier, link.mimic.offset)
              for link in reversed(chain[:-1]) if link.mimic is not None))


class SegmentSearches:
    """Where one set of times (timeline basis, ns) falls among the samples of a query's
    moving things: one search per moving frame and one per time group of joints, shared by
    everything taken at those times (poses, joint values, and their rates).

    Attributes
    ----------
    times : ndarray of int64 or None
        The times; None for a path on which nothing is sampled.
    """

    __slots__ = ("_found", "_shifts", "times")

    def __init__(self, times: NDArray[np.int64] | None, shifts: Mapping[str, int]) -> None:
        self.times = times
        self._shifts = shifts
        self._found: dict[tuple[str, str], Segments] = {}

    def of_frame(self, frame: str, keyframe_times: NDArray[np.int64]) -> Segments:
        """The times among the keyframes of the moving frame ``frame`` (its own basis)."""
        return self._search(("frame", frame), frame, keyframe_times)

    def of_joint(self, joint: DrivenJoint, sample_times: NDArray[np.int64]) -> Segments:
        """The times among the samples of the trajectory driving ``joint`` (its own
        basis)."""
        return self._search(("joints", joint.time_group), joint.primary, sample_times)

    def _search(self, key: tuple[str, str], source: str, sample_times: NDArray[np.int64]
                ) -> Segments:
        found = self._found.get(key)
        if found is None:
            assert self.times is not None  # a moving thing is a source: the query has times
            found = self._found[key] = Segments(sample_times, self.times - self._shifts[source])
        return found


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
        primary = values.get(sampler.primary)
        if primary is None:
            trajectory = sampler.trajectory
            if trajectory is None:
                primary = sampler.rest
            else:
                segments = searches.of_joint(sampler, trajectory.times)
                primary = trajectory.sample(segments.times, segments)
            values[sampler.primary] = primary
        samples.append(sampler.follow(primary))
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


def warn_joints_without_samples(tree: TreeDescription, samplers: Sequence[JointSampler],
                                held: Collection[str] = ()) -> None:
    """One :class:`JointWithoutSamplesWarning` per version of a tree, naming its joints
    without samples, when one of ``samplers`` (but those ``held``) holds its rest value."""
    if not any(isinstance(sampler, DrivenJoint) and sampler.trajectory is None
               and sampler.primary not in held for sampler in samplers):
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
