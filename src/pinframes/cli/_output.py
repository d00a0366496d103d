"""Writing poses per time as CSV, JSON or NPZ: ``time_s, x, y, z, qx, qy, qz, qw``.

``time_s`` is seconds after the result's reference time (empty / null / NaN for a static
pose); ``x y z`` metres; ``qx qy qz qw`` a unit quaternion.
"""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import numpy as np

from ..errors import FileFormatError
from ..formats._atomic import atomic_write
from ..values.pose import Pose

__all__ = ["COLUMNS", "OUTPUT_FORMATS", "output_format", "pose_rows", "write_poses"]

COLUMNS = ("time_s", "x", "y", "z", "qx", "qy", "qz", "qw")
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
    seconds = pose.times.astype(np.int64) / 1e9
    return seconds, np.concatenate([pose.translation, pose.quaternion], axis=1)


def write_poses(pose: Pose, fmt: str, out: str | None, *, frame: str, relative_to: str
                ) -> None:
    """Write ``pose`` (of ``frame`` in ``relative_to``) to the file ``out`` or stdout."""
    if fmt == "npz":
        if out is None:
            raise FileFormatError("NPZ output is binary: give a file with -o")
        with atomic_write(out, "wb") as handle:
            _write_npz(handle, pose, frame, relative_to)
        return
    text = _csv_text(pose) if fmt == "csv" else _json_text(pose, frame, relative_to)
    if out is None:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    with atomic_write(out, "w") as handle:
        handle.write(text)


def _csv_text(pose: Pose) -> str:
    seconds, values = pose_rows(pose)
    lines = [",".join(COLUMNS)]
    for time, row in zip(seconds.tolist(), values.tolist(), strict=True):
        time_text = "" if np.isnan(time) else repr(time)
        lines.append(",".join([time_text, *map(repr, row)]))
    return "\n".join(lines) + "\n"


def _json_text(pose: Pose, frame: str, relative_to: str) -> str:
    seconds, values = pose_rows(pose)
    records = [
        {"time_s": None if np.isnan(time) else time,
         **dict(zip(COLUMNS[1:], row, strict=True))}
        for time, row in zip(seconds.tolist(), values.tolist(), strict=True)
    ]
    document = {
        "frame": frame,
        "relative_to": relative_to,
        "reference_time": _reference_text(pose),
        "units": {"time_s": "s", "xyz": "m", "quaternion": "x y z w"},
        "poses": records,
    }
    return json.dumps(document, indent=1) + "\n"


def _write_npz(handle: io.BufferedWriter, pose: Pose, frame: str, relative_to: str) -> None:
    seconds, values = pose_rows(pose)
    np.savez(handle, time_s=seconds, translation=values[:, :3], quaternion=values[:, 3:],
             frame=np.array(frame), relative_to=np.array(relative_to),
             reference_time=np.array(_reference_text(pose) or ""))


def _reference_text(pose: Pose) -> str | None:
    return None if pose.reference_time is None else str(pose.reference_time)
