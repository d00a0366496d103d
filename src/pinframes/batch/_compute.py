"""One run's poses, evaluated chunk by chunk as Arrow tables (one row per sample).

Columns: ``run`` (the run id), ``time_s`` (seconds after the result's reference time, or
the relative time when there is none), ``timestamp`` (the absolute time, ``timestamp[ns]``,
null without a reference time), ``x_m y_m z_m`` (the translation of ``frame`` in
``relative_to``, metres) and ``qx qy qz qw`` (its unit quaternion, ``w >= 0``). With
``options.velocity``, also ``vx_m_s vy_m_s vz_m_s`` (the velocity of ``frame``'s origin
relative to ``relative_to``, m/s) and ``wx_rad_s wy_rad_s wz_rad_s`` (its angular velocity,
rad/s), both in ``relative_to``'s axes: :meth:`FrameTree.velocity` at the same times.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
import pyarrow as pa  # type: ignore[import-untyped]

from .. import FrameTree, Pose, TimeAxis, Velocity
from ..errors import FrameNotFoundError, InvalidTimeError, near_misses
from ..formats.tables import COLUMNS, VELOCITY_COLUMNS
from ._options import BatchOptions

__all__ = ["MAX_GRID_SAMPLES", "POSE_SCHEMA", "VELOCITY_SCHEMA", "output_schema",
           "pose_chunks"]

MAX_GRID_SAMPLES = 50_000_000
"""The most times a ``step`` may resample one run to (about 4 GB of rows); the grid is
checked before any of it is made, and made one chunk at a time."""

# the columns of pose files (pinframes pose), with the run id and the absolute time
POSE_SCHEMA = pa.schema([
    ("run", pa.string()),
    (COLUMNS[0], pa.float64()),
    ("timestamp", pa.timestamp("ns")),
    *((name, pa.float64()) for name in COLUMNS[1:]),
])
VELOCITY_SCHEMA = pa.schema([(name, pa.float64()) for name in VELOCITY_COLUMNS])


def output_schema(options: BatchOptions) -> pa.Schema:
    """The columns of the rows ``options`` asks for: the pose's, then the velocity's."""
    if not options.velocity:
        return POSE_SCHEMA
    return pa.schema([*POSE_SCHEMA, *VELOCITY_SCHEMA])


def pose_chunks(tree: FrameTree, run_id: str, options: BatchOptions) -> Iterator[pa.Table]:
    """The poses of ``options.frame`` in ``options.relative_to`` for one run, at most
    ``options.chunk_size`` rows per table, so memory stays bounded for long runs; with
    ``options.velocity``, the velocity columns too (see the module docstring)."""
    for name in (options.frame, options.relative_to):
        if name is not None and name not in tree:
            raise FrameNotFoundError("no frame of this name in this run"
                                     + near_misses(name, tree.frames), frame=name)
    relative_to = options.relative_to or tree.parent(options.frame)
    if relative_to is None:
        tree.pose(options.frame)  # raises the error for the root, which has no parent
        raise AssertionError("unreachable: the root has no pose in its parent")
    times = _query_times(tree, options.frame, relative_to, options)
    for start in range(0, times.count, options.chunk_size):
        chunk = times.chunk(start, start + options.chunk_size)
        pose = tree.pose(options.frame, relative_to=relative_to, times=chunk,
                         time_ref=times.time_ref)
        velocity = tree.velocity(options.frame, relative_to, chunk,
                                 time_ref=times.time_ref) if options.velocity else None
        yield _table(run_id, pose, velocity, output_schema(options))


@dataclass(frozen=True)
class _QueryTimes:
    """The times of one run's query, made chunk by chunk: ``offsets`` (int64 ns) or, for
    a resampled run, the grid ``offsets[0] + k * step_ns`` for ``k < count``."""

    offsets: np.ndarray
    reference: np.datetime64 | None
    time_ref: np.datetime64 | None
    step_ns: int | None
    count: int

    def chunk(self, start: int, stop: int) -> np.ndarray:
        """Times ``start`` to ``stop`` (timedelta64 or datetime64 [ns])."""
        stop = min(stop, self.count)
        if self.step_ns is None:
            offsets = self.offsets[start:stop]
        else:
            offsets = self.offsets[0] + self.step_ns * np.arange(start, stop, dtype=np.int64)
        return TimeAxis(offsets, self.reference).as_numpy()


def _query_times(tree: FrameTree, frame: str, relative_to: str, options: BatchOptions
                 ) -> _QueryTimes:
    """The times to evaluate and the query's time_ref; a resampling grid of more than
    :data:`MAX_GRID_SAMPLES` times is an :class:`InvalidTimeError` at ``step``, found
    before any of it is made."""
    axis = options.times if options.times is not None else tree.sample_times(frame, relative_to)
    if axis is None:
        raise InvalidTimeError(f"nothing moves between {frame!r} and {relative_to!r} in "
                               "this run: give explicit times", field="times")
    time_ref = options.time_ref if options.times is not None else axis.reference
    offsets = axis.offsets
    count = offsets.shape[0]
    if options.step_ns is not None:
        count = (int(offsets[-1]) - int(offsets[0])) // options.step_ns + 1
        if count > MAX_GRID_SAMPLES:
            raise InvalidTimeError(
                f"resampling this run from its first to its last sample "
                f"({(int(offsets[-1]) - int(offsets[0])) / 1e9:g} s) every "
                f"{options.step_ns / 1e9:g} s gives {count:,} times, more than "
                f"{MAX_GRID_SAMPLES:,}; take a larger step", field="step")
    return _QueryTimes(offsets, axis.reference, time_ref, options.step_ns, count)


def _table(run_id: str, pose: Pose, velocity: Velocity | None, schema: pa.Schema
           ) -> pa.Table:
    times = pose.times
    assert times is not None  # a query at given times is sampled at those times
    count = times.shape[0]
    absolute = pose.absolute_times
    quaternion = pose.quaternion
    columns = [
        pa.repeat(pa.scalar(run_id, pa.string()), count),
        pa.array(times.astype(np.int64) / 1e9),
        pa.nulls(count, pa.timestamp("ns")) if absolute is None else pa.array(absolute),
        *(pa.array(pose.translation[:, axis]) for axis in range(3)),
        *(pa.array(quaternion[:, axis]) for axis in range(4)),
    ]
    if velocity is not None:
        columns += [pa.array(rates[:, axis]) for rates in (velocity.linear, velocity.angular)
                    for axis in range(3)]
    return pa.Table.from_arrays(columns, schema=schema)
