"""Sampling a compiled path's joints at times: the one sampling step of every query and of
:meth:`PinocchioTree.configurations`.

A free-flyer gets its moving frame's interpolated pose, a robot joint its value (radians or
metres) from its trajectory, its mimic primary's, or its rest value (with one warning per
tree version naming the joints without samples).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import JointWithoutSamplesWarning, warn_at_caller
from ..values.interpolation import Keyframes, Segments
from ..values.joint import Joint
from ..values.se3 import samples_first
from ._description import TreeDescription
from ._model import CompiledModel

__all__ = ["CHUNK", "SegmentSearches", "sample_configurations", "sample_joint_values",
           "sample_joints", "warn_joints_without_samples"]

CHUNK = 1 << 12
"""Samples evaluated at once: the temporaries of a chunk (under 300 kB each) stay in the
CPU caches; 2,048-8,192 ran alike, 16,384 1.8x slower (Panda, 10^5 samples, one thread)."""


class SegmentSearches:
    """Where one set of times (timeline basis, ns) falls among the samples of a query's
    moving things: one search per moving frame and one per time group of joints
    (:meth:`TreeDescription.time_group`: equal sample times and reference time), shared by
    everything taken at those times (poses, joint values, and their rates).

    Attributes
    ----------
    times : ndarray of int64 or None
        The times; None for a path on which nothing is sampled.
    """

    __slots__ = ("_found", "_shifts", "_tree", "times")

    def __init__(self, tree: TreeDescription, times: NDArray[np.int64] | None,
                 shifts: dict[str, int]) -> None:
        self._tree = tree
        self.times = times
        self._shifts = shifts
        self._found: dict[tuple[str, str], Segments] = {}

    def of_frame(self, frame: str, keyframe_times: NDArray[np.int64]) -> Segments:
        """The times among the keyframes of the moving frame ``frame`` (its own basis)."""
        return self._search(("frame", frame), frame, keyframe_times)

    def of_joint(self, joint: str, sample_times: NDArray[np.int64]) -> Segments:
        """The times among the samples of the driven joint ``joint`` (its own basis)."""
        return self._search(("joints", self._tree.time_group(joint)), joint, sample_times)

    def _search(self, key: tuple[str, str], source: str, sample_times: NDArray[np.int64]
                ) -> Segments:
        found = self._found.get(key)
        if found is None:
            assert self.times is not None  # a moving thing is a source: the query has times
            found = self._found[key] = Segments(sample_times, self.times - self._shifts[source])
        return found


def sample_joints(
    tree: TreeDescription, model: CompiledModel, keyframes: Sequence[Keyframes | None],
    times: NDArray[np.int64] | None, shifts: dict[str, int],
    searches: SegmentSearches | None = None,
    held: Mapping[str, NDArray[np.float64] | float] | None = None,
) -> list[Any]:
    """Every joint of ``model`` at ``times`` (timeline basis, ns).

    A free-flyer gets its moving frame's ``(rotation, translation)`` from ``keyframes[i]``,
    samples last (``(3, 3, N)``, ``(3, N)``); a robot joint its value(s) (radians or metres):
    its trajectory, its mimic primary's, or 0. ``shifts`` holds, per source, what to
    subtract from a timeline time to land on its own time basis; ``searches`` may pass the
    caller's :class:`SegmentSearches` of ``times`` (to reuse them for rates). ``held`` gives
    joints (by name) values (one, or one per time) instead of their samples; their mimic
    joints follow them.
    """
    if searches is None:
        searches = SegmentSearches(tree, times, shifts)
    cache: dict[str, NDArray[np.float64] | float] = dict(held or {})
    samples: list[Any] = []
    for joint, frames in zip(model.joints, keyframes, strict=True):
        if joint.joint is None:
            assert frames is not None
            segments = searches.of_frame(joint.frame, frames.times)
            samples.append(frames.transform_at(segments.times, segments))
        else:
            samples.append(sample_joint_values(tree, joint.joint, searches, cache))
    return samples


def sample_configurations(
    tree: TreeDescription, model: CompiledModel, times: NDArray[np.int64],
    shifts: dict[str, int], held: Mapping[str, NDArray[np.float64] | float] | None = None,
) -> NDArray[np.float64]:
    """Pinocchio configurations ``q`` of ``model``, shape ``(N, nq)``, at ``times`` (timeline
    basis, ns): each free-flyer the interpolated pose of its moving frame in the frame's
    parent (``x y z qx qy qz qw``; the model holds the joint's placement), each robot joint
    its value as :func:`sample_joints` gives it (with ``held``)."""
    if not model.joints:
        return np.zeros((times.shape[0], 0))
    keyframes = [tree.local_poses[joint.frame].keyframes if joint.joint is None else None
                 for joint in model.joints]
    samples = sample_joints(tree, model, keyframes, times, shifts, held=held)
    motions = [samples_first(sample) if joint.joint is None else None
               for joint, sample in zip(model.joints, samples, strict=True)]
    values = [None if joint.joint is None else sample
              for joint, sample in zip(model.joints, samples, strict=True)]
    return model.configuration(motions, values, times.shape[0])


def sample_joint_values(
    tree: TreeDescription, joint: Joint, searches: SegmentSearches,
    cache: dict[str, NDArray[np.float64] | float],
) -> NDArray[np.float64] | float:
    """Values of ``joint`` at the times of ``searches``: its trajectory, its mimic
    primary's, or its rest value.

    ``cache`` keeps the values per joint name for the other joints sampled at those times.
    """
    if joint.name in cache:
        return cache[joint.name]
    trajectory = tree.joint_trajectories.get(joint.name)
    if joint.mimic is not None:
        primary = sample_joint_values(tree, tree.joints_by_name[joint.mimic.joint], searches,
                                      cache)
        value = joint.mimic.multiplier * primary + joint.mimic.offset
    elif trajectory is not None:
        segments = searches.of_joint(joint.name, trajectory.times)
        value = trajectory.sample(segments.times, segments)
    else:
        value = joint.rest_value
        warn_joints_without_samples(tree)
    cache[joint.name] = value
    return value


def warn_joints_without_samples(tree: TreeDescription) -> None:
    """One :class:`JointWithoutSamplesWarning` per version of a tree, naming its joints
    without samples."""
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
