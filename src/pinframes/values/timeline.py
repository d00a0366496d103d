"""Which times a query is evaluated at, and which reference time its result carries.

Implements the weldx ``CoordinateSystemManager.get_cs`` rules (docs/time-semantics.md). All times
here are int64 nanoseconds: *offsets* relative to a reference, or *absolute* nanoseconds
since the epoch when any reference time is involved.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ExtrapolationError, InvalidTimeError, ReferenceTimeError
from .timeconv import TimeAxis, parse_timestamp, shift_ns, timestamp_ns

__all__ = ["QueryTimeline", "TimedSource", "plan_query_timeline", "source_reference"]


def source_reference(own: np.datetime64 | None, tree_reference: np.datetime64 | None
                     ) -> np.datetime64 | None:
    """What the times of a moving frame or a driven joint count from: its own reference
    time, else its tree's (docs/time-semantics.md); None when neither has one."""
    return own if own is not None else tree_reference


@dataclass(frozen=True)
class TimedSource:
    """Keyframe times of one moving thing on a query path (a moving frame or a joint).

    ``reference`` is its own reference time, or the tree's for a source without one.
    """

    name: str
    times: NDArray[np.int64]
    reference: np.datetime64 | None

    def on_basis(self, absolute: bool) -> NDArray[np.int64]:
        """Keyframe times as absolute nanoseconds, or as plain offsets."""
        if absolute and self.reference is not None:
            return shift_ns(self.times, timestamp_ns(self.reference),
                            field=f"times of {self.name!r}")
        return self.times


@dataclass(frozen=True)
class QueryTimeline:
    """The times a query is evaluated at.

    Attributes
    ----------
    evaluation_times : ndarray of int64 or None
        Times on the sources' basis (absolute ns if ``absolute``, else offsets); None for a
        static result.
    absolute : bool
        Whether ``evaluation_times`` and the sources' times are absolute nanoseconds.
    reference : numpy.datetime64 or None
        Reference time of the result.
    """

    evaluation_times: NDArray[np.int64] | None
    absolute: bool
    reference: np.datetime64 | None

    def shifts(self, sources: Iterable[TimedSource]) -> dict[str, int]:
        """Per source, what to subtract from a time of this timeline (ns) to land on the
        source's own time basis."""
        absolute = self.absolute
        return {source.name: (timestamp_ns(source.reference)
                              if absolute and source.reference is not None else 0)
                for source in sources}

    def require_within(self, sources: Iterable[TimedSource], times: NDArray[np.int64]
                       ) -> None:
        """An :class:`~pinframes.errors.ExtrapolationError` naming the source when
        ``times`` (on this timeline) reach before a source's first sample or after its
        last (``extrapolation='error'``)."""
        first, last = times.min(), times.max()
        for source in sources:
            samples = source.on_basis(self.absolute)
            early, late = samples[0] - first, last - samples[-1]
            if early > 0 or late > 0:
                sides = ([f"{early / 1e9:.9g} s before its first keyframe"] if early > 0
                         else []) + ([f"{late / 1e9:.9g} s after its last keyframe"]
                                     if late > 0 else [])
                raise ExtrapolationError(
                    f"requested times reach {' and '.join(sides)} (extrapolation='error')",
                    frame=source.name, field="times")

    @property
    def result_offsets(self) -> NDArray[np.int64] | None:
        """Times of the result relative to :attr:`reference`."""
        if self.evaluation_times is None or not self.absolute:
            return self.evaluation_times
        assert self.reference is not None  # absolute times always carry their reference
        try:
            return shift_ns(self.evaluation_times, -timestamp_ns(self.reference))
        except InvalidTimeError:
            raise ReferenceTimeError(
                f"the result's times lie more than 292 years from its reference time "
                f"{self.reference}, beyond int64 nanoseconds; query at given times with "
                f"a time_ref nearer to them", field="time_ref") from None


def plan_query_timeline(
    sources: list[TimedSource],
    times: TimeAxis | None,
    time_ref: Any,
    tree_reference: np.datetime64 | None,
    tree_has_frame_references: bool,
) -> QueryTimeline:
    """Apply the reference-time table of docs/time-semantics.md to one query.

    Parameters
    ----------
    sources
        The moving things on the query path.
    times
        The requested times, or None for the union of the sources' keyframes.
    time_ref
        The query's ``time_ref`` argument (ignored when ``times`` is None).
    tree_reference
        The tree's own reference time.
    tree_has_frame_references
        Whether the tree's moving frames carry reference times of their own.
    """
    source_references = [s.reference for s in sources if s.reference is not None]
    lowest_source_reference = min(source_references) if source_references else None
    if times is None:
        if not sources:
            return QueryTimeline(None, False, None)
        absolute = lowest_source_reference is not None
        union = _union([s.on_basis(absolute) for s in sources])
        reference = tree_reference if tree_reference is not None else lowest_source_reference
        return _within_reach_of_sources(QueryTimeline(union, absolute, reference), sources)

    query_reference = None
    if time_ref is not None:
        query_reference = parse_timestamp(time_ref, field="time_ref")
        if (tree_reference is None and not tree_has_frame_references
                and not times.is_absolute):
            raise ReferenceTimeError(
                "a time_ref was given, but neither the tree nor its frames have a reference "
                "time, so it is ambiguous; query without time_ref and set the reference time "
                "of the result yourself", field="time_ref")
    reference = next(
        (r for r in (query_reference, tree_reference, lowest_source_reference, times.reference)
         if r is not None),
        None,
    )
    if times.is_absolute or reference is not None:
        base = times.reference if times.is_absolute else reference
        assert base is not None
        requested = shift_ns(times.offsets, timestamp_ns(base))
    else:
        return QueryTimeline(times.offsets, False, None)
    if sources and lowest_source_reference is None:
        raise ReferenceTimeError(
            "absolute times or a time_ref were given, but the moving frames on this path ("
            + ", ".join(s.name for s in sources) + ") have no reference time",
            field="times")
    return _within_reach_of_sources(QueryTimeline(requested, True, reference), sources)


def _union(times: list[NDArray[np.int64]]) -> NDArray[np.int64]:
    """The distinct times of all ``times`` in increasing order (a new array). One strictly
    increasing array is copied as it is: sorting it again took ``np.unique`` 1 ms per 10^4
    times, a target pose's own times in ``FrameTree.solve_joints``."""
    if len(times) == 1 and bool(np.all(times[0][1:] > times[0][:-1])):
        return times[0].copy()
    return np.unique(np.concatenate(times))


def _within_reach_of_sources(timeline: QueryTimeline, sources: list[TimedSource]
                             ) -> QueryTimeline:
    """``timeline``, once each source can count its times from its own reference time.

    Sources sample at timeline times minus their reference; numpy would wrap that around for
    times more than 292 years from the reference, and the frame would be sampled at a
    wrong time.
    """
    times = timeline.evaluation_times
    if not timeline.absolute or times is None:
        return timeline
    ends = np.array([times.min(), times.max()])
    for source in sources:
        if source.reference is None:
            continue
        try:
            shift_ns(ends, -timestamp_ns(source.reference))
        except InvalidTimeError:
            raise ReferenceTimeError(
                f"the query's times lie more than 292 years from this frame's reference time "
                f"{source.reference}, beyond int64 nanoseconds", frame=source.name,
                field="reference_time") from None
    return timeline
