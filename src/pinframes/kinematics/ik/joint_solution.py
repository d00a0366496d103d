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
    velocity_limits : ndarray, shape (n,)
        The largest rate of each joint its URDF velocity limits allow, radians or metres per
        second: its own limit, or where a mimic joint follows it with multiplier ``m`` and
        a tighter limit ``L``, ``L / |m|``; ``inf`` where no limit is given (a limit of 0
        counts as none).
    velocity_limit_joints : tuple of str
        Per joint, the joint whose limit :attr:`velocity_limits` holds: the joint itself or
        the mimic joint following it.
    tilt : ndarray, shape (T, 2), or None
        With process windows (``tilt=``): the tilt of the tool's z from the target's, radians,
        ``(a, b)`` with the tool's z ``Rx(a) Ry(b)`` the target's (about the target's x, then
        the y so turned): ``z = (sin b, -sin a cos b, cos a cos b)`` in the target's axes.
        None without windows.
    path_deviation : ndarray, shape (T,), or None
        Per sample, how far (metres) the tool strays from its target between the sample
        before and it while the solved joints move linearly from the one to the other (a
        controller interpolating the solution): the distance at the interval's midpoint,
        or the largest at its quarter points where that comes near the tolerance; 0 for the
        first sample. Without given times the samples are dense enough to keep it within
        ``path_tolerance`` wherever both ends are reached (see ``FrameTree.solve_joints``).
    path_angle_deviation : ndarray, shape (T,), or None
        The same for the orientation, radians (as :attr:`orientation_error`).
    flat_error : ndarray, shape (T,), or None
        With ``flat=``: the angle between the flat frame's z and ``up``, radians; a sample
        more than ``flat_tolerance`` from up where the solved joints could turn it up (the
        tool let go, from the sample's solution) is not :attr:`reached`. None without.
    jumps : ndarray of int, shape (J,), or None
        The samples whose step from the one before jumps: one joint changes by more than
        ``jump_threshold`` times the path's median step and more than 0.1 radian (or metre)
        (``pinframes.kinematics.ik.joint_jumps``). Empty when none does.
    urdf_joint_names : tuple of str or None
        :attr:`joint_names` as the robot's URDF names them (the tree's prefix removed: what
        the robot's controller knows), when every solved joint belongs to one robot read
        from a URDF; None otherwise. :func:`pinframes.write_joint_trajectory` writes these.
    configurations : ndarray of str, shape (T,), or None
        For a 6-axis arm of a closed-form family (docs/closed-form-ik.md), each sample's
        configuration flags, e.g. ``"front,up,noflip"``; None for other chains.
    """

    joint_names: tuple[str, ...]
    positions: FloatArray
    times: NDArray[np.timedelta64]
    reference_time: np.datetime64 | None
    position_error: FloatArray
    orientation_error: FloatArray
    reached: NDArray[np.bool_]
    velocity_limits: FloatArray
    velocity_limit_joints: tuple[str, ...]
    tilt: FloatArray | None = None
    path_deviation: FloatArray | None = None
    path_angle_deviation: FloatArray | None = None
    jumps: NDArray[np.intp] | None = None
    flat_error: FloatArray | None = None
    urdf_joint_names: tuple[str, ...] | None = None
    configurations: NDArray[np.str_] | None = None

    @property
    def velocities(self) -> FloatArray:
        """Joint rates (T, n), radians or metres per second, over the interval ending at each
        sample: ``(q_i - q_{i-1}) / (t_i - t_{i-1})``, the first row 0. Two samples at one
        time: 0 where the values are equal, infinite where they differ."""
        rates = np.zeros_like(self.positions, dtype=float)
        if self.positions.shape[0] < 2:
            return rates
        steps = np.diff(self.positions, axis=0)
        durations = np.diff(self.times).astype(np.float64)[:, None] / 1e9  # seconds
        with np.errstate(divide="ignore", invalid="ignore"):
            rates[1:] = np.where(steps == 0.0, 0.0, steps / durations)
        rates[1:][(durations == 0.0) & (steps != 0.0)] = np.inf
        return rates

    @property
    def joint_speed_ratios(self) -> FloatArray:
        """``|velocity| / limit`` per sample and joint (T, n), see :attr:`velocity_limits`;
        0 where a joint has no limit."""
        return np.abs(self.velocities) / self.velocity_limits

    @property
    def speed_ratio(self) -> FloatArray:
        """Per sample (T,), the largest of :attr:`joint_speed_ratios`: above 1 a joint moves
        faster than its URDF velocity limit allows; 0 without limits."""
        return self.joint_speed_ratios.max(axis=1, initial=0.0)

    def when(self, index: int) -> str:
        """Sample ``index``'s time as messages give it: seconds, after the reference time
        when there is one."""
        return f"{int(self.times[index].astype(np.int64)) / 1e9:.9g} s" + (
            "" if self.reference_time is None else f" after {self.reference_time}")

    @property
    def all_reached(self) -> bool:
        """True when every sample reached its target."""
        return bool(self.reached.all())

    def __len__(self) -> int:
        return int(self.positions.shape[0])
