"""The clearance along a planned motion, between its samples too.

At each sample, ``FrameTree.clearance`` measures the smallest distance ``d`` between the
shapes of ``a`` and ``b``. Between two samples the joints move linearly (as the tree
interpolates them), and no point of a shape moves further from where it was at either
sample than

    delta = sum_j |dq_j| (r_j + rho) (1 + sum_j |dq_j|)

over the program joints ``j`` that move the shape: ``|dq_j|`` the joint's step (radians),
``r_j`` the distance from the joint's origin to the shape's frame origin (the larger of the
two samples'), ``rho`` the radius of a sphere about that origin holding every shape of the
frame (a prismatic joint: its step, metres); the last factor covers ``r_j`` growing within
the step. So the interval is clear when ``max(d_k, d_k+1) - delta_a - delta_b`` is at least
the margin; where it is not, the interval is halved, and the middle measured, until it is
(at most :data:`MAX_HALVINGS` times; what is left is reported at the bound).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ArgumentTypeError
from ..kinematics.collision.coal_objects import ShapeLoader
from ..tree import FrameTree
from ..values.geometry import GEOMETRY_METADATA_KEY
from ..values.motion import CollisionRecord, MoveRecord

__all__ = ["MAX_HALVINGS", "ClearanceCheck", "collisions", "parse_check"]

FloatArray = NDArray[np.float64]

MAX_HALVINGS = 10
"""How often an interval between two samples is halved before its bound is reported."""


@dataclass(frozen=True)
class ClearanceCheck:
    """What ``check=`` asks: the frames (names or patterns) of both sides, the pairs left
    out and the margin, metres."""

    a: str | tuple[str, ...]
    b: str | tuple[str, ...]
    exclude: tuple[tuple[str, str], ...] = ()
    margin: float = 0.0


def parse_check(check: Any) -> ClearanceCheck | None:
    """``check=``: None, ``(a, b)`` or a mapping with ``a``, ``b``, ``exclude``, ``margin``."""
    if check is None or isinstance(check, ClearanceCheck):
        return check
    if isinstance(check, Mapping):
        unknown = set(check) - {"a", "b", "exclude", "margin"}
        if unknown or "a" not in check or "b" not in check:
            raise ArgumentTypeError("check= takes a, b, exclude and margin (a and b required)",
                                    field="check")
        exclude = tuple((str(first), str(second)) for first, second in check.get("exclude", ()))
        return ClearanceCheck(_side(check["a"]), _side(check["b"]), exclude,
                              float(check.get("margin", 0.0)))
    if isinstance(check, Sequence) and not isinstance(check, str) and len(check) == 2:
        return ClearanceCheck(_side(check[0]), _side(check[1]))
    raise ArgumentTypeError("expected check=(a, b) or check=dict(a=..., b=..., exclude=..., "
                            f"margin=...), got {check!r}", field="check")


def collisions(tree: FrameTree, joint_names: tuple[str, ...], seconds: FloatArray,
               positions: FloatArray, records: Sequence[MoveRecord],
               rows: Sequence[tuple[int, int]], check: ClearanceCheck
               ) -> tuple[CollisionRecord, ...]:
    """One record per move that comes closer than the margin: its closest approach."""
    work = tree.copy()
    work.set_joint_trajectory(seconds, positions, joint_names)
    measured = work.clearance(check.a, check.b, times=seconds, exclude=check.exclude)
    reach = _Reach(work, joint_names, measured.frames_a, measured.frames_b, seconds)
    times, distances, pairs = [seconds], [measured.distance], [measured.closest]
    starts, ends = seconds[:-1], seconds[1:]
    at_start, at_end = measured.distance[:-1], measured.distance[1:]
    steps = np.abs(np.diff(positions, axis=0))
    interval = np.arange(steps.shape[0])
    for _ in range(MAX_HALVINGS + 1):
        # an interval with a sample too close already is reported at that sample
        apart = (np.minimum(at_start, at_end) >= check.margin) & (np.minimum(at_start, at_end) > 0)
        open_ = apart & (np.maximum(at_start, at_end) - reach.bound(steps, interval)
                         < check.margin)
        if not open_.any():
            break
        starts, ends, at_start, at_end = starts[open_], ends[open_], at_start[open_], at_end[open_]
        steps, interval = steps[open_] / 2, interval[open_]
        middle = (starts + ends) / 2
        if len(times) > MAX_HALVINGS:  # give up halving: report the bound
            times.append(middle)
            distances.append(np.maximum(at_start, at_end) - reach.bound(steps * 2, interval))
            pairs.append(measured.closest[interval])
            break
        found = work.clearance(check.a, check.b, times=middle, exclude=check.exclude)
        times.append(middle)
        distances.append(found.distance)
        pairs.append(found.closest)
        starts, ends = np.concatenate([starts, middle]), np.concatenate([middle, ends])
        at_start = np.concatenate([at_start, found.distance])
        at_end = np.concatenate([found.distance, at_end])
        steps, interval = np.concatenate([steps, steps]), np.concatenate([interval, interval])
    return _per_move(np.concatenate(times), np.concatenate(distances),
                     np.concatenate(pairs), seconds, records, rows, check.margin)


class _Reach:
    """How far a shape of ``a`` or ``b`` can move for joint steps, from the joints' and the
    frames' origins at every sample."""

    def __init__(self, tree: FrameTree, joint_names: tuple[str, ...], frames_a: Iterable[str],
                 frames_b: Iterable[str], seconds: FloatArray) -> None:
        joint_frames = {joint.name: frame for frame in tree.frames
                        if (joint := tree.joint_of(frame)) is not None}
        self.seconds = seconds
        self.origins = {name: tree.pose(joint_frames[name], tree.root, times=seconds
                                        ).translation for name in joint_names}
        loader = ShapeLoader("collision")
        self.sides = []
        for frames in (frames_a, frames_b):
            side = []
            for frame in frames:
                above = set(_ancestors(tree, frame))
                moving = [column for column, name in enumerate(joint_names)
                          if joint_frames[name] in above]
                if not moving:
                    continue  # nothing the program moves carries this frame
                geometry = tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY)
                radius = max((float(np.linalg.norm(shape.rotation @ shape.centre
                                                   + shape.translation)) + shape.radius
                              for shape in loader.shapes(frame, geometry)), default=0.0)
                origin = tree.pose(frame, tree.root, times=seconds).translation
                arms = np.stack([np.linalg.norm(origin - self.origins[joint_names[column]],
                                                axis=1) + radius for column in moving], axis=1)
                prismatic = np.array([tree.joints[joint_names[column]].kind == "prismatic"
                                      for column in moving])
                arms[:, prismatic] = 1.0
                side.append((np.array(moving), np.maximum(arms[:-1], arms[1:]), prismatic))
            self.sides.append(side)

    def bound(self, steps: FloatArray, interval: NDArray[np.intp]) -> FloatArray:
        """How far a shape of ``a`` plus one of ``b`` can move for joint ``steps`` (K, n)
        within the sample intervals ``interval`` (K,) (their arms)."""
        total = np.zeros(steps.shape[0])
        for side in self.sides:
            worst = np.zeros(steps.shape[0])
            for moving, arms, prismatic in side:
                moved = steps[:, moving]
                turned = moved[:, ~prismatic].sum(axis=1)
                worst = np.maximum(worst, (moved * arms[interval]).sum(axis=1) * (1 + turned))
            total += worst
        return total


def _per_move(times: FloatArray, distances: FloatArray, pairs: NDArray[np.str_],
              seconds: FloatArray, records: Sequence[MoveRecord],
              rows: Sequence[tuple[int, int]], margin: float) -> tuple[CollisionRecord, ...]:
    found = []
    for record, (first, last) in zip(records, rows, strict=True):
        inside = (times >= seconds[first]) & (times <= seconds[last])
        close = inside & ((distances < margin) | (distances <= 0.0))
        if not close.any():
            continue
        worst = int(np.flatnonzero(close)[np.argmin(distances[close])])
        found.append(CollisionRecord(record.name, float(times[worst]), str(pairs[worst][0]),
                                     str(pairs[worst][1]), float(distances[worst])))
    return tuple(found)


def _ancestors(tree: FrameTree, frame: str) -> list[str]:
    chain: list[str] = []
    current: str | None = frame
    while current is not None:
        chain.append(current)
        current = tree.parent(current)
    return chain


def _side(value: Any) -> str | tuple[str, ...]:
    return value if isinstance(value, str) else tuple(str(name) for name in value)
