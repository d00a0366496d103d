"""``sensor_msgs/JointState`` messages as samples per joint (docs/ros-bags.md).

Each message names the joints it carries (``name[]``, ``position[]`` in radians or metres)
at ``header.stamp``; messages may name a subset. Each joint is sampled at the stamps of the
messages that name it, sorted by stamp; of two samples of a joint at one stamp the one
tf2 would keep of the transforms ``robot_state_publisher`` makes of them (ROS 1: the first
received; ROS 2: the later). A message whose ``position`` is empty or not as long as
``name`` is skipped (``robot_state_publisher`` skips it too), and so is a position that is
NaN or infinite (the transforms made from it would be refused by tf2): one warning for
each kind.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ...errors import BagWarning, warn_at_caller
from ..limits import current_limits, exceeded
from ._tf_tracks import kept_of_repeated_stamps, repeated_stamp_rule

__all__ = ["JointSamples", "joint_samples"]


@dataclass(frozen=True)
class JointSamples:
    """One joint's samples: strictly increasing stamps (ns since the epoch) and positions
    (radians or metres)."""

    stamps_ns: NDArray[np.int64]
    positions: NDArray[np.float64]


def joint_samples(messages: Iterable[object], file: Path, ros_version: int
                  ) -> dict[str, JointSamples]:
    """The samples of every joint named in ``messages`` (deserialised JointStates in
    receive order) of a bag of ``ros_version``, joints in order of first appearance."""
    stamps: dict[str, list[int]] = {}
    positions: dict[str, list[float]] = {}
    skipped = 0
    not_finite: list[str] = []
    for message in messages:
        names = list(message.name)  # type: ignore[attr-defined]
        values = np.asarray(message.position, np.float64)  # type: ignore[attr-defined]
        if values.shape[0] != len(names):
            skipped += 1
            continue
        stamp = message.header.stamp  # type: ignore[attr-defined]
        stamp_ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
        for name, value in zip(names, values.tolist(), strict=True):
            if not math.isfinite(value):
                not_finite.append(name)
                continue
            stamps.setdefault(name, []).append(stamp_ns)
            positions.setdefault(name, []).append(value)
    if skipped:
        warn_at_caller(f"{file}: skipped {skipped:,} joint states whose position "
                       "list is empty or not as long as their name list", BagWarning)
    if not_finite:
        warn_at_caller(f"{file}: skipped {len(not_finite):,} joint positions that are NaN or "
                       f"infinite (first: joint {not_finite[0]!r})", BagWarning)
    samples = {}
    repeated = []
    for name in stamps:
        times = np.asarray(stamps[name], np.int64)
        values = np.asarray(positions[name], np.float64)
        order = np.argsort(times, kind="stable")
        times, values = times[order], values[order]
        last = kept_of_repeated_stamps(times, ros_version)
        if last.shape[0] < times.shape[0]:
            repeated.append(name)
        if last.shape[0] > current_limits().max_samples:
            raise exceeded("max_samples", f"{last.shape[0]:,} joint states",
                           field="joint").located(file=file, frame=name)
        samples[name] = JointSamples(times[last], values[last])
    if repeated:
        warn_at_caller(f"{file}: {len(repeated)} joints with two samples at one "
                       f"stamp {repeated_stamp_rule(ros_version)}: "
                       + ", ".join(map(repr, repeated[:5])), BagWarning)
    return samples
