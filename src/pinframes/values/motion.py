"""`Motion`: a planned program as one joint trajectory at a fixed step, with the records of
its moves (`MoveRecord`) and of where it comes too close to something (`CollisionRecord`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import NameNotFoundError
from .timed import Timed

__all__ = ["CollisionRecord", "Motion", "MoveRecord"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class MoveRecord:
    """One move of a planned program.

    Attributes
    ----------
    name : str
        The move's name (given, or made from its kind and place in the program).
    kind : str
        ``"joints"`` (point to point), ``"linear"``, ``"approach"``, ``"seam"``,
        ``"retract"`` or ``"wait"``.
    start_s, end_s : float
        When the move starts and ends, seconds on the motion's times.
    requested_speed : float or None
        For linear and seam moves, the tool's highest speed asked for along the path, m/s:
        along a line in its target's frame, or along the seam frame's path in its parent (a
        seam on its own times: its own highest speed there); None for the others.
    reached_speed : float or None
        The tool's highest speed along the move as planned, m/s: below the requested one
        where the joints' limits do not allow it.
    """

    name: str
    kind: str
    start_s: float
    end_s: float
    requested_speed: float | None = None
    reached_speed: float | None = None

    @property
    def duration_s(self) -> float:
        """``end_s - start_s``, seconds."""
        return self.end_s - self.start_s


@dataclass(frozen=True)
class CollisionRecord:
    """A move that comes closer to something than the margin allows.

    Attributes
    ----------
    move : str
        The move's name.
    time_s : float
        When the distance is smallest, seconds on the motion's times.
    frame_a, frame_b : str
        The two frames whose shapes come that close.
    distance : float
        Their distance then, metres (0 or less: touching or overlapping). Between samples,
        a lower bound.
    """

    move: str
    time_s: float
    frame_a: str
    frame_b: str
    distance: float


@dataclass(frozen=True)
class Motion(Timed):
    """A program planned as one joint trajectory, sampled at a fixed step.

    Put it on a tree with ``tree.set_motion(motion)``; write it with
    :func:`pinframes.write_joint_trajectory` (CSV, NPZ, or a ROS bag's ``JointTrajectory``
    with velocities and accelerations).

    Attributes
    ----------
    joint_names : tuple of str
        The program's joints, the columns of the arrays.
    times : ndarray of timedelta64[ns], shape (T,)
        Sample times after :attr:`reference_time` (plain offsets when None), one step apart.
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    positions, velocities, accelerations : ndarray, shape (T, n)
        Joint values (radians or metres), their rates (per second) and the rates of those
        (per second squared), from the timing of each move: continuous in position and
        velocity, at rest where one move ends and the next starts.
    moves : tuple of MoveRecord
        The moves in order.
    collisions : tuple of CollisionRecord
        The moves that came closer than the margin, one record each (empty without a
        check).
    reached : ndarray of bool, shape (T,)
        Whether the tool is on its target at each sample: False where a target of a linear
        or seam move was out of reach (the closest configuration is held).
    urdf_joint_names : tuple of str or None
        :attr:`joint_names` as the robot's URDF names them (what a controller takes and
        :func:`pinframes.write_joint_trajectory` writes), when every joint belongs to one
        robot read from a URDF; else None.
    """

    joint_names: tuple[str, ...]
    times: NDArray[np.timedelta64]
    reference_time: np.datetime64 | None
    positions: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    moves: tuple[MoveRecord, ...]
    collisions: tuple[CollisionRecord, ...]
    reached: NDArray[np.bool_]
    urdf_joint_names: tuple[str, ...] | None = None

    @property
    def cycle_time(self) -> float:
        """The whole program's duration, seconds."""
        return float((self.times[-1] - self.times[0]).astype(np.int64)) / 1e9

    @property
    def all_reached(self) -> bool:
        """True when every sample reached its target."""
        return bool(self.reached.all())

    def move(self, name: str) -> MoveRecord:
        """The record of the move named ``name`` (a :class:`NameNotFoundError` naming the
        moves if none)."""
        for record in self.moves:
            if record.name == name:
                return record
        raise NameNotFoundError(f"no move {name!r}; the moves are "
                                f"{', '.join(repr(record.name) for record in self.moves)}",
                                field="name")

    def __len__(self) -> int:
        return int(self.positions.shape[0])
