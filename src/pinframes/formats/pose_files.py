"""Writing poses per time as CSV, JSON or NPZ, as ``pinframes pose`` does.

Columns ``time_s, x_m, y_m, z_m, qx, qy, qz, qw``: seconds after the pose's reference time,
the origin in metres and the unit quaternion ``(x, y, z, w)``. A static pose is one row whose
time is NaN (``nan`` in CSV, ``null`` in JSON).

CSV
    One header line, then one line of numbers per time, so that
    ``numpy.loadtxt(path, delimiter=",", skiprows=1)`` and ``pandas.read_csv(path)`` read it.
    With a reference time the first column is named ``time_s_after_<timestamp>``
    (``time_s_after_2024-03-01T08:00:00``), so the file carries it.
JSON
    ``{"frame", "relative_to", "reference_time", "units", "poses": [{column: value}]}``.
NPZ
    ``numpy.savez`` arrays ``time_s`` (T,), ``translation`` (T, 3) metres, ``quaternion``
    (T, 4), and the strings ``frame``, ``relative_to`` and ``reference_time`` ("" if none).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import IO, Any

import numpy as np

from ..errors import ArgumentTypeError, FileFormatError
from ..kinematics import Velocity
from ..values.pose import Pose
from ..values.timeconv import format_timestamp_iso
from .atomic import atomic_write

__all__ = ["COLUMNS", "POSE_FILE_FORMATS", "VELOCITY_COLUMNS", "pose_file_format", "poses_text",
           "write_poses"]

COLUMNS = ("time_s", "x_m", "y_m", "z_m", "qx", "qy", "qz", "qw")
VELOCITY_COLUMNS = ("vx_m_s", "vy_m_s", "vz_m_s", "wx_rad_s", "wy_rad_s", "wz_rad_s")
POSE_FILE_FORMATS = ("csv", "json", "npz")


def pose_file_format(path: str | os.PathLike[str]) -> str | None:
    """The format the suffix of ``path`` names (``.csv``, ``.json``, ``.npz``), else None."""
    suffix = Path(path).suffix.lower().lstrip(".")
    return suffix if suffix in POSE_FILE_FORMATS else None


def write_poses(pose: Pose, path: str | os.PathLike[str], format: str | None = None, *,
                frame: str | None = None, relative_to: str | None = None,
                velocity: Velocity | None = None) -> None:
    """Write ``pose`` (of ``frame`` in ``relative_to``, names kept in JSON and NPZ) to
    ``path`` as CSV, JSON or NPZ (``format``, default: from the suffix), atomically; with
    ``velocity`` (at the same times) its columns :data:`VELOCITY_COLUMNS` follow."""
    if not isinstance(pose, Pose):
        raise ArgumentTypeError(f"expected a pinframes.Pose, got {type(pose).__name__}",
                                field="pose")
    format = format or pose_file_format(path)
    if format not in POSE_FILE_FORMATS:
        raise FileFormatError("cannot tell the pose file format: pass format='csv', 'json' "
                              "or 'npz', or name the file .csv, .json or .npz", file=path)
    if format == "npz":
        with atomic_write(path, "wb") as handle:
            _write_npz(handle, pose, frame, relative_to, velocity)
        return
    with atomic_write(path, "w") as handle:
        handle.write(poses_text(pose, format, frame=frame, relative_to=relative_to,
                                velocity=velocity))


def poses_text(pose: Pose, format: str = "csv", *, frame: str | None = None,
               relative_to: str | None = None, velocity: Velocity | None = None) -> str:
    """The CSV or JSON text :func:`write_poses` writes."""
    if format == "csv":
        return _csv_text(pose, velocity)
    if format == "json":
        return _json_text(pose, frame, relative_to, velocity)
    raise FileFormatError(f"expected csv or json text, got {format!r}", field="format")


def _rows(pose: Pose, velocity: Velocity | None = None
          ) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """Seconds (T,) (NaN for a static pose), the values of every row and their column names
    (``x y z qx qy qz qw``, then the velocity's)."""
    if pose.seconds is None:
        seconds = np.array([np.nan])
        values = np.concatenate([pose.translation, pose.quaternion])[None]
    else:
        seconds = pose.seconds
        values = np.concatenate([pose.translation, pose.quaternion], axis=1)
    if velocity is None:
        return seconds, values, COLUMNS[1:]
    values = np.concatenate([values, np.atleast_2d(velocity.linear),
                             np.atleast_2d(velocity.angular)], axis=1)
    return seconds, values, COLUMNS[1:] + VELOCITY_COLUMNS


def _csv_text(pose: Pose, velocity: Velocity | None) -> str:
    seconds, values, names = _rows(pose, velocity)
    reference = _reference_text(pose)
    time_column = COLUMNS[0] if reference is None else f"{COLUMNS[0]}_after_{reference}"
    lines = [",".join([time_column, *names])]
    for time, row in zip(seconds.tolist(), values.tolist(), strict=True):
        lines.append(",".join(map(repr, [time, *row])))
    return "\n".join(lines) + "\n"


def _json_text(pose: Pose, frame: str | None, relative_to: str | None,
               velocity: Velocity | None) -> str:
    seconds, values, names = _rows(pose, velocity)
    records = [
        {COLUMNS[0]: None if np.isnan(time) else time, **dict(zip(names, row, strict=True))}
        for time, row in zip(seconds.tolist(), values.tolist(), strict=True)
    ]
    units = {"time_s": "s", "x_m y_m z_m": "m", "qx qy qz qw": "unit quaternion"}
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


def _write_npz(handle: IO[Any], pose: Pose, frame: str | None,
               relative_to: str | None, velocity: Velocity | None) -> None:
    seconds, values, _ = _rows(pose)
    rates: dict[str, Any] = {} if velocity is None else {
        "linear_velocity_m_s": velocity.linear, "angular_velocity_rad_s": velocity.angular,
        "velocity_axes": np.array(velocity.expressed_in)}
    np.savez(handle, time_s=seconds, translation=values[:, :3], quaternion=values[:, 3:],
             frame=np.array(frame or ""), relative_to=np.array(relative_to or ""),
             reference_time=np.array(_reference_text(pose) or ""), **rates)


def _reference_text(pose: Pose) -> str | None:
    reference = pose.reference_time
    return None if reference is None else format_timestamp_iso(reference)
