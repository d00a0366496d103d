"""One joint's limits on velocity, acceleration and jerk, as a robot's configuration gives them."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["JointRateLimits"]


@dataclass(frozen=True)
class JointRateLimits:
    """The largest velocity, acceleration and jerk of one joint, each None when not limited.

    Attributes
    ----------
    velocity : float or None
        rad/s for a turning joint, m/s for a sliding one.
    acceleration : float or None
        rad/s^2 or m/s^2.
    jerk : float or None
        rad/s^3 or m/s^3.
    """

    velocity: float | None = None
    acceleration: float | None = None
    jerk: float | None = None
