"""Evaluating pose queries for the command line: time options, chunks and a progress bar."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import Any, TextIO, TypeVar

import numpy as np

from ..errors import InvalidTimeError
from ..kinematics import Velocity
from ..tree import FrameTree
from ..values.pose import Pose
from ..values.timeconv import (
    TimeAxis,
    parse_time_axis,
    parse_timedelta,
    parse_timestamp,
    timestamp_ns,
)

__all__ = ["ProgressBar", "add_time_arguments", "in_chunks", "pose_in_chunks", "pose_velocity",
           "requested_times", "terminal_stderr", "times_from_options"]

Result = TypeVar("Result")

POSE_CHUNK_SIZE = 20_000
"""Times a pose query takes per call; the progress bar moves once per chunk."""

MAX_SAMPLES = 50_000_000
"""The most times a --start/--stop/--step grid may have (about 3 GB of poses)."""

_BAR_WIDTH = 30


def add_time_arguments(parser: argparse.ArgumentParser) -> None:
    """``--times`` or ``--start/--stop/--step``, and ``--time-ref``."""
    group = parser.add_argument_group(
        "times", "Times are seconds (1.5), durations (500ms, 2s, P0DT0H0M2S) or timestamps "
        "(2024-03-01T08:00:00). Relative times count from --time-ref, else from the "
        "tree's reference time. Default: every keyframe and joint sample on the path.")
    group.add_argument("--times", nargs="+", metavar="T",
                       help="these times (default: every sample on the path)")
    group.add_argument("--start", metavar="T", help="first time of a grid (default: the first "
                       "sample on the path)")
    group.add_argument("--stop", metavar="T", help="last time of a grid, included when it "
                       "falls on the grid (default: the last sample on the path)")
    group.add_argument("--step", metavar="DT", help="grid step, a positive duration (default: "
                       "none, no grid)")
    group.add_argument("--time-ref", metavar="TIMESTAMP",
                       help="reference time that relative times count from (default: the "
                       "tree's, else the earliest of the moving frames' on the path)")


def requested_times(args: argparse.Namespace, tree: FrameTree, frame: str,
                    relative_to: str) -> TimeAxis | None:
    """The times asked for by the time options (None: every sample on the path)."""
    return times_from_options(args, lambda: tree.sample_times(frame, relative_to))


def times_from_options(args: argparse.Namespace,
                       default_times: Callable[[], TimeAxis | None]) -> TimeAxis | None:
    """The times asked for by the time options; None when none are given. A grid without
    ``--start`` or ``--stop`` ends where ``default_times()`` (the query's own times) ends."""
    grid = args.start is not None or args.stop is not None or args.step is not None
    if args.times is not None and grid:
        raise InvalidTimeError("give either --times or --start/--stop/--step, not both",
                               field="--times")
    if args.times is not None:
        return parse_time_axis(args.times, field="--times")
    if not grid:
        return None
    if args.step is None:
        raise InvalidTimeError("--start and --stop need --step", field="--step")
    step = int(parse_timedelta(args.step, field="--step").astype(np.int64))
    if step <= 0:
        raise InvalidTimeError(f"must be a positive duration, got {args.step!r}",
                               field="--step")
    samples = default_times()
    if samples is None and (args.start is None or args.stop is None):
        raise InvalidTimeError("nothing on this path moves, so give both --start and --stop",
                               field="--step")
    ends = [_grid_end(args.start, "--start", samples, 0),
            _grid_end(args.stop, "--stop", samples, -1)]
    if ends[0][0] != ends[1][0]:
        base = (parse_timestamp(args.time_ref, field="--time-ref") if args.time_ref
                else None if samples is None else samples.reference)
        if base is None:
            raise InvalidTimeError("--start and --stop must both be timestamps or both "
                                   "relative times", field="--stop")
        ends = [(True, value if absolute else value + int(base.astype(np.int64)))
                for absolute, value in ends]
    (absolute, first), (_, last) = ends
    if last < first:
        raise InvalidTimeError("--stop is before --start", field="--stop")
    count = (last - first) // step + 1
    if count > MAX_SAMPLES:
        raise InvalidTimeError(f"this grid has {count} times, more than {MAX_SAMPLES}; take a "
                               "larger --step", field="--step")
    offsets = step * np.arange(count, dtype=np.int64)
    if absolute:
        return TimeAxis(offsets, np.datetime64(first, "ns"))
    return TimeAxis(first + offsets, None)


def _grid_end(value: str | None, field: str, samples: TimeAxis | None, index: int
              ) -> tuple[bool, int]:
    """One end of a grid: (is absolute, nanoseconds since the epoch or offset)."""
    if value is not None:
        axis = parse_time_axis([value], field=field)
    else:
        assert samples is not None  # the caller passes the path's samples without a value
        axis = TimeAxis(samples.offsets[[index]], samples.reference)
    if axis.reference is None:
        return False, int(axis.offsets[0])
    return True, int(axis.offsets[0]) + timestamp_ns(axis.reference)


def pose_in_chunks(tree: FrameTree, frame: str, relative_to: str, times: TimeAxis | None,
                   time_ref: Any = None, *, progress: TextIO | None = None) -> Pose:
    """``tree.pose(frame, relative_to, times, time_ref)``, in chunks of
    :data:`POSE_CHUNK_SIZE` times.

    With ``progress`` (a terminal), a text bar on it shows how far the evaluation is.
    """
    if times is None:
        times = tree.sample_times(frame, relative_to)
        if times is None:
            return tree.pose(frame, relative_to=relative_to)
        time_ref = times.reference
    parts = in_chunks(lambda values: tree.pose(frame, relative_to, values, time_ref), times,
                      progress)
    return parts[0] if len(parts) == 1 else _concatenate(parts)


def in_chunks(query: Callable[[np.ndarray], Result], times: TimeAxis,
              progress: TextIO | None, size: int = POSE_CHUNK_SIZE) -> list[Result]:
    """``query(values)`` for consecutive chunks of at most ``size`` of ``times``
    (``timedelta64`` values, or ``datetime64`` with a reference), with a progress bar on
    ``progress`` (a terminal) when there is more than one chunk."""
    values = times.as_numpy()
    count = values.shape[0]
    bar = ProgressBar(progress, count) if progress is not None and count > size else None
    parts = []
    for start in range(0, count, size):
        parts.append(query(values[start:start + size]))
        if bar is not None:
            bar.update(min(start + size, count))
    if bar is not None:
        bar.close()
    return parts


def pose_velocity(tree: FrameTree, pose: Pose, frame: str, relative_to: str,
                  expressed_in: str | None = None) -> Velocity:
    """``tree.velocity`` of ``frame`` in ``relative_to`` at the times of ``pose`` (its
    result), so that rows line up."""
    offsets, reference = pose.times, pose.reference_time
    if offsets is None:
        return tree.velocity(frame, relative_to, expressed_in=expressed_in)
    times = offsets if reference is None else reference + offsets
    return tree.velocity(frame, relative_to, times, expressed_in, time_ref=reference)


def _concatenate(parts: list[Pose]) -> Pose:
    """One pose from consecutive chunks, on the first chunk's reference time."""
    reference = parts[0].reference_time
    if reference is None:
        times = np.concatenate([part.times for part in parts])
    else:
        times = np.concatenate([part.absolute_times for part in parts])
    return Pose(np.concatenate([part.translation for part in parts]),
                np.concatenate([part.rotation for part in parts]), times=times,
                reference_time=reference)


class ProgressBar:
    """``[#######.......]  45%  9000/20000 samples`` redrawn in place on a terminal."""

    def __init__(self, stream: TextIO, total: int) -> None:
        self._stream = stream
        self._total = total
        self.update(0)

    def update(self, done: int) -> None:
        filled = _BAR_WIDTH * done // self._total
        percent = 100 * done // self._total
        self._stream.write(f"\r[{'#' * filled}{'.' * (_BAR_WIDTH - filled)}] {percent:3d}%  "
                           f"{done}/{self._total} samples")
        self._stream.flush()

    def close(self) -> None:
        self._stream.write("\n")
        self._stream.flush()


def terminal_stderr() -> TextIO | None:
    """Standard error when it is a terminal (where a progress bar belongs), else None."""
    return sys.stderr if sys.stderr.isatty() else None
