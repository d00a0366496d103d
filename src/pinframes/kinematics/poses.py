"""Answering ``FrameTree.poses``: the poses of many (frame, relative_to) pairs in one call.

The pose of ``a`` in ``b`` is ``inv(P_b) @ M(t) @ P_a``, where ``P_a`` is ``a``'s static
placement in its nearest moving ancestor (its *anchor*, cached by the tree) and ``M`` the
pose of ``a``'s anchor in ``b``'s anchor. Pairs whose anchors coincide are static and are
computed together as gathers and one stacked product; the pairs that move are grouped by
their two anchors, and each group costs one query between its anchors (one compiled model,
one interpolation of each moving frame), shared by every pair hanging off the same two
moving frames (all tiles of a map relative to a moving robot, say).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import InvalidTimeError
from ..values.pose_stack import PoseStack
from ._description import TreeDescription
from ._plan import QueryPlan, plan_query
from .pose import planned_transforms

__all__ = ["evaluate_poses", "planned_poses"]


def evaluate_poses(
    tree: TreeDescription, frames: list[str], references: list[str], times: Any, time_ref: Any,
    extrapolation: str,
) -> PoseStack:
    """``tree.poses(frames, references, times, time_ref)``; names already checked. Each
    path between two anchors is planned from the caller's arguments; those that move must
    share one timeline."""
    def plan_between(frame: str, relative_to: str) -> QueryPlan:
        return plan_query(tree, frame, relative_to, times, time_ref, extrapolation)
    return _stacked_poses(tree, frames, references, plan_between)


def planned_poses(tree: TreeDescription, frames: list[str], references: list[str],
                  plan: QueryPlan) -> PoseStack:
    """The poses of ``frames`` in ``references`` at the times of ``plan``."""
    def plan_between(frame: str, relative_to: str) -> QueryPlan:
        return plan.on(tree, frame, relative_to)
    return _stacked_poses(tree, frames, references, plan_between)


def _stacked_poses(tree: TreeDescription, frames: list[str], references: list[str],
                   plan_between: Callable[[str, str], QueryPlan]) -> PoseStack:
    """The poses of the pairs, each path between two anchors planned by ``plan_between``."""
    index = {name: position for position, name in enumerate(dict.fromkeys(frames + references))}
    anchored = [tree.anchor(name) for name in index]
    anchor_index: dict[str, int] = {}
    anchors = np.array([anchor_index.setdefault(anchor, len(anchor_index))
                        for anchor, _ in anchored], dtype=np.intp)
    anchor_names = list(anchor_index)
    rotations = np.array([placement[0] for _, placement in anchored]).reshape(-1, 3, 3)
    translations = np.array([placement[1] for _, placement in anchored]).reshape(-1, 3)
    count = len(frames)
    a = np.fromiter(map(index.__getitem__, frames), dtype=np.intp, count=count)
    b = np.fromiter(map(index.__getitem__, references), dtype=np.intp, count=count)
    # inv(P_b) and P_a per pair
    rotation_b_t = np.swapaxes(rotations[b], 1, 2)
    rotation_a, translation_a = rotations[a], translations[a]
    translation_b = translations[b]
    pair_anchors = anchors[a] * len(anchor_names) + anchors[b]
    moving = anchors[a] != anchors[b]
    if not moving.any():
        rotation = np.matmul(rotation_b_t, rotation_a)
        translation = np.einsum("nij,nj->ni", rotation_b_t, translation_a - translation_b)
        timeline = plan_between(frames[0], references[0])
        if timeline.offsets is None:
            return PoseStack(rotation, translation)
        samples = timeline.count
        return PoseStack(
            np.repeat(rotation[:, None], samples, axis=1),
            np.repeat(translation[:, None], samples, axis=1),
            timeline.offsets, timeline.reference_time)
    groups, members = np.unique(pair_anchors[moving], return_inverse=True)
    plans = []  # per group: the path between its two anchors
    for code in groups:
        plans.append(plan_between(anchor_names[code // len(anchor_names)],
                                  anchor_names[code % len(anchor_names)]))
    # a path through joints without samples, queried without times, holds still: it
    # repeats over the timeline of the paths that move (or the result is static)
    timed = [plan for plan in plans if plan.offsets is not None]
    shared = timed[0] if timed else None
    for plan in timed[1:]:
        _check_same_timeline(timed[0], plan)
    samples = 1 if shared is None else shared.count
    translation = np.empty((count, samples, 3))
    rotation = np.empty((count, samples, 3, 3))
    moving_pairs = np.flatnonzero(moving)
    for group, plan in enumerate(plans):
        pairs = moving_pairs[members == group]
        # inv(P_b) @ M(t) @ P_a for every pair of the group and every time
        between_rotation, between_translation = planned_transforms(tree, plan)
        rotation_m = np.broadcast_to(between_rotation, (samples, 3, 3))
        translation_m = np.broadcast_to(between_translation, (samples, 3))
        placed = np.matmul(rotation_m[None], rotation_a[pairs, None])
        rotation[pairs] = np.matmul(rotation_b_t[pairs, None], placed)
        moved = np.einsum("tij,pj->pti", rotation_m, translation_a[pairs])
        moved += translation_m[None] - translation_b[pairs, None]
        translation[pairs] = np.einsum("pij,ptj->pti", rotation_b_t[pairs], moved)
    static = np.flatnonzero(~moving)
    rotation[static] = np.matmul(rotation_b_t[static], rotation_a[static])[:, None]
    translation[static] = np.einsum("nij,nj->ni", rotation_b_t[static],
                                    translation_a[static] - translation_b[static])[:, None]
    if shared is None:
        return PoseStack(rotation[:, 0], translation[:, 0])
    return PoseStack(rotation, translation, shared.offsets, shared.reference_time)


def _check_same_timeline(first: QueryPlan, other: QueryPlan) -> None:
    same = (first.reference_time == other.reference_time and first.offsets is not None
            and other.offsets is not None and np.array_equal(first.offsets, other.offsets))
    if not same:
        anchor_a, anchor_b = other.path.frame, other.path.relative_to
        raise InvalidTimeError(
            f"the pairs move on different timelines (the path from {anchor_a!r} to "
            f"{anchor_b!r} has other times or another reference time than the first moving "
            "pair); pass times= and time_ref= to put them on one", frame=anchor_a,
            field="times")
