"""Reading joint trajectories: joint values over time from CSV or NPZ files.

CSV
    A header line, then one line per sample. The first column is the time: ``time_s``
    (seconds) or ``time`` (seconds, durations such as ``500ms`` or ISO timestamps such as
    ``2024-03-01T08:00:00``). Every other column is one joint, named in the header, in
    radians (revolute, continuous) or metres (prismatic). Empty lines and lines starting
    with ``#`` are skipped.
NPZ
    ``numpy.savez`` arrays ``times`` (T,) (float seconds, ``timedelta64`` or
    ``datetime64``), ``positions`` (T, n) and ``joint_names`` (n,) strings.

Errors name the joint (column) and where the sample is: the line of a CSV file (counted from
1, as editors do, the header included), the sample of an NPZ file (its index in the arrays,
counted from 0, as numpy does).
"""

from __future__ import annotations

import csv
import io
import math
import os
import zipfile
import zlib
from collections.abc import Callable, Sequence
from typing import IO

import numpy as np
from numpy.typing import NDArray

from ...errors import FileFormatError, InvalidTimeError, PinframesError
from ...values.timeconv import format_timestamp_iso, parse_time_axis
from .._paths import path_argument
from .._registry import FileFormat, detect_format, file_format
from ..limits import Limits, current_limits, exceeded, reader_with_limits
from ..reading import InputFile, read_bytes, read_text

__all__ = [
    "CSV_TRAJECTORY_FORMAT",
    "JOINT_TRAJECTORY",
    "NPZ_TRAJECTORY_FORMAT",
    "joint_trajectory_csv",
    "read_csv_trajectory",
    "read_joint_trajectory",
    "read_npz_trajectory",
]

JOINT_TRAJECTORY = "joint trajectory"
"""Registry kind of joint trajectory files (``.csv``, ``.npz``)."""

_TIME_COLUMNS = ("time_s", "time")
_ZIP_MAGIC = b"PK\x03\x04"
# What a broken NPZ raises from numpy and zipfile: a bad header, a short file, a bad CRC or
# deflate stream, a compression method (NotImplementedError, a RuntimeError) or encryption
# that zipfile does not support.
_ARCHIVE_ERRORS = (ValueError, EOFError, OSError, zipfile.BadZipFile, zlib.error, RuntimeError)


@reader_with_limits
def read_joint_trajectory(
    path: str | os.PathLike[str], *, limits: Limits | None = None,
) -> tuple[np.ndarray, NDArray[np.float64], list[str]]:
    """Read joint values over time from a ``.csv`` or ``.npz`` file.

    ``limits`` bounds the rows (``max_samples``) and the decompressed size of an NPZ
    (``max_decompressed_bytes``); see :class:`pinframes.Limits`.

    Returns
    -------
    times : ndarray, shape (T,)
        Strictly increasing. Float seconds (``time_s`` column, float NPZ times),
        ``timedelta64[ns]`` or ``datetime64[ns]``.
    positions : ndarray, shape (T, n)
        Joint values, radians or metres.
    joint_names : list of str
        The n joint names, as written in the file.

    Raises
    ------
    FileFormatError
        Malformed content; the message names the file, the column and the line.
    ReadError
        The file is missing, a folder, unreadable, or (CSV) not UTF-8 text.
    """
    path = path_argument(path)
    reader = file_format(detect_format(path, kind=JOINT_TRAJECTORY), JOINT_TRAJECTORY).read
    assert reader is not None
    return reader(path)


def joint_trajectory_csv(times: np.ndarray, positions: NDArray[np.float64],
                         joint_names: Sequence[str], *, significant_digits: int | None = None,
                         comment: str | None = None) -> str:
    """The text of a ``.csv`` joint trajectory file that :func:`read_joint_trajectory` reads.

    ``times`` (T,) are float seconds (a ``time_s`` column) or ``datetime64`` (a ``time``
    column of ISO timestamps); ``positions`` (T, n) radians or metres, one column per name.
    Names are quoted as CSV quotes them (a name holding a comma or a quote reads back
    whole). Numbers are written to round-trip exactly, or with ``significant_digits``.
    ``comment`` becomes a first ``#`` line.
    """
    def number(value: float) -> str:
        return repr(value) if significant_digits is None else f"{value:.{significant_digits}g}"

    absolute = np.issubdtype(np.asarray(times).dtype, np.datetime64)
    stamps = ([format_timestamp_iso(stamp) for stamp in times] if absolute
              else [number(float(time)) for time in times])
    out = io.StringIO()
    if comment is not None:
        out.write("# " + " ".join(comment.splitlines()) + "\n")
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["time" if absolute else "time_s", *joint_names])
    for stamp, row in zip(stamps, np.asarray(positions, dtype=float).tolist(), strict=True):
        writer.writerow([stamp, *map(number, row)])
    return out.getvalue()


