"""Writing poses per time as CSV, JSON or NPZ: ``time_s, x, y, z, qx, qy, qz, qw``.

``time_s`` is seconds after the result's reference time (empty / null / NaN for a static
pose); ``x y z`` metres; ``qx qy qz qw`` a unit quaternion. With a velocity, six columns
follow: ``vx_m_s vy_m_s vz_m_s`` (metres per second) and ``wx_rad_s wy_rad_s wz_rad_s``
(radians per second).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import IO, Any

import numpy as np

from ..errors import FileFormatError
from ..formats._atomic import atomic_write
from ..kinematics import Velocity
from ..values.pose import Pose

__all__ = ["COLUMNS", "OUTPUT_FORMATS", "VELOCITY_COLUMNS", "output_format", "pose_rows",
           "write_poses", "write_text"]

COLUMNS = ("time_s", "x", "y", "z", "qx", "qy", "qz", "qw")
VELOCITY_COLUMNS = ("vx_m_s", "vy_m_s", "vz_m_s", "wx_rad_s", "wy_rad_s", "wz_rad_s")
OUTPUT_FORMATS = ("csv", "json", "npz")


def output_format(requested: str | None, out: str | None) -> str:
    """The format asked for, else the one the output file name implies, else CSV."""
    if requested is not None:
        return requested
    if out is not None:
        suffix = Path(out).suffix.lower().lstrip(".")
        if suffix in OUTPUT_FORMATS:
            return suffix
    return "csv"


def pose_rows(pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Seconds (T,) (NaN for a static pose) and ``x y z qx qy qz qw`` (T, 7)."""
    if not pose.is_time_dependent:
        return np.array([np.nan]), np.concatenate([pose.translation, pose.quaternion])[None]
    seconds = pose.keyframes.times / 1e9
    return seconds, np.concatenate([pose.translation, pose.quaternion], axis=1)


def write_poses(pose: Pose, fmt: str, out: str | None, *, frame: str, relative_to: str,
                velocity: Velocity | None = None) -> None:
    """Write ``pose`` (of ``frame`` in ``relative_to``) to the file ``out`` or stdout, with
    the columns of ``velocity`` (at the same times) after the pose's when given."""
    if fmt == "npz":
        if out is None:
            raise FileFormatError("NPZ output is binary: give a file with -o")
        with atomic_write(out, "wb") as handle:
            _write_npz(handle, pose, frame, relative_to, velocity)
        return
    write_text(_csv_text(pose, velocity) if fmt == "csv"
               else _json_text(pose, frame, relative_to, velocity), out)


def write_text(text: str, out: str | None) -> None:
    """``text`` to the file ``out`` (atomically) or to standard output."""
    if out is None:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    with atomic_write(out, "w") as handle:
        handle.write(text)


def _columns(pose: Pose, velocity: Velocity | None
             ) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """Seconds, the values of every row, and the column names after ``time_s``."""
    seconds, values = pose_rows(pose)
    if velocity is None:
        return seconds, values, COLUMNS[1:]
    values = np.concatenate([values, velocity.linear, velocity.angular], axis=1)
    return seconds, values, COLUMNS[1:] + VELOCITY_COLUMNS


def _csv_text(pose: Pose, velocity: Velocity | None) -> str:
    seconds, values, names = _columns(pose, velocity)
    lines = [",".join(("time_s", *names))]
    for time, row in zip(seconds.tolist(), values.tolist(), strict=True):
        time_text = "" if np.isnan(time) else repr(time)
        lines.append(",".join([time_text, *map(repr, row)]))
    return "\n".join(lines) + "\n"


def _json_text(pose: Pose, frame: str, relative_to: str, velocity: Velocity | None) -> str:
    seconds, values, names = _columns(pose, velocity)
    records = [
        {"time_s": None if np.isnan(time) else time, **dict(zip(names, row, strict=True))}
        for time, row in zip(seconds.tolist(), values.tolist(), strict=True)
    ]
    units = {"time_s": "s", "xyz": "m", "quaternion": "x y z w"}
    if velocity is not None:
        units.update({"v": "m/s", "w": "rad/s", "velocity_axes": velocity.expressed_in})
    document = {
        "frame": frame,
        "relative_to": relative_to,
        "reference_time": _reference_text(pose),
        "units": units,
        "poses": records,
    }
    return json.dumps(document, indent=1) + "\n"


def _write_npz(handle: IO[bytes], pose: Pose, frame: str, relative_to: str,
               velocity: Velocity | None) -> None:
    seconds, values = pose_rows(pose)
    rates: dict[str, Any] = {} if velocity is None else {
        "linear_velocity_m_s": velocity.linear, "angular_velocity_rad_s": velocity.angular,
        "velocity_axes": np.array(velocity.expressed_in)}
    np.savez(handle, time_s=seconds, translation=values[:, :3], quaternion=values[:, 3:],
             frame=np.array(frame), relative_to=np.array(relative_to),
             reference_time=np.array(_reference_text(pose) or ""), **rates)


def _reference_text(pose: Pose) -> str | None:
    return None if pose.reference_time is None else str(pose.reference_time)
