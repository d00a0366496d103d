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

pinframes reads no pose file; the three formats are registered (kind :data:`POSES`,
:data:`POSE_FORMATS`) with their content tests, so that a reader given one says so.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import IO, Any

import numpy as np

from ...errors import ArgumentTypeError, FileFormatError
from ...kinematics import Velocity
from ...values.pose import Pose
from ...values.timeconv import format_timestamp_iso
from .._registry import FileFormat
from ..atomic import atomic_write
from ..reading import InputFile

__all__ = ["COLUMNS", "POSES", "POSE_FILE_FORMATS", "POSE_FORMATS", "VELOCITY_COLUMNS",
           "pose_file_format", "poses_text", "write_poses"]

COLUMNS = ("time_s", "x_m", "y_m", "z_m", "qx", "qy", "qz", "qw")
"""The columns of a pose: seconds, the origin in metres, the unit quaternion (x, y, z, w)."""
VELOCITY_COLUMNS = ("vx_m_s", "vy_m_s", "vz_m_s", "wx_rad_s", "wy_rad_s", "wz_rad_s")
"""The columns of a velocity: its origin's (m/s), then the angular velocity (rad/s)."""
POSE_FILE_FORMATS = ("csv", "json", "npz")
POSES = "poses"
"""Registry kind of pose files."""
_ZIP_MAGIC = b"PK\x03\x04"


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
    units = {COLUMNS[0]: "s", " ".join(COLUMNS[1:4]): "m",
             " ".join(COLUMNS[4:]): "unit quaternion"}
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


def _is_pose_csv(source: InputFile) -> bool:
    """A CSV header of :data:`COLUMNS` (the time column may name its reference time)."""
    header = source.start().split(b"\n", 1)[0].decode("utf-8", "replace").strip()
    time, _, rest = header.partition(",")
    return (time == COLUMNS[0] or time.startswith(f"{COLUMNS[0]}_after_")) and (
        rest.split(",")[:len(COLUMNS) - 1] == list(COLUMNS[1:]))


def _is_pose_json(source: InputFile) -> bool:
    """A JSON object with the keys :func:`poses_text` writes first and last."""
    return source.start().startswith(b"{") and all(
        f'"{key}":'.encode() in source.head() for key in ("frame", "relative_to", "poses"))


def _is_pose_npz(source: InputFile) -> bool:
    """A ZIP archive whose first member is ``time_s.npy``, as :func:`write_poses` writes
    (the member's name starts at byte 30 of the archive, its length at byte 26)."""
    head = source.head()
    length = int.from_bytes(head[26:28], "little")
    return head.startswith(_ZIP_MAGIC) and head[30:30 + length] == f"{COLUMNS[0]}.npy".encode()


POSE_FORMATS = (
    FileFormat("csv", "CSV", (".csv",), kind=POSES, head_test=_is_pose_csv,
               looks_like="a CSV table of poses (pinframes pose writes those)"),
    FileFormat("json", "JSON", (".json",), kind=POSES, head_test=_is_pose_json,
               looks_like="a JSON file of poses (pinframes pose -f json writes those)"),
    FileFormat("npz", "NPZ", (".npz",), kind=POSES, head_test=_is_pose_npz,
               looks_like="a ZIP archive of poses in NPZ (pinframes pose writes those)"),
)
"""The pose file formats, as the registry holds them (:data:`POSE_FILE_FORMATS` by name)."""
