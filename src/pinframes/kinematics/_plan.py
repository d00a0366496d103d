"""A planned query: made once from the caller's arguments, then handed on.

A :class:`QueryPlan` holds the query's path (:class:`PreparedPath`: a cached static pose, or
the frames between the two ends and their lowest common ancestor compiled into a
:class:`~pinframes.kinematics._model.CompiledModel`, with the moving things it samples), the
timeline of the requested times (the reference-time rules of
:mod:`pinframes.values.timeline`, the tree's reference time, the ``extrapolation`` policy)
and each sampled source's shift onto its own time basis. Every query takes one or makes one
with :func:`plan_query`; a query that needs another path at the same times asks the plan
(:meth:`QueryPlan.on`), so requested times are parsed and planned once per call; a query
that reads several frames against each other plans one model holding them all
(``also=``), sampled once for every pair of them.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ExtrapolationError
from ..values.numbers import require_finite_pose
from ..values.se3 import Transform
from ..values.timeconv import parse_time_axis
from ..values.timeline import QueryTimeline, TimedSource, plan_query_timeline
from ._description import ModelLayout, TreeDescription
from ._memo import Memo
from ._model import CompiledModel
from ._sampling import (
    JointSampler,
    frame_times,
    path_samplers,
    warn_joints_without_samples,
)

__all__ = ["EXTRAPOLATION_POLICIES", "PreparedPath", "QueryPlan", "plan_query",
           "prepare_path"]

EXTRAPOLATION_POLICIES = ("clamp", "error")
"""Outside its keyframes a moving thing holds its first / last value, or the query fails."""

_WITHOUT_TIMES = {policy: f"plan without times, {policy}" for policy in EXTRAPOLATION_POLICIES}
"""Where a path keeps its plan without times (per policy)."""


@dataclass(frozen=True)
class PreparedPath:
    """A query path prepared for repeated evaluation, once per tree version.

    Either ``static`` (the pose of the frame in the reference frame, when nothing between
    them can move) or ``model`` (holding both ends and any frames asked for beside them)
    with, per joint, how it is sampled (its :mod:`._sampling` sampler), the moving things
    they read, and the joints without samples (``resting``, held at their rest value).
    ``plans`` keeps what queries derive from the path once (the one-time plan, the plan
    without times), so that it lives as long as the path.
    """

    frame: str
    relative_to: str
    static: Transform | None
    model: CompiledModel | None = None
    samplers: tuple[JointSampler, ...] = ()
    sources: tuple[TimedSource, ...] = ()
    resting: frozenset[str] = frozenset()
    plans: Memo = field(default_factory=Memo, compare=False, repr=False)


def prepare_path(tree: TreeDescription, frame: str, relative_to: str,
                 also: Sequence[str] = ()) -> PreparedPath:
    """The query path from ``frame`` to ``relative_to``, compiled once per tree version.

    With frames ``also``, always a compiled model, rooted at the lowest common ancestor of
    them all and holding them all: one sampling of it serves every pair of its frames.
    """
    key = (frame, relative_to, *also)
    cached = tree.memo.get(PreparedPath, key)
    if cached is not None:
        return cached
    layout = tree.path_layout(frame, relative_to, also)
    if not isinstance(layout, ModelLayout):
        require_finite_pose(layout[1], frame, relative_to)
        path = PreparedPath(frame, relative_to, layout)
    else:
        model = CompiledModel(layout)
        path = PreparedPath(frame, relative_to, None, model, *path_samplers(tree, model))
    return tree.memo.keep(PreparedPath, key, path)


@dataclass(slots=True)
class QueryPlan:
    """A query's path, its timeline and its sources' shifts, made once per call (and
    never changed: a plan may be kept with its path and handed to several queries).

    Attributes
    ----------
    path : PreparedPath
        The path from the query frame to the reference frame.
    timeline : QueryTimeline
        The query's times on one basis, and the reference time of its result.
    shifts : dict of str to int
        Per sampled source (moving frame, driven joint), what to subtract from a timeline
        time to land on its own time basis (ns).
    extrapolation : str
        The policy checked for every path planned on this timeline.
    times : ndarray of int64 or None
        The times evaluated (timeline basis, ns): all of the timeline's, or one part of
        them (:meth:`parts`); None when nothing is sampled (a static result).
    offsets : ndarray of int64 or None
        The result's times for those samples, ns after :attr:`reference_time`.
    """

    path: PreparedPath
    timeline: QueryTimeline
    shifts: dict[str, int]
    extrapolation: str
    times: NDArray[np.int64] | None
    offsets: NDArray[np.int64] | None

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
        policy, timeline, times = extrapolation or self.extrapolation, self.timeline, self.times
        if path.resting:
            warn_joints_without_samples(tree, path.resting)
        if policy == "error" and times is not None:
            timeline.require_within(path.sources, times)
        return QueryPlan(path, timeline, timeline.shifts(path.sources), policy, times,
                         self.offsets)

    def at(self, rows: NDArray[np.intp] | NDArray[np.bool_] | slice) -> QueryPlan:
        """This plan at some of its samples (indices in any order, a mask or a slice)."""
        assert self.times is not None and self.offsets is not None
        return QueryPlan(self.path, self.timeline, self.shifts, self.extrapolation,
                         self.times[rows], self.offsets[rows])

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
    held: Collection[str] = (), extra: Iterable[TimedSource] = (), also: Sequence[str] = (),
) -> QueryPlan:
    """The plan of a query from the caller's arguments: the path from ``frame`` to
    ``relative_to`` (its model holding the frames ``also`` too, :func:`prepare_path`) and
    the timeline of ``times`` / ``time_ref`` on ``sources`` (by default the moving things
    of the path but the ``held`` joints, whose values the caller gives, and the ``extra``
    ones, a target's or another path's; others where the times are those of other
    things).

    Warns (once per tree version) when a joint of the path holds its rest value.
    """
    if extrapolation not in EXTRAPOLATION_POLICIES:
        raise ExtrapolationError(f"expected one of {', '.join(EXTRAPOLATION_POLICIES)}, "
                                 f"got {extrapolation!r}", field="extrapolation")
    path = prepare_path(tree, frame, relative_to, also)
    own_sources = sources is None and not held and not extra
    without_times = times is None and own_sources
    if without_times:  # the same plan every time: kept with the path
        kept = path.plans.get(QueryPlan, _WITHOUT_TIMES[extrapolation])
        if kept is not None:
            return kept
    if path.resting:
        warn_joints_without_samples(tree, path.resting, held)
    planned = path.sources if own_sources else tuple(sources) if sources is not None else (
        *(source for source in path.sources if source.name not in held), *extra)
    requested = None
    if isinstance(times, str) and times in tree.depths:
        requested = frame_times(tree, times)
    elif times is not None:
        requested = parse_time_axis(times, field="times")
    timeline = _NO_TIMELINE
    if requested is not None or planned:
        timeline = plan_query_timeline(list(planned), requested, time_ref, tree.reference_time,
                                       tree.has_frame_references)
    evaluated = timeline.evaluation_times
    shifts = timeline.shifts(planned if own_sources else (*path.sources, *planned))
    if extrapolation == "error" and evaluated is not None:
        timeline.require_within(path.sources, evaluated)
    plan = QueryPlan(path, timeline, shifts, extrapolation, evaluated, timeline.result_offsets)
    if without_times:
        path.plans.keep(QueryPlan, _WITHOUT_TIMES[extrapolation], plan)
    return plan


_NO_TIMELINE = QueryTimeline(None, False, None)
"""The timeline of a query without times on a path on which nothing is sampled."""
