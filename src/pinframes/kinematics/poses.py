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

from typing import Any

import numpy as np

from ..errors import InvalidTimeError
from ..values.pose import Pose
from ..values.pose_stack import PoseStack
from ._description import TreeDescription
from .pose import evaluate_pose

__all__ = ["evaluate_poses"]


def evaluate_poses(
    tree: TreeDescription, frames: list[str], references: list[str], times: Any, time_ref: Any,
    extrapolation: str,
) -> PoseStack:
    """``tree.poses(frames, references, times, time_ref)``; names already checked."""
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
        if times is None:
            return PoseStack(rotation, translation)
        timeline = evaluate_pose(tree, frames[0], references[0], times, time_ref,
                                 extrapolation)
        samples = len(timeline)
        return PoseStack(
            np.repeat(rotation[:, None], samples, axis=1),
            np.repeat(translation[:, None], samples, axis=1),
            timeline._times, timeline.reference_time)
    groups, members = np.unique(pair_anchors[moving], return_inverse=True)
    betweens = []  # per group: its two anchors and the pose of one in the other
    for code in groups:
        anchor_a = anchor_names[code // len(anchor_names)]
        anchor_b = anchor_names[code % len(anchor_names)]
        betweens.append((anchor_a, anchor_b, evaluate_pose(tree, anchor_a, anchor_b, times,
                                                           time_ref, extrapolation)))
    # a path through joints without samples, queried without times, holds still: it
    # repeats over the timeline of the paths that move (or the result is static)
    timed = [entry for entry in betweens if entry[2]._times is not None]
    shared = timed[0][2] if timed else None
    for anchor_a, anchor_b, between in timed[1:]:
        _check_same_timeline(timed[0][2], between, anchor_a, anchor_b)
    samples = 1 if shared is None else len(shared)
    translation = np.empty((count, samples, 3))
    rotation = np.empty((count, samples, 3, 3))
    moving_pairs = np.flatnonzero(moving)
    for group, (_, _, between) in enumerate(betweens):
        pairs = moving_pairs[members == group]
        # inv(P_b) @ M(t) @ P_a for every pair of the group and every time
        rotation_m = np.broadcast_to(between.rotation, (samples, 3, 3))
        translation_m = np.broadcast_to(between.translation, (samples, 3))
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
    return PoseStack(rotation, translation, shared._times, shared.reference_time)


def _check_same_timeline(first: Pose, other: Pose, anchor_a: str, anchor_b: str) -> None:
    same = (first.reference_time == other.reference_time and first._times is not None
            and other._times is not None and np.array_equal(first._times, other._times))
    if not same:
        raise InvalidTimeError(
            f"the pairs move on different timelines (the path from {anchor_a!r} to "
            f"{anchor_b!r} has other times or another reference time than the first moving "
            "pair); pass times= and time_ref= to put them on one", frame=anchor_a,
            field="times")
