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
from ..values.pose import Pose
from ..values.timeconv import format_timestamp_iso
from ._atomic import atomic_write

__all__ = ["COLUMNS", "POSE_FILE_FORMATS", "pose_file_format", "poses_text", "write_poses"]

COLUMNS = ("time_s", "x_m", "y_m", "z_m", "qx", "qy", "qz", "qw")
POSE_FILE_FORMATS = ("csv", "json", "npz")


def pose_file_format(path: str | os.PathLike[str]) -> str | None:
    """The format the suffix of ``path`` names (``.csv``, ``.json``, ``.npz``), else None."""
    suffix = Path(path).suffix.lower().lstrip(".")
    return suffix if suffix in POSE_FILE_FORMATS else None


def write_poses(pose: Pose, path: str | os.PathLike[str], format: str | None = None, *,
                frame: str | None = None, relative_to: str | None = None) -> None:
    """Write ``pose`` (of ``frame`` in ``relative_to``, names kept in JSON and NPZ) to
    ``path`` as CSV, JSON or NPZ (``format``, default: from the suffix), atomically."""
    if not isinstance(pose, Pose):
        raise ArgumentTypeError(f"expected a pinframes.Pose, got {type(pose).__name__}",
                                field="pose")
    format = format or pose_file_format(path)
    if format not in POSE_FILE_FORMATS:
        raise FileFormatError("cannot tell the pose file format: pass format='csv', 'json' "
                              "or 'npz', or name the file .csv, .json or .npz", file=path)
    if format == "npz":
        with atomic_write(path, "wb") as handle:
            _write_npz(handle, pose, frame, relative_to)
        return
    with atomic_write(path, "w") as handle:
        handle.write(poses_text(pose, format, frame=frame, relative_to=relative_to))


def poses_text(pose: Pose, format: str = "csv", *, frame: str | None = None,
               relative_to: str | None = None) -> str:
    """The CSV or JSON text :func:`write_poses` writes."""
    if format == "csv":
        return _csv_text(pose)
    if format == "json":
        return _json_text(pose, frame, relative_to)
    raise FileFormatError(f"expected csv or json text, got {format!r}", field="format")


def _rows(pose: Pose) -> tuple[np.ndarray, np.ndarray]:
    """Seconds (T,) (NaN for a static pose) and ``x y z qx qy qz qw`` (T, 7)."""
    if pose.seconds is None:
        return np.array([np.nan]), np.concatenate([pose.translation, pose.quaternion])[None]
    return pose.seconds, np.concatenate([pose.translation, pose.quaternion], axis=1)


def _csv_text(pose: Pose) -> str:
    seconds, values = _rows(pose)
    reference = _reference_text(pose)
    time_column = COLUMNS[0] if reference is None else f"{COLUMNS[0]}_after_{reference}"
    lines = [",".join([time_column, *COLUMNS[1:]])]
    for time, row in zip(seconds.tolist(), values.tolist(), strict=True):
        lines.append(",".join(map(repr, [time, *row])))
    return "\n".join(lines) + "\n"


def _json_text(pose: Pose, frame: str | None, relative_to: str | None) -> str:
    seconds, values = _rows(pose)
    records = [
        {COLUMNS[0]: None if np.isnan(time) else time,
         **dict(zip(COLUMNS[1:], row, strict=True))}
        for time, row in zip(seconds.tolist(), values.tolist(), strict=True)
    ]
    document = {
        "frame": frame,
        "relative_to": relative_to,
        "reference_time": _reference_text(pose),
        "units": {"time_s": "s", "x_m y_m z_m": "m", "qx qy qz qw": "unit quaternion"},
        "poses": records,
    }
    return json.dumps(document, indent=1) + "\n"


def _write_npz(handle: IO[Any], pose: Pose, frame: str | None,
               relative_to: str | None) -> None:
    seconds, values = _rows(pose)
    np.savez(handle, time_s=seconds, translation=values[:, :3], quaternion=values[:, 3:],
             frame=np.array(frame or ""), relative_to=np.array(relative_to or ""),
             reference_time=np.array(_reference_text(pose) or ""))


def _reference_text(pose: Pose) -> str | None:
    reference = pose.reference_time
    return None if reference is None else format_timestamp_iso(reference)
