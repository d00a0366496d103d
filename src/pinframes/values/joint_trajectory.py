"""Joint trajectories: `JointTrajectory`, one joint's values over time, and building them."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import (
    ArgumentTypeError,
    InvalidTimeError,
    JointError,
    JointLimitWarning,
    joint_not_found,
    warn_at_caller,
)
from ._readonly import readonly_copy
from .interpolation import (
    DEFAULT_JOINT_INTERPOLATION,
    JointInterpolation,
    Segments,
)
from .joint import Joint
from .numbers import float_array
from .quantities import is_quantity, metres, radians
from .timeconv import parse_time_axis

__all__ = ["JointTrack", "JointTrajectory", "joint_trajectories_from_samples"]


@dataclass(frozen=True)
class JointTrajectory:
    """Values of one joint at strictly increasing times.

    Attributes
    ----------
    times : ndarray of int64, shape (T,)
        Nanoseconds after ``reference`` (or plain offsets when it is None).
    reference : numpy.datetime64 or None
        What ``times`` count from.
    values : ndarray, shape (T,)
        Radians or metres. Continuous joints are stored unwrapped, so that linear
        interpolation takes the short way round.
    interpolation : type of JointInterpolation
        How values go between samples (default
        :class:`~pinframes.values.interpolation.LinearValues`: linearly).

    Immutable: ``times`` and ``values`` are read-only copies of the arrays given.
    """

    times: NDArray[np.int64]
    reference: np.datetime64 | None
    values: NDArray[np.float64]
    interpolation: type[JointInterpolation] = field(default=DEFAULT_JOINT_INTERPOLATION,
                                                    repr=False)
    _scheme: JointInterpolation | None = field(default=None, init=False, repr=False,
                                               compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "times", readonly_copy(self.times))
        object.__setattr__(self, "values", readonly_copy(self.values))

    @classmethod
    def _on_shared_times(cls, times: NDArray[np.int64], reference: np.datetime64 | None,
                         values: NDArray[np.float64]) -> JointTrajectory:
        """A trajectory on ``times``, a read-only copy this module made for all the joints of
        one call: not copied again (7 joints at 10^7 samples would hold 560 MB of times)."""
        trajectory = cls(times[:1], reference, values[:1])
        object.__setattr__(trajectory, "times", times)
        object.__setattr__(trajectory, "values", readonly_copy(values))
        return trajectory

    def scheme(self) -> JointInterpolation:
        """The instance of :attr:`interpolation` for this trajectory, made on first use."""
        scheme = self._scheme
        if scheme is None:
            scheme = self.interpolation(self.times, self.values)
            object.__setattr__(self, "_scheme", scheme)
        return scheme

    def sample(self, times: NDArray[np.int64], segments: Segments | None = None
               ) -> NDArray[np.float64]:
        """Values at ``times`` (ns on this trajectory's own basis), held outside the samples.

        ``segments`` may pass ``Segments(self.times, times)`` when it is known (trajectories
        set together share their times, and so their segments).
        """
        return self.scheme().sample(times, segments)

    def value_at(self, time: int, position: tuple[int, float] | None = None) -> float:
        """The value at one ``time`` (ns on this trajectory's own basis), as :meth:`sample`
        gives it, in Python floats; ``position`` may pass ``segment_position(self.times,
        time)`` when it is known."""
        return self.scheme().value_at(time, position)

    def rates(self, times: NDArray[np.int64], segments: Segments | None = None
              ) -> NDArray[np.float64]:
        """Rates (rad/s or m/s) at ``times`` (ns on this trajectory's own basis): zero where
        the value is held."""
        return self.scheme().rates(times, segments)


JointTrack = JointTrajectory
"""The earlier name of :class:`JointTrajectory` (kept for existing code)."""


def joint_trajectories_from_samples(
    joints: Mapping[str, Joint], times: Any, positions: Any,
    joint_names: Sequence[str] | None = None,
) -> dict[str, JointTrajectory]:
    """One trajectory per named joint from ``positions`` (T, n) at T ``times``, checked.

    ``joints`` are the tree's joints by name; see
    :meth:`pinframes.FrameTree.set_joint_trajectory` for the rules.
    """
    if isinstance(joint_names, str):
        raise ArgumentTypeError(f"expected a list of joint names, got the string {joint_names!r}",
                                field="joint_names")
    if joint_names is None:
        joint_names = [name for name, joint in joints.items() if joint.is_actuated]
    joint_names = list(joint_names)
    for name in joint_names:
        if name not in joints:
            raise joint_not_found(name, joints, field="joint_names")
        mimic = joints[name].mimic
        if mimic is not None:
            raise JointError(f"joint {name!r} is a mimic joint of {mimic.joint!r}; drive that "
                             "joint instead", field="joint_names")
    if len(set(joint_names)) != len(joint_names):
        raise JointError("joint names repeat", field="joint_names")
    axis = parse_time_axis(times, field="times")
    count = axis.offsets.shape[0]
    if count > 1 and np.any(np.diff(axis.offsets) <= 0):
        raise InvalidTimeError("joint sample times must be strictly increasing", field="times")
    values = _positions(_in_joint_units(positions, [joints[name] for name in joint_names]),
                        count, joint_names)
    shared_times = readonly_copy(axis.offsets)
    trajectories = {}
    for column, name in enumerate(joint_names):
        joint = joints[name]
        column_values = values[:, column]
        _warn_outside_limits(name, joint.lower, joint.upper, column_values)
        if joint.kind == "continuous":
            column_values = np.unwrap(column_values)
        trajectories[name] = JointTrajectory._on_shared_times(shared_times, axis.reference,
                                                              column_values)
    return trajectories


def _in_joint_units(positions: Any, joints: list[Joint]) -> Any:
    """A pint quantity of positions in radians (revolute and continuous joints) or metres
    (prismatic joints); plain numbers unchanged. One quantity cannot drive both kinds."""
    if not is_quantity(positions):
        return positions
    kinds = {"prismatic" if joint.kind == "prismatic" else "angular" for joint in joints}
    if len(kinds) > 1:
        raise JointError("one quantity cannot hold both angles and lengths: give radians for "
                         "revolute and metres for prismatic joints as plain numbers",
                         field="positions")
    if kinds == {"prismatic"}:
        return metres(positions, "positions", JointError)
    return radians(positions, "positions", JointError)


def _positions(positions: Any, count: int, joint_names: list[str]) -> np.ndarray:
    # each joint's column is copied later
    values = float_array(positions, "positions", JointError, finite=False)
    if values.ndim == 1 and len(joint_names) == 1:
        values = values[:, None]
    if values.shape != (count, len(joint_names)):
        raise JointError(
            f"positions have shape {values.shape}, expected ({count}, {len(joint_names)}) for "
            f"{count} times and joints {', '.join(joint_names) or '(none)'}",
            field="positions")
    if not np.all(np.isfinite(values)):
        row, column = np.argwhere(~np.isfinite(values))[0]
        raise JointError(f"non-finite value at sample {row} (counted from 0)",
                         joint=joint_names[column], field="positions")
    return values


def _warn_outside_limits(name: str, lower: float | None, upper: float | None,
                         values: np.ndarray) -> None:
    below = lower is not None and values.min() < lower
    above = upper is not None and values.max() > upper
    if below or above:
        warn_at_caller(
            f"joint {name!r}: values {values.min():.6g} to {values.max():.6g} leave its "
            f"limits [{lower}, {upper}]", JointLimitWarning)
