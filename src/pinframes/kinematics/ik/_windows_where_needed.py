"""Process windows only where needed: a solve with ``tilt=`` first solves the nominal
orientation (the tool's z the target's: no tilt), and uses the windows only on the stretches
the nominal solve misses.

Solved with its windows throughout, the smallest joint motion from sample to sample spends
the free tilt on saving joint motion, and the tool drifts into a corner of its windows for
the whole path, also where it could hold the target's orientation. Here every sample the
nominal solve reaches keeps its nominal solution (tilt 0); each stretch it misses is solved
with the windows from the nominal solution before it (the smallest motion from there tilts
only as far as the stretch needs), and the jumps where the stretches join are bridged as any
other; all by the one tracker given (:class:`._trackers.JumpsBridged`).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import NDArray

from ._between_samples import DEFAULT_PATH_TOLERANCE, Deviations, densely_tracked, deviations
from ._newton_tracking import Tracked
from ._path_chunks import PathToSolve
from ._tool_error import AxisMatch, PoseMatch, WindowMatch, tilts_of
from ._trackers import JumpsBridged

__all__ = ["nominal_where_reachable"]

FloatArray = NDArray[np.float64]


def nominal_where_reachable(
    request: PathToSolve, windows: WindowMatch, start: FloatArray, search_starts: bool,
    strict: bool, frame: str, tolerance: tuple[float, float] | None, track: JumpsBridged,
) -> tuple[PathToSolve, Tracked, FloatArray, Deviations]:
    """As :func:`densely_tracked` for a request whose match is ``windows``: the request on
    the times solved (its match ``windows``), the solutions, their tilts (T, 2) and
    deviations (see the module docstring)."""
    nominal = AxisMatch("z") if windows.free_spin else PoseMatch()
    solved, tracked, _, _ = densely_tracked(dataclasses.replace(request, error=nominal),
                                            start, search_starts, False, frame, tolerance,
                                            track)
    request = dataclasses.replace(solved, error=windows)
    missed = ~tracked.reached
    if missed.any():
        edges = np.flatnonzero(np.diff(np.concatenate([[False], missed, [False]]).astype(int)))
        for begin, end in zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True):
            rows = np.arange(begin, end)
            stretch, _ = track.tracker(request.at(rows),
                                       tracked.positions[begin - 1] if begin else start,
                                       search_starts and not begin, False, frame)
            for name in ("positions", "position_error", "orientation_error", "reached",
                         "measured"):
                getattr(tracked, name)[rows] = getattr(stretch, name)
        tracked = track.bridged(request, tracked, frame)
    if strict:
        request.require_reached(tracked, frame)
    tilts = tilts_of(request.tools_in_targets(request.plan.sample_times, tracked.positions)[0])
    measuring = DEFAULT_PATH_TOLERANCE if tolerance is None else tolerance
    return request, tracked, tilts, deviations(request, tracked.positions, measuring)