def read_csv_trajectory(
    path: str | os.PathLike[str],
) -> tuple[np.ndarray, NDArray[np.float64], list[str]]:
    """Times, positions and joint names of a ``.csv`` joint trajectory file."""
    text = read_text(path)
    try:
        lines = [(number, row) for number, row in
                 enumerate(csv.reader(io.StringIO(text, newline="")), start=1)
                 if row and any(cell.strip() for cell in row)
                 and not row[0].lstrip().startswith("#")]
    except csv.Error as exc:
        raise FileFormatError(f"not a readable CSV file: {exc}", file=path) from None
    if not lines:
        raise FileFormatError("empty file: expected a header line and samples", file=path)
    header_line, header = lines[0]
    header = [cell.strip() for cell in header]
    if header[0] not in _TIME_COLUMNS:
        raise FileFormatError(
            f"the first column must be the time, named {' or '.join(_TIME_COLUMNS)}; got "
            f"{header[0]!r}", file=path, field=f"line {header_line}")
    names = header[1:]
    _check_names(names, path, f"line {header_line}")
    rows = lines[1:]
    if not rows:
        raise FileFormatError("no samples after the header", file=path)
    positions = np.empty((len(rows), len(names)))
    time_cells = []
    for index, (number, row) in enumerate(rows):
        if len(row) != len(header):
            raise FileFormatError(f"{len(row)} values, but the header has {len(header)} columns",
                                  file=path, field=f"line {number}")
        time_cells.append(row[0].strip())
        for column, cell in enumerate(row[1:]):
            try:
                positions[index, column] = float(cell)
            except ValueError:
                raise FileFormatError(f"expected a number, got {cell.strip()!r}", file=path,
                                      joint=names[column], field=f"line {number}") from None
    times = _csv_times(time_cells, header[0], rows, path)
    _check_samples(times, positions, names, path, lambda index: f"line {rows[index][0]}")
    return times, positions, names


def _csv_times(cells: list[str], column: str, rows: list[tuple[int, list[str]]],
               path: str | os.PathLike[str]) -> np.ndarray:
    if column == "time_s":
        times = np.empty(len(cells))
        for index, cell in enumerate(cells):
            try:
                times[index] = float(cell)
            except ValueError:
                raise FileFormatError(f"expected seconds in '{column}', got {cell!r}",
                                      file=path, field=f"line {rows[index][0]}") from None
        return times
    try:
        axis = parse_time_axis(cells, field=column)
    except InvalidTimeError as exc:
        raise FileFormatError(exc.message, file=path, field=column) from None
    return axis.as_numpy()


def read_npz_trajectory(
    path: str | os.PathLike[str],
) -> tuple[np.ndarray, NDArray[np.float64], list[str]]:
    """Times, positions and joint names of a ``.npz`` joint trajectory file."""
    content = read_bytes(path)
    _check_npz_sizes(content, path)
    try:
        archive = np.load(io.BytesIO(content), allow_pickle=False)
    except _ARCHIVE_ERRORS as exc:
        raise FileFormatError(f"not a readable NPZ file: {exc}", file=path) from None
    if not isinstance(archive, np.lib.npyio.NpzFile):
        raise FileFormatError("not an NPZ archive (written by numpy.savez)", file=path)
    with archive:
        missing = [key for key in ("times", "positions", "joint_names") if key not in archive]
        if missing:
            raise FileFormatError(f"missing array(s) {', '.join(missing)}; expected times, "
                                  "positions and joint_names", file=path)
        arrays = {}
        for key in ("times", "positions", "joint_names"):
            try:
                arrays[key] = archive[key]
            except _ARCHIVE_ERRORS as exc:
                raise FileFormatError(f"cannot read the array: {exc}", file=path,
                                      field=key) from None
    times, positions, names = arrays["times"], arrays["positions"], arrays["joint_names"]
    if names.ndim != 1 or names.dtype.kind not in "US":
        raise FileFormatError(f"expected a 1-D array of strings, got {names.dtype} shape "
                              f"{names.shape}", file=path, field="joint_names")
    name_list = [str(name) for name in names]
    _check_names(name_list, path, "joint_names")
    if times.ndim != 1 or times.size == 0 or times.dtype.kind not in "iufmM":
        raise FileFormatError(f"expected a non-empty 1-D array of times, got {times.dtype} "
                              f"shape {times.shape}", file=path, field="times")
    if positions.dtype.kind not in "iuf" or positions.shape != (times.size, len(name_list)):
        raise FileFormatError(
            f"expected numbers of shape ({times.size}, {len(name_list)}) (times x joint_names), "
            f"got {positions.dtype} shape {positions.shape}", file=path, field="positions")
    if times.dtype.kind in "iu":
        times = times.astype(float)
    positions = positions.astype(float)
    _check_samples(times, positions, name_list, path, lambda index: f"sample {index}")
    return times, positions, name_list


