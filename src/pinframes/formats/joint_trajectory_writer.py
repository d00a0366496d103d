"""``write_joint_trajectory``: joint values over time to the files a scene robot reads
(``.csv``, ``.npz``: :mod:`.joint_trajectory`) or to a ROS bag (``.mcap``, ``.bag``,
``.db3``, a folder: :mod:`.rosbag`). A module of its own above both formats, because the
bag format reads URDFs (:mod:`.urdf`), which read and write joint values as
:mod:`.joint_trajectory` does.

What ``pinframes solve -o`` writes. Joint names: a solution's as the robot's URDF names them
(the tree's prefix removed, as a robot's controller knows them) when every joint belongs to
one robot read from a URDF (:attr:`JointSolution.urdf_joint_names`), else the tree's; a
``(times, positions, joint_names)`` tuple's as given.
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import (
    ArgumentTypeError,
    FileFormatError,
    InvalidDataError,
    InvalidTimeError,
    PinframesError,
)
from ..kinematics import JointSolution
from ..tree import FrameTree
from ..tree.urdf_names import urdf_joint_names
from ..values.motion import Motion
from ..values.numbers import float_array
from ..values.timeconv import parse_time_axis
from ._paths import path_argument
from ._writable import check_joint_names
from .atomic import atomic_write
from .joint_trajectory import joint_trajectory_csv
from .rosbag import write_trajectory_bag

__all__ = ["write_joint_trajectory"]

BAG_SUFFIXES = (".mcap", ".bag", ".db3")
Times = NDArray[np.datetime64] | NDArray[np.timedelta64]


def write_joint_trajectory(
    trajectory: JointSolution | Motion | tuple[Any, Any, Sequence[str]],
    path: str | os.PathLike[str], *, tree: FrameTree | None = None,
) -> None:
    """Write joint values over time, atomically, in the format the name says.

    Parameters
    ----------
    trajectory : JointSolution, Motion or (times, positions, joint_names)
        A solution of :meth:`FrameTree.solve_joints` or a planned program's
        :class:`~pinframes.values.motion.Motion` (their absolute times when they have a
        reference time; a motion's velocities and accelerations go into an NPZ and a bag's
        ``JointTrajectory`` too), or T times (seconds, durations or timestamps, strictly
        increasing), positions (T, n) in radians or metres and n joint names.
    path : path
        ``.csv`` (``time_s`` seconds, or ``time`` ISO timestamps, then one column per
        joint), ``.npz`` (``times`` as ``timedelta64[ns]`` or ``datetime64[ns]``,
        ``positions``, ``joint_names``): both read by :func:`pinframes.read_joint_trajectory`
        and a scene's ``robots[].trajectory``. ``.mcap``, ``.bag``, ``.db3`` or another name
        (a ROS 2 bag folder): a ``trajectory_msgs/JointTrajectory`` on
        ``/joint_trajectory`` and ``sensor_msgs/JointState`` on ``/joint_states`` at the
        samples.
    tree : FrameTree or None
        The tree a solution was solved in, for a solution that does not carry its joints'
        URDF names (:attr:`JointSolution.urdf_joint_names`, which ``solve_joints`` fills):
        its joints are then named as their URDF names them, when they belong to one robot.

    Joint names follow the tree writers' rules: at least one, no control character or lone
    surrogate, and in a CSV header no space at either end and no first ``=``, ``+``, ``-``
    or ``@`` (a spreadsheet formula); an :class:`~pinframes.errors.UnsupportedFeatureError`
    names the joint and the file.
    """
    file = Path(path_argument(path))
    suffix = file.suffix.lower()
    try:
        times, positions, names = _samples(trajectory, tree)
        check_joint_names(names, csv_header=suffix == ".csv")
    except PinframesError as exc:
        raise exc.located(file=file) from None
    rates = ((trajectory.velocities, trajectory.accelerations)
             if isinstance(trajectory, Motion) else None)
    if suffix == ".csv":
        seconds = times if times.dtype.kind == "M" else times.astype(np.int64) / 1e9
        with atomic_write(file, "w") as handle:
            handle.write(joint_trajectory_csv(seconds, positions, names))
    elif suffix == ".npz":
        buffer = io.BytesIO()
        arrays: dict[str, Any] = {"times": times, "positions": positions,
                                  "joint_names": np.array(names, str)}
        if rates is not None:
            arrays.update(velocities=rates[0], accelerations=rates[1])
        np.savez(buffer, **arrays)
        with atomic_write(file, "wb") as handle:
            handle.write(buffer.getvalue())
    elif suffix in BAG_SUFFIXES or not suffix or file.is_dir():
        write_trajectory_bag(times, positions, names, file, rates=rates)
    else:
        raise FileFormatError(f"unknown joint trajectory file type {suffix!r}; expected .csv, "
                              ".npz, a ROS bag (.mcap, .bag, .db3) or a bag folder (a name "
                              "without a suffix)", file=file)


def _samples(trajectory: Any, tree: FrameTree | None
             ) -> tuple[Times, NDArray[np.float64], list[str]]:
    """Times (``datetime64[ns]`` or ``timedelta64[ns]``), positions (T, n) and names."""
    if isinstance(trajectory, JointSolution | Motion):
        absolute = trajectory.absolute_times
        times = absolute if absolute is not None else trajectory.times.astype(
            "timedelta64[ns]")
        names = list(trajectory.joint_names)
        named = (trajectory.urdf_joint_names if tree is None
                 else urdf_joint_names(tree, names))
        return (times, np.asarray(trajectory.positions, np.float64),
                names if named is None else list(named))
    if not isinstance(trajectory, tuple) or len(trajectory) != 3:
        raise ArgumentTypeError("expected a JointSolution or a tuple (times, positions, "
                                f"joint_names), got {type(trajectory).__name__}",
                                field="trajectory")
    raw_times, raw_positions, raw_names = trajectory
    axis = parse_time_axis(raw_times)
    times = axis.as_numpy()
    if times.shape[0] == 0 or np.any(np.diff(axis.offsets) <= 0):
        raise InvalidTimeError("times must be strictly increasing (and at least one)",
                               field="times")
    if isinstance(raw_names, str) or not all(isinstance(n, str) and n for n in raw_names):
        raise ArgumentTypeError("expected a list of non-empty joint names",
                                field="joint_names")
    names = list(raw_names)
    if len(set(names)) != len(names):
        raise InvalidDataError("a joint is named twice", field="joint_names")
    positions = float_array(raw_positions, "positions", InvalidDataError)
    if positions.shape != (times.shape[0], len(names)):
        raise InvalidDataError(f"expected positions of shape ({times.shape[0]}, {len(names)}) "
                               f"(times x joint_names), got {positions.shape}",
                               field="positions")
    return times, positions, names
