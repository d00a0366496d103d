"""A whole tree at one instant: the time every frame is taken at, and every joint's value.

Writers that store one pose per frame sample every path at the same instant; a relative
time is resolved once for the whole tree (the rules of ``to_pinocchio().configurations``),
not once per path, whose references could differ.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InvalidTimeError
from ._description import TreeDescription
from ._plan import plan_query
from ._sampling import (
    frame_source,
    joint_sampler,
    joint_source,
    sample_joints,
    warn_joints_without_samples,
)

__all__ = ["Snapshot", "snapshot"]


@dataclass(frozen=True)
class Snapshot:
    """One instant of a tree.

    Attributes
    ----------
    time : numpy.datetime64, numpy.timedelta64 or None
        The instant, as ``FrameTree.pose(..., times=[time])`` takes it: a timestamp when
        the tree has reference times, else a duration; None when nothing moves.
    joint_values : dict of str to float
        Every robot joint's value then (radians or metres), mimic joints included.
    """

    time: np.datetime64 | np.timedelta64 | None
    joint_values: dict[str, float]


def snapshot(tree: TreeDescription, time: Any, time_ref: Any = None) -> Snapshot:
    """The tree at ``time`` (None only for a tree in which nothing moves)."""
    sources = [frame_source(tree, frame) for frame, pose in tree.local_poses.items()
               if pose.is_time_dependent]
    sources += [joint_source(tree, name) for name in tree.joint_trajectories]
    if time is None and sources:
        raise InvalidTimeError("parts of the tree move (" + ", ".join(
            s.name for s in sources) + "); give the time to take them at", field="time")
    plan = plan_query(tree, tree.root, tree.root, None if time is None else [time], time_ref,
                      "clamp", sources)
    times = plan.times
    # a JointError for a mimic of a missing joint
    samplers = [joint_sampler(tree, joint) for joint in tree.joints_by_name.values()]
    warn_joints_without_samples(tree, {sampler.primary for sampler in samplers
                                       if sampler.trajectory is None})
    samples = sample_joints(samplers, times, plan.shifts)
    values = {sampler.name: float(np.ravel(sample)[0])
              for sampler, sample in zip(samplers, samples, strict=True)}
    if times is None:
        return Snapshot(None, values)
    if plan.timeline.absolute:
        return Snapshot(np.datetime64(int(times[0]), "ns"), values)
    return Snapshot(np.timedelta64(int(times[0]), "ns"), values)