def _check_npz_sizes(content: bytes, path: str | os.PathLike[str]) -> None:
    """Refuse an NPZ that is no ZIP archive, or whose arrays would decompress to more than
    ``max_decompressed_bytes``, from the sizes its ZIP directory and ``.npy`` headers
    declare, before numpy allocates or inflates anything (zipfile never yields more bytes
    than a member declares)."""
    if not zipfile.is_zipfile(io.BytesIO(content)):
        raise FileFormatError("not a readable NPZ file: not a ZIP archive (numpy.savez "
                              "writes one)", file=path)
    limit = current_limits().max_decompressed_bytes
    total = 0
    try:
        with zipfile.ZipFile(io.BytesIO(content)) as archive:
            for info in archive.infolist():
                total += info.file_size
                if total > limit:
                    raise exceeded("max_decompressed_bytes", f"the archive's members "
                                   f"decompress to more than {limit:,} bytes",
                                   field=info.filename).located(file=path)
                if info.filename.endswith(".npy"):
                    with archive.open(info) as member:
                        declared = _npy_bytes(member)
                    if declared > info.file_size:
                        raise FileFormatError(
                            f"the array header declares {declared:,} bytes, but the member "
                            f"holds {info.file_size:,}", file=path, field=info.filename)
    except PinframesError:
        raise
    except _ARCHIVE_ERRORS as exc:
        raise FileFormatError(f"not a readable NPZ file: {exc}", file=path) from None


def _npy_bytes(member: IO[bytes]) -> int:
    """The bytes of the array whose ``.npy`` header starts ``member``."""
    version = np.lib.format.read_magic(member)
    if version == (1, 0):
        shape, _, dtype = np.lib.format.read_array_header_1_0(member)
    elif version == (2, 0):
        shape, _, dtype = np.lib.format.read_array_header_2_0(member)
    else:
        raise ValueError(f".npy format version {version} is not read (1.0 and 2.0 are)")
    return math.prod(shape) * dtype.itemsize


def _check_names(names: list[str], path: str | os.PathLike[str], field: str) -> None:
    if not names:
        raise FileFormatError("no joint columns: expected one column per joint", file=path,
                              field=field)
    seen = set()
    for name in names:
        if not name:
            raise FileFormatError("a joint name is empty", file=path, field=field)
        if name in seen:
            raise FileFormatError("joint named twice", file=path, joint=name, field=field)
        seen.add(name)


def _check_samples(times: np.ndarray, positions: NDArray[np.float64], names: list[str],
                   path: str | os.PathLike[str], where: Callable[[int], str]) -> None:
    """Check the samples a reader read: their count, finite and strictly increasing times,
    finite joint values. ``where(index)`` says where sample ``index`` is in the file (a CSV
    line, an NPZ array index counted from 0), the field of every error."""
    if times.shape[0] > current_limits().max_samples:
        raise exceeded("max_samples", f"{times.shape[0]:,} samples",
                       field="times").located(file=path)
    if times.dtype.kind == "f" and not np.all(np.isfinite(times)):
        index = int(np.argmin(np.isfinite(times)))
        raise FileFormatError(f"the time {times[index]} is not finite", file=path,
                              field=where(index))
    try:
        parse_time_axis(times)  # the same range rules as every other time input
    except InvalidTimeError as exc:
        raise FileFormatError(exc.message, file=path, field="times") from None
    steps = np.diff(times)
    if np.any(steps <= steps.dtype.type(0)):
        index = int(np.argmax(steps <= steps.dtype.type(0))) + 1
        raise FileFormatError(f"times must be strictly increasing; this time is not after "
                              f"the one at {where(index - 1)}", file=path, field=where(index))
    if not np.all(np.isfinite(positions)):
        index, column = (int(i) for i in np.argwhere(~np.isfinite(positions))[0])
        raise FileFormatError(f"the joint value {positions[index, column]} is not finite",
                              file=path, joint=names[column], field=where(index))


def is_csv_trajectory(source: InputFile) -> bool:
    """Whether ``source`` looks like a CSV joint trajectory (its content test): the first
    line that is not a comment is a header whose first column is the time."""
    for line in source.start().splitlines():
        if line.strip() and not line.lstrip().startswith(b"#"):
            cells = [cell.strip() for cell in line.split(b",")]
            return len(cells) > 1 and cells[0].decode("utf-8", "replace") in _TIME_COLUMNS
    return False


def is_npz(source: InputFile) -> bool:
    """Whether ``source`` is a ZIP archive, as ``numpy.savez`` writes (its content test)."""
    return source.start().startswith(_ZIP_MAGIC)


CSV_TRAJECTORY_FORMAT = FileFormat(
    "csv", "CSV", (".csv",), read_csv_trajectory, kind=JOINT_TRAJECTORY,
    head_test=is_csv_trajectory, looks_like="a CSV table of joint values (a joint "
    "trajectory .csv goes in a scene's robots[].trajectory)")
"""Joint trajectories in CSV (see the module docstring)."""
NPZ_TRAJECTORY_FORMAT = FileFormat(
    "npz", "NPZ", (".npz",), read_npz_trajectory, kind=JOINT_TRAJECTORY, head_test=is_npz,
    looks_like="a ZIP archive such as an NPZ file (a joint trajectory .npz goes in a scene's "
    "robots[].trajectory)")
"""Joint trajectories in NPZ (see the module docstring)."""
