"""Driving robot joints from sampled values: checks, then one :class:`JointTrack` per joint."""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ArgumentTypeError, InvalidTimeError, JointError, near_misses
from .joint_track import JointTrack
from .timeconv import parse_time_axis

if TYPE_CHECKING:
    from .tree import FrameTree

__all__ = ["JointLimitWarning", "set_joint_trajectory"]


class JointLimitWarning(UserWarning):
    """Joint values outside the limits written in the URDF."""


def set_joint_trajectory(
    tree: FrameTree, times: Any, positions: Any, joint_names: Sequence[str] | None = None
) -> None:
    """Set samples of joint values; see :meth:`pinframes.FrameTree.set_joint_trajectory`."""
    if isinstance(joint_names, str):
        raise ArgumentTypeError(f"expected a list of joint names, got the string {joint_names!r}",
                                field="joint_names")
    if joint_names is None:
        joint_names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    joint_names = list(joint_names)
    joints = tree.joints
    for name in joint_names:
        if name not in joints:
            raise JointError(f"no joint named {name!r} in the tree"
                             + near_misses(name, joints, "joint"), field="joint_names")
        if not joints[name].is_actuated:
            raise JointError(f"joint {name!r} is a mimic joint of "
                             f"{joints[name].mimic.joint!r}; drive that joint instead",
                             field="joint_names")
    if len(set(joint_names)) != len(joint_names):
        raise JointError("joint names repeat", field="joint_names")
    axis = parse_time_axis(times, field="times")
    count = axis.offsets.shape[0]
    if count > 1 and np.any(np.diff(axis.offsets) <= 0):
        raise InvalidTimeError("joint sample times must be strictly increasing", field="times")
    values = _positions(positions, count, joint_names)
    tracks = {}
    for column, name in enumerate(joint_names):
        joint = joints[name]
        column_values = values[:, column]
        _warn_outside_limits(name, joint.lower, joint.upper, column_values)
        if joint.kind == "continuous":
            column_values = np.unwrap(column_values)
        tracks[name] = JointTrack(axis.offsets, axis.reference, column_values)
    for name, track in tracks.items():
        tree.set_joint_track(name, track)


def _positions(positions: Any, count: int, joint_names: list[str]) -> np.ndarray:
    try:
        values = np.array(positions, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        raise JointError(f"positions must be numbers: {exc}", field="positions") from None
    if values.ndim == 1 and len(joint_names) == 1:
        values = values[:, None]
    if values.shape != (count, len(joint_names)):
        raise JointError(
            f"positions have shape {values.shape}, expected ({count}, {len(joint_names)}) for "
            f"{count} times and joints {', '.join(joint_names) or '(none)'}",
            field="positions")
    if not np.all(np.isfinite(values)):
        row, column = np.argwhere(~np.isfinite(values))[0]
        raise JointError(f"non-finite value at sample {row}", frame=joint_names[column],
                         field="positions")
    return values


def _warn_outside_limits(name: str, lower: float | None, upper: float | None,
                         values: np.ndarray) -> None:
    below = lower is not None and values.min() < lower
    above = upper is not None and values.max() > upper
    if below or above:
        warnings.warn(
            f"joint {name!r}: values {values.min():.6g} to {values.max():.6g} leave its "
            f"limits [{lower}, {upper}]", JointLimitWarning, stacklevel=4)
