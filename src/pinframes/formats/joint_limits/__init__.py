"""MoveIt ``joint_limits.yaml`` files: each joint's velocity, acceleration and jerk limits."""

from ._reader import read_joint_limits

__all__ = ["read_joint_limits"]
