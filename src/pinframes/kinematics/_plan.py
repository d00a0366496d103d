"""A planned query: made once from the caller's arguments, then handed on.

A :class:`QueryPlan` holds the query's path (:class:`PreparedPath`: a cached static pose, or
the frames between the two ends and their lowest common ancestor compiled into a
:class:`~pinframes.kinematics._model.CompiledModel`, with the moving things it samples), the
timeline of the requested times (the reference-time rules of
:mod:`pinframes.values.timeline`, the tree's reference time, the ``extrapolation`` policy)
and each sampled source's shift onto its own time basis. Every query takes one or makes one
with :func:`plan_query`; a query that needs another path at the same times asks the plan
(:meth:`QueryPlan.on`), so requested times are parsed and planned once per call.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ExtrapolationError, InvalidTimeError
from ..values.numbers import require_finite_pose
from ..values.se3 import Transform
from ..values.timeconv import TimeAxis, parse_time_axis, timestamp_ns
from ..values.timeline import QueryTimeline, TimedSource, plan_query_timeline
from ._description import ModelLayout, TreeDescription
from ._model import CompiledModel
from ._sampling import (
    JointSampler,
    frame_source,
    path_samplers,
    warn_joints_without_samples,
)

__all__ = ["EXTRAPOLATION_POLICIES", "PreparedPath", "QueryPlan", "plan_query",
           "prepare_path"]

EXTRAPOLATION_POLICIES = ("clamp", "error")
"""Outside its keyframes a moving thing holds its first / last value, or the query fails."""


@dataclass(frozen=True)
class PreparedPath:
    """A query path prepared for repeated evaluation, once per tree version.

    Either ``static`` (the pose of the frame in the reference frame, when nothing between
    them can move) or ``model`` with, per joint, how it is sampled (its
    :mod:`._sampling` sampler), and the moving things they read. ``plans`` keeps what
    queries derive from the path once (the one-time plan), so that it lives as long as the
    path.
    """

    frame: str
    relative_to: str
    static: Transform | None
    model: CompiledModel | None = None
    samplers: tuple[JointSampler, ...] = ()
    sources: tuple[TimedSource, ...] = ()
    plans: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)


def prepare_path(tree: TreeDescription, frame: str, relative_to: str) -> PreparedPath:
    """The query path from ``frame`` to ``relative_to``, compiled once per tree version."""
    key = (frame, relative_to)
    cached = tree.cached(key)
    if cached is not None:
        return cached
    layout = tree.path_layout(frame, relative_to)
    if isinstance(layout, ModelLayout):
        model = CompiledModel(layout)
        path = PreparedPath(frame, relative_to, None, model, *path_samplers(tree, model))
    else:
        require_finite_pose(layout[1], frame, relative_to)
        path = PreparedPath(frame, relative_to, layout)
    tree.store(key, path)
    return path


class QueryPlan:
    """A query's path, its timeline and its sources' shifts, made once per call.

    Attributes
    ----------
    path : PreparedPath
        The path from the query frame to the reference frame.
    timeline : QueryTimeline
        The query's times on one basis, and the reference time of its result.
    times : ndarray of int64 or None
        The times evaluated (timeline basis, ns): all of the timeline's, or one part of
        them (:meth:`part`); None when nothing is sampled (a static result).
    offsets : ndarray of int64 or None
        The result's times for those samples, ns after :attr:`reference_time`.
    shifts : dict of str to int
        Per sampled source (moving frame, driven joint), what to subtract from a timeline
        time to land on its own time basis (ns).
    extrapolation : str
        The policy checked for every path planned on this timeline.
    """

    __slots__ = ("extrapolation", "offsets", "path", "shifts", "timeline", "times")

    def __init__(self, path: PreparedPath, timeline: QueryTimeline, shifts: dict[str, int],
                 extrapolation: str, times: NDArray[np.int64] | None,
                 offsets: NDArray[np.int64] | None) -> None:
        self.path = path
        self.timeline = timeline
        self.shifts = shifts
        self.extrapolation = extrapolation
        self.times = times
        self.offsets = offsets

    @property
    def count(self) -> int:
        """Samples of the result (1 for a static one)."""
        return 1 if self.offsets is None else int(self.offsets.shape[0])

    @property
    def result_times(self) -> NDArray[np.timedelta64] | None:
        """:attr:`offsets` as ``timedelta64[ns]``; None for a static result."""
        return None if self.offsets is None else self.offsets.astype("timedelta64[ns]")

    @property
    def reference_time(self) -> np.datetime64 | None:
        """What the result's times count from."""
        return self.timeline.reference

    @property
    def sample_times(self) -> NDArray[np.int64]:
        """:attr:`times`, or the one time 0 of a path on which nothing is sampled."""
        return np.zeros(1, dtype=np.int64) if self.times is None else self.times

    def on(self, tree: TreeDescription, frame: str, relative_to: str,
           extrapolation: str | None = None) -> QueryPlan:
        """The plan of another path at this plan's times (its sources checked against
        ``extrapolation``, by default this plan's)."""
        path = prepare_path(tree, frame, relative_to)
        return _planned(tree, path, path.sources, (), self.timeline,
                        extrapolation or self.extrapolation, self.times, self.offsets)

    def parts(self, size: int) -> Iterator[tuple[slice, QueryPlan]]:
        """The plan in slices of at most ``size`` samples, with where each goes in the
        result."""
        if self.times is None or self.offsets is None:
            yield slice(0, 1), self
            return
        count = self.times.shape[0]
        if count <= size:
            yield slice(0, count), self
            return
        for start in range(0, count, size):
            part = slice(start, min(count, start + size))
            plan = QueryPlan(self.path, self.timeline, self.shifts, self.extrapolation,
                             self.times[part], self.offsets[part])
            yield part, plan


