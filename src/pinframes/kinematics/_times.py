"""The times of a query: requested times (a frame name, seconds, timestamps) put on one
timeline by the reference-time rules (docs/time-semantics.md, :mod:`pinframes.values.timeline`)
with the tree's reference time, the ``extrapolation`` policy, and each source's shift from
the timeline to its own time basis.
"""

from __future__ import annotations

from typing import Any

from ..errors import ExtrapolationError, InvalidTimeError
from ..values.timeconv import TimeAxis, parse_time_axis, timestamp_ns
from ..values.timeline import QueryTimeline, TimedSource, plan_query_timeline
from ._description import TreeDescription
from ._path import PreparedPath

__all__ = ["EXTRAPOLATION_POLICIES", "basis_shifts", "checked_timeline", "plan_timeline"]

EXTRAPOLATION_POLICIES = ("clamp", "error")
"""Outside its keyframes a moving thing holds its first / last value, or the query fails."""


def checked_timeline(
    tree: TreeDescription, path: PreparedPath, times: Any, time_ref: Any, extrapolation: str,
) -> QueryTimeline:
    """The timeline of a query on ``path``, with its ``extrapolation`` policy checked and
    applied."""
    if extrapolation not in EXTRAPOLATION_POLICIES:
        raise ExtrapolationError(f"expected one of {', '.join(EXTRAPOLATION_POLICIES)}, "
                                 f"got {extrapolation!r}", field="extrapolation")
    sources = list(path.sources)
    timeline = plan_timeline(tree, sources, times, time_ref)
    if extrapolation == "error" and timeline.evaluation_times is not None:
        _check_within_keyframes(sources, timeline)
    return timeline


def plan_timeline(
    tree: TreeDescription, sources: list[TimedSource], times: Any, time_ref: Any
) -> QueryTimeline:
    """The evaluation times of a query on ``sources`` (docs/time-semantics.md)."""
    return plan_query_timeline(sources, _requested_times(tree, times), time_ref,
                               tree.reference_time, tree.has_frame_references)


def basis_shifts(sources: list[TimedSource], timeline: QueryTimeline) -> dict[str, int]:
    """Per source, what to subtract from timeline times (ns) to land on its own time basis."""
    return {
        s.name: timestamp_ns(s.reference)
        if timeline.absolute and s.reference is not None else 0
        for s in sources
    }


def _requested_times(tree: TreeDescription, times: Any) -> TimeAxis | None:
    if times is None:
        return None
    if isinstance(times, str) and times in tree.depths:
        if not tree.is_moving(times):
            raise InvalidTimeError(f"frame {times!r} does not move, so it has no times to "
                                   "take (a string naming a frame means that frame's "
                                   "keyframe times; pass seconds as a number or as '5s')",
                                   field="times")
        source = tree.frame_source(times)
        return TimeAxis(source.times, source.reference)
    return parse_time_axis(times, field="times")


def _check_within_keyframes(sources: list[TimedSource], timeline: QueryTimeline) -> None:
    requested = timeline.evaluation_times
    assert requested is not None  # checked only for queries at times
    first, last = requested.min(), requested.max()
    for source in sources:
        keyframes = source.on_basis(timeline.absolute)
        early, late = keyframes[0] - first, last - keyframes[-1]
        if early > 0 or late > 0:
            sides = ([f"{early / 1e9:.9g} s before its first keyframe"] if early > 0 else []) + (
                [f"{late / 1e9:.9g} s after its last keyframe"] if late > 0 else [])
            raise ExtrapolationError(
                f"requested times reach {' and '.join(sides)} (extrapolation='error')",
                frame=source.name, field="times")
