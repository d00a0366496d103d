"""Per-joint limits on velocity, acceleration and (optionally) jerk, for timing moves."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import JointError

__all__ = ["MotionLimits"]


@dataclass(frozen=True)
class MotionLimits:
    """Per-joint limits for timing, in each joint's unit (rad or m) per s, s^2, s^3.

    Attributes
    ----------
    velocity : numpy.ndarray
        Shape ``(n,)``, each > 0: the largest joint speed (rad/s or m/s).
    acceleration : numpy.ndarray
        Shape ``(n,)``, each > 0: the largest joint acceleration (rad/s^2 or m/s^2).
    jerk : numpy.ndarray or None
        Shape ``(n,)``, each > 0 (rad/s^3 or m/s^3), or None: no jerk limit.

    Raises
    ------
    JointError
        A limit that is not a finite number > 0, or lengths that differ; the field names
        the limit and the joint's index (``acceleration[2]``).
    """

    velocity: np.ndarray
    acceleration: np.ndarray
    jerk: np.ndarray | None = None

    def __post_init__(self) -> None:
        velocity = _positive("velocity", self.velocity, None)
        object.__setattr__(self, "velocity", velocity)
        object.__setattr__(self, "acceleration",
                           _positive("acceleration", self.acceleration, velocity.size))
        if self.jerk is not None:
            object.__setattr__(self, "jerk", _positive("jerk", self.jerk, velocity.size))

    @property
    def joint_count(self) -> int:
        """How many joints the limits are for."""
        return int(self.velocity.size)


def _positive(name: str, values: object, size: int | None) -> np.ndarray:
    """``values`` as a read-only ``(n,)`` float array of finite numbers > 0."""
    try:
        array = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise JointError(f"must be numbers, got {values!r}", field=name) from None
    if array.ndim > 1:
        raise JointError(f"must be one value per joint, got shape {array.shape}", field=name)
    array = array.reshape(-1)
    if size is not None and array.size != size:
        raise JointError(f"has {array.size} values for {size} joints (the velocity limits')",
                         field=name)
    if array.size == 0:
        raise JointError("holds no joint", field=name)
    bad = np.flatnonzero(~(np.isfinite(array) & (array > 0)))
    if bad.size:
        index = int(bad[0])
        raise JointError(f"must be a finite number > 0, got {array[index]!r}",
                         field=f"{name}[{index}]")
    array.setflags(write=False)
    return array