def plan_query(
    tree: TreeDescription, frame: str, relative_to: str, times: Any, time_ref: Any,
    extrapolation: str, sources: Iterable[TimedSource] | None = None,
    held: Collection[str] = (),
) -> QueryPlan:
    """The plan of a query from the caller's arguments: the path from ``frame`` to
    ``relative_to`` and the timeline of ``times`` / ``time_ref`` on ``sources`` (by default
    the moving things of the path but the ``held`` joints, whose values the caller gives;
    others where the times are those of other things, or of a target).

    Warns (once per tree version) when a joint of the path holds its rest value.
    """
    if extrapolation not in EXTRAPOLATION_POLICIES:
        raise ExtrapolationError(f"expected one of {', '.join(EXTRAPOLATION_POLICIES)}, "
                                 f"got {extrapolation!r}", field="extrapolation")
    requested = None
    if times is not None:
        requested = (_frame_times(tree, times) if isinstance(times, str) and times in tree.depths
                     else parse_time_axis(times, field="times"))
    path = prepare_path(tree, frame, relative_to)
    planned = tuple(source for source in path.sources if source.name not in held
                    ) if sources is None else tuple(sources)
    timeline = _NO_TIMELINE
    if requested is not None or planned:
        timeline = plan_query_timeline(list(planned), requested, time_ref, tree.reference_time,
                                       tree.has_frame_references)
    return _planned(tree, path, planned, held, timeline, extrapolation,
                    timeline.evaluation_times, timeline.result_offsets)


_NO_TIMELINE = QueryTimeline(None, False, None)
"""The timeline of a query without times on a path on which nothing is sampled."""


def _frame_times(tree: TreeDescription, frame: str) -> TimeAxis:
    """The keyframe times of the moving frame ``frame``, for ``times=frame``."""
    if not tree.is_moving(frame):
        raise InvalidTimeError(f"frame {frame!r} does not move, so it has no times to take "
                               "(a string naming a frame means that frame's keyframe times; "
                               "pass seconds as a number or as '5s')", field="times")
    source = frame_source(tree, frame)
    return TimeAxis(source.times, source.reference)


def _planned(tree: TreeDescription, path: PreparedPath, sources: Iterable[TimedSource],
             held: Collection[str], timeline: QueryTimeline, extrapolation: str,
             times: NDArray[np.int64] | None, offsets: NDArray[np.int64] | None) -> QueryPlan:
    """The plan of ``path`` on ``timeline`` at ``times``: each source's shift, its
    keyframes checked against the ``extrapolation`` policy; the warning about joints that
    hold their rest value (but those ``held``)."""
    warn_joints_without_samples(tree, path.samplers, held)
    absolute = timeline.absolute
    shifts = {source.name: (timestamp_ns(source.reference)
                            if absolute and source.reference is not None else 0)
              for source in (*path.sources, *sources)}
    if extrapolation == "error" and times is not None:
        _check_within_keyframes(path.sources, absolute, times)
    return QueryPlan(path, timeline, shifts, extrapolation, times, offsets)


def _check_within_keyframes(sources: Iterable[TimedSource], absolute: bool,
                            requested: NDArray[np.int64]) -> None:
    first, last = requested.min(), requested.max()
    for source in sources:
        keyframes = source.on_basis(absolute)
        early, late = keyframes[0] - first, last - keyframes[-1]
        if early > 0 or late > 0:
            sides = ([f"{early / 1e9:.9g} s before its first keyframe"] if early > 0 else []) + (
                [f"{late / 1e9:.9g} s after its last keyframe"] if late > 0 else [])
            raise ExtrapolationError(
                f"requested times reach {' and '.join(sides)} (extrapolation='error')",
                frame=source.name, field="times")
