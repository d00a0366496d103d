"""The sample times of a query path: what ``FrameTree.pose`` evaluates at by default."""

from __future__ import annotations

from . import _query
from .timeconv import TimeAxis
from .tree import FrameTree

__all__ = ["sample_times"]


def sample_times(tree: FrameTree, frame: str, relative_to: str) -> TimeAxis | None:
    """Every keyframe and joint sample time on the path from ``frame`` to ``relative_to``.

    The times ``tree.pose(frame, relative_to)`` evaluates at, without evaluating: offsets
    in nanoseconds after the reference time that result would carry (None if it has none).
    Returns None when nothing on the path moves.
    """
    tree.path(frame, relative_to)  # raises for unknown frames
    evaluation = _query._evaluation(tree, frame, relative_to)
    if evaluation.model is None:
        return None
    sources = _query.model_sources(tree, evaluation.model)
    timeline = _query.plan_timeline(tree, sources, None, None)
    if timeline.evaluation_times is None:
        return None
    return TimeAxis(timeline.result_offsets, timeline.reference)
