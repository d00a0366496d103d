"""``pinframes transform FILE DATA FRAME -r OTHER``: measured points or vectors into a frame.

``DATA`` is a CSV file with a header: three data columns and optionally ``time_s``. The
data columns name their unit (``x_mm``; see :mod:`._column_units`): points are converted
to metres, moved, and written back in that unit. With ``time_s`` every row is one point at
its own time (seconds after the tree's reference time, or after ``--time-ref``); without it
every point is taken at every time of the time options (default: every keyframe and joint
sample on the path; a static path needs none).
"""

from __future__ import annotations

import argparse
import csv
import io
from collections.abc import Callable

import numpy as np

from ..errors import FileFormatError, InvalidDataError
from ..formats.reading import read_text
from ..values.length_units import LENGTH_SYMBOLS
from ..values.timeconv import TimeAxis, parse_time_axis
from ._column_units import metres_per_unit
from ._evaluate import add_time_arguments, requested_times
from ._extrapolation import add_extrapolation_argument, check_extrapolation
from ._files import read_tree, require_frames
from ._output import require_suffix, write_text
from ._subcommand import Subparsers, subcommand_parser

__all__ = ["add_parser", "run"]

TIME_COLUMN = "time_s"


def add_parser(subparsers: Subparsers, parents: list[argparse.ArgumentParser]) -> None:
    """Register the ``transform`` subcommand."""
    parser = subcommand_parser(
        subparsers, parents, "transform", run,
        help="points or vectors measured in one frame, in another",
        description="Read points (or, with --vectors, directions) given in FRAME from the CSV "
        "file DATA and write them in --relative-to. DATA has a header row naming three data "
        "columns in one unit, LABEL_UNIT (points: "
        f"{', '.join(LENGTH_SYMBOLS)}, or no unit for metres; e.g. x_mm,y_mm,z_mm), kept in "
        f"the output with the data in that unit, and optionally '{TIME_COLUMN}': then each "
        "row is one point at its own time (seconds after the reference time). Without it "
        "every point is written at every time of the time options, with columns time_s, "
        "point (its row number) and the data columns.")
    parser.add_argument("data", metavar="DATA", help="CSV file of points or vectors")
    parser.add_argument("frame", metavar="FRAME", help="the frame the data are given in")
    parser.add_argument("--relative-to", "-r", metavar="OTHER", required=True,
                        help="the frame to write the data in")
    parser.add_argument("--vectors", action="store_true",
                        help="the data are directions (velocities, normals): rotate only "
                        "(default: off, the data are points)")
    add_time_arguments(parser)
    add_extrapolation_argument(parser)
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="write to this CSV file (default: standard output)")


def run(args: argparse.Namespace) -> int:
    """Transform the data and write them."""
    require_suffix(args.output, (".csv",), "CSV")
    tree = read_tree(args.file, args)
    require_frames(tree, args.file, args.frame, args.relative_to)
    names, times, data = _read_data(args.data)
    if not np.all(np.isfinite(data)):
        row = int(np.argwhere(~np.isfinite(data))[0][0])
        raise InvalidDataError(f"line {row + 2}: not a finite number", file=args.data,
                               field=names[int(np.argwhere(~np.isfinite(data[row]))[0][0])])
    factor = metres_per_unit(names, not args.vectors, args.data)
    data = data * factor
    method = tree.transform_vectors if args.vectors else tree.transform_points
    if times is not None:
        if args.times is not None or args.start or args.stop or args.step:
            raise FileFormatError(f"has a '{TIME_COLUMN}' column: leave out the time options",
                                  file=args.data, field=TIME_COLUMN)
        check_extrapolation(args, tree, [(args.frame, args.relative_to)],
                            parse_time_axis(times, field=TIME_COLUMN), args.time_ref)
        out = method(data, args.frame, args.relative_to, times, per_time=True,
                     time_ref=args.time_ref)
        header, rows = [TIME_COLUMN, *names], np.column_stack([times, out])
    else:
        axis = requested_times(args, tree, args.frame, args.relative_to)
        check_extrapolation(args, tree, [(args.frame, args.relative_to)], axis, args.time_ref)
        axis = axis or tree.sample_times(args.frame, args.relative_to)
        if axis is None:  # nothing moves: the points as they are
            header, rows = names, method(data, args.frame, args.relative_to)
        else:
            header, rows = _every_point_at_every_time(method, args, axis, data, names)
    rows = np.array(rows)
    rows[..., -3:] /= factor
    _write(header, rows, args.output)
    return 0


def _every_point_at_every_time(
    method: Callable[..., np.ndarray], args: argparse.Namespace, axis: TimeAxis,
    data: np.ndarray, names: list[str],
) -> tuple[list[str], np.ndarray]:
    """Every point at every time of ``axis``."""
    time_ref = args.time_ref if axis.reference is None else axis.reference
    out = method(data, args.frame, args.relative_to, axis.as_numpy(), time_ref=time_ref)
    count, points = out.shape[:2]
    seconds = np.repeat(axis.offsets / 1e9, points)
    index = np.tile(np.arange(points), count)
    return [TIME_COLUMN, "point", *names], np.column_stack([seconds, index,
                                                          out.reshape(-1, 3)])


def _read_data(path: str) -> tuple[list[str], np.ndarray | None, np.ndarray]:
    """Data column names, times in seconds (or None) and the (N, 3) data of a CSV file."""
    reader = csv.reader(io.StringIO(read_text(path)))
    header = [name.strip() for name in next(reader, [])]
    if len(set(header)) != len(header):
        raise FileFormatError("column names repeat", file=path, field="header")
    names = [name for name in header if name != TIME_COLUMN]
    if len(names) != 3:
        raise FileFormatError(f"expected three data columns besides '{TIME_COLUMN}', got "
                              f"{', '.join(names) or 'none'}", file=path, field="header")
    rows = [row for row in reader if row]
    if not rows:
        raise FileFormatError("no data rows", file=path)
    values = np.empty((len(rows), len(header)))
    for number, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise FileFormatError(f"line {number}: {len(row)} values for {len(header)} columns",
                                  file=path)
        for column, cell in enumerate(row):
            try:
                values[number - 2, column] = float(cell)
            except ValueError:
                raise FileFormatError(f"line {number}: not a number: {cell!r}", file=path,
                                      field=header[column]) from None
    columns = [header.index(name) for name in names]
    times = values[:, header.index(TIME_COLUMN)] if TIME_COLUMN in header else None
    return names, times, values[:, columns]


def _write(header: list[str], rows: np.ndarray, out: str | None) -> None:
    lines = [",".join(header)]
    lines += [",".join(repr(value) for value in row) for row in np.atleast_2d(rows).tolist()]
    write_text("\n".join(lines) + "\n", out)
