"""Sampling a compiled path's joints at times: the one sampling step of every query and of
:meth:`PinocchioTree.configurations`.

A free-flyer gets its moving frame's interpolated pose, a robot joint its value (radians or
metres) from its trajectory, its mimic primary's, or its rest value (with one warning per
tree version naming the joints without samples).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import JointWithoutSamplesWarning
from ..values.interpolation import Keyframes, segment_positions
from ..values.joint import Joint
from ._description import TreeDescription
from ._model import CompiledModel

__all__ = ["CHUNK", "sample_joint_values", "sample_joints", "warn_joints_without_samples"]

CHUNK = 1 << 12
"""Samples evaluated at once: the temporaries of a chunk (under 300 kB each) stay in the
CPU caches; 2,048-8,192 ran alike, 16,384 1.8x slower (Panda, 10^5 samples, one thread)."""


def sample_joints(
    tree: TreeDescription, model: CompiledModel, keyframes: Sequence[Keyframes | None],
    times: NDArray[np.int64] | None, shifts: dict[str, int],
) -> list[Any]:
    """Every joint of ``model`` at ``times`` (timeline basis, ns).

    A free-flyer gets its moving frame's ``(rotation, translation)`` from ``keyframes[i]``,
    samples last (``(3, 3, N)``, ``(3, N)``); a robot joint its value(s) (radians or metres):
    its trajectory, its mimic primary's, or 0. ``shifts`` holds, per source, what to
    subtract from a timeline time to land on its own time basis.
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
        warn_joints_without_samples(tree)
    cache[joint.name] = value
    return value


def warn_joints_without_samples(tree: TreeDescription) -> None:
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
