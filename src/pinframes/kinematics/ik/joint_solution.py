"""`JointSolution`: what ``FrameTree.solve_joints`` returns, joint values per sample and how
well each sample reached its target."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...values.timed import Timed

__all__ = ["JointSolution"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class JointSolution(Timed):
    """Joint values that put a tool frame on its target, sample by sample.

    Apply it with ``tree.set_joint_trajectory(sol.seconds, sol.positions,
    joint_names=sol.joint_names)`` (relative times count from the tree's reference time;
    when :attr:`reference_time` is set, pass ``sol.absolute_times`` instead of
    ``sol.seconds``).

    Attributes
    ----------
    joint_names : tuple of str
        The solved joints, the columns of :attr:`positions`.
    positions : ndarray, shape (T, n)
        Joint values, radians (revolute, continuous) or metres (prismatic), within the
        joints' position limits.
    times : ndarray of timedelta64[ns], shape (T,)
        Sample times after :attr:`reference_time` (or plain offsets when it is None).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    position_error : ndarray, shape (T,)
        Distance between the origins of the tool and of the target, metres.
    orientation_error : ndarray, shape (T,)
        Angle of the rotation between the tool's axes and the target's, radians; with a free
        axis, the angle between that axis of the tool and the target's.
    reached : ndarray of bool, shape (T,)
        Whether both errors are within the tolerances. Where not, :attr:`positions` hold the
        closest configuration found within the limits.
    """

    joint_names: tuple[str, ...]
    positions: FloatArray
    times: NDArray[np.timedelta64]
    reference_time: np.datetime64 | None
    position_error: FloatArray
    orientation_error: FloatArray
    reached: NDArray[np.bool_]

    @property
    def all_reached(self) -> bool:
        """True when every sample reached its target."""
        return bool(self.reached.all())

    def __len__(self) -> int:
        return int(self.positions.shape[0])
