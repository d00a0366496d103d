"""Between samples: how far the tool strays from its target while the solved joints move
linearly from one sample to the next (what a controller interpolating the solution does),
and default times made dense enough that it stays within the path tolerance.

The deviation of an interval is measured at its midpoint, and at its quarter points too
where the midpoint strays more than a quarter of the tolerance: the solved joints
interpolated linearly (radians or metres), everything else and the target sampled at those
times as a pose query would, the tool compared with the target by the solve's own match (the
whole pose, a free axis, process windows). Without times, every interval whose two ends
reached their targets and whose deviation passes the tolerance is halved (its midpoint
added), and the path solved again from the same first solution, until none passes or the
intervals that do are :data:`SHORTEST_INTERVAL` long (a jump no sample can bridge: see
``JointSolution.jumps``) or the samples reach :data:`MOST_SAMPLES`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .._plan import QueryPlan
from .._sampling import KERNEL_CHUNK
from ._newton_tracking import Tracked
from ._path_chunks import PathToSolve
from ._trackers import Tracker

__all__ = ["DEFAULT_PATH_TOLERANCE", "MOST_SAMPLES", "SHORTEST_INTERVAL", "Deviations",
           "densely_tracked", "deviations"]

FloatArray = NDArray[np.float64]

QUARTERS_FROM = 0.25
"""The share of the path tolerance past which an interval's midpoint has its quarter points
measured too (a chord strays 3/4 as far there as at its middle)."""

SHORTEST_INTERVAL = 1_000_000
"""Nanoseconds (1 ms): an interval this short is not halved again."""

DEFAULT_PATH_TOLERANCE = (1e-4, math.radians(0.1))
"""How far (metres, radians: 0.1 mm, 0.1 degree) the tool may stray from its target between
two default samples while the solved joints move linearly from the one to the other."""

MOST_SAMPLES = 1_000_000
"""The default times are not made denser than this many samples."""


@dataclass(frozen=True)
class Deviations:
    """Per sample (T,), the largest position (m) and orientation (rad) deviation of the
    joint-interpolated tool from its target between it and the sample before (0 for the
    first)."""

    position: FloatArray
    orientation: FloatArray

    def over(self, length: float, angle: float) -> NDArray[np.bool_]:
        """Per sample, whether its interval passes ``length`` (m) or ``angle`` (rad)."""
        return (self.position > length) | (self.orientation > angle)


def deviations(request: PathToSolve, positions: FloatArray, tolerance: tuple[float, float]
               ) -> Deviations:
    """The :class:`Deviations` of the solved joints at ``positions`` (T, n) on the times of
    ``request``'s plan: at each interval's midpoint, and at its quarter points where the
    midpoint strays more than :data:`QUARTERS_FROM` of ``tolerance`` (metres, radians)."""
    moments = request.plan.sample_times
    count = moments.shape[0]
    position, orientation = np.zeros(count), np.zeros(count)
    for begin in range(1, count, KERNEL_CHUNK):
        ends = np.arange(begin, min(count, begin + KERNEL_CHUNK))
        apart, turned = _strays(request, positions, ends, 2)
        position[ends], orientation[ends] = apart, turned
        near = ends[(apart > QUARTERS_FROM * tolerance[0])
                    | (turned > QUARTERS_FROM * tolerance[1])]
        for quarter in (1, 3):
            if near.shape[0]:
                apart, turned = _strays(request, positions, near, quarter)
                np.maximum(position[near], apart, out=position[near])
                np.maximum(orientation[near], turned, out=orientation[near])
    return Deviations(position, orientation)


def _strays(request: PathToSolve, positions: FloatArray, ends: NDArray[np.intp],
            quarter: int) -> tuple[FloatArray, FloatArray]:
    """Position (m) and orientation (rad) errors of the tool, by the request's match, at
    ``quarter`` quarters of the interval before each sample ``ends``, the solved joints
    linear between its two samples."""
    moments = request.plan.sample_times
    before, after = moments[ends - 1], moments[ends]
    times = before + (after - before) * quarter // 4  # no float rounding of ns
    between = positions[ends - 1] + (positions[ends] - positions[ends - 1]) * (quarter / 4)
    return request.error.errors(*request.tools_in_targets(times, between))


def densely_tracked(request: PathToSolve, start: FloatArray, search_starts: bool,
                    strict: bool, frame: str, tolerance: tuple[float, float] | None,
                    track: Tracker) -> tuple[PathToSolve, Tracked, FloatArray | None, Deviations]:
    """``request`` solved by ``track`` (any :class:`._trackers.Tracker`) on its plan's
    times, with ``tolerance`` (metres, radians) on times made denser where an interval
    passes it (see the module docstring): the request on the times solved, its solutions,
    tilts and deviations. An added sample that is not reached is taken out again, and the
    interval it halved is not halved again (a target interpolated off what the joints can
    reach)."""
    measuring = DEFAULT_PATH_TOLERANCE if tolerance is None else tolerance
    tracked, tilts = track(request, start, search_starts, strict, frame)
    measured = deviations(request, tracked.positions, measuring)
    if tolerance is None:
        return request, tracked, tilts, measured
    first = tracked.positions[0]
    given = np.ones(len(tracked.reached), dtype=bool)  # not added
    settled = np.zeros_like(given)  # per sample, the interval before it is not halved
    while True:
        moments = request.plan.sample_times
        lengths = np.zeros(moments.shape[0], dtype=np.int64)
        lengths[1:] = np.diff(moments)
        both_reached = np.zeros_like(given)
        both_reached[1:] = tracked.reached[1:] & tracked.reached[:-1]
        halved = np.flatnonzero(measured.over(*tolerance) & both_reached & ~settled
                                & (lengths >= 2 * SHORTEST_INTERVAL))
        if not halved.shape[0] or moments.shape[0] + halved.shape[0] > MOST_SAMPLES:
            break
        request = dataclasses.replace(request, plan=_with_midpoints(request.plan, halved))
        given, settled = np.insert(given, halved, False), np.insert(settled, halved, False)
        tracked, tilts = track(request, first, False, False, frame)
        missed = np.flatnonzero(~given & ~tracked.reached)
        if missed.shape[0]:
            settled[missed + 1] = True  # (an added sample always has one after it)
            kept = np.ones_like(given)
            kept[missed] = False
            request = request.at(kept)
            tracked = tracked.taken(kept)
            tilts = None if tilts is None else tilts[kept]
            given, settled = given[kept], settled[kept]
        measured = deviations(request, tracked.positions, measuring)
    if strict:  # a sample given lost on the way
        request.require_reached(tracked, frame)
    return request, tracked, tilts, measured


def _with_midpoints(plan: QueryPlan, halved: NDArray[np.intp]) -> QueryPlan:
    """``plan`` with the midpoint of the interval before each sample ``halved`` added."""
    assert plan.times is not None and plan.offsets is not None
    times, offsets = plan.times, plan.offsets
    middles = times[halved - 1] + (times[halved] - times[halved - 1]) // 2
    shift = offsets[0] - times[0]  # offsets are the times less the reference
    return QueryPlan(plan.path, plan.timeline, plan.shifts, plan.extrapolation,
                     np.insert(times, halved, middles), np.insert(offsets, halved,
                                                                  middles + shift))
