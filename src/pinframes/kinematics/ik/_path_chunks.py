"""A planned solve, chunk by chunk: the samples of ``solve_joints`` in chunks of
:data:`~pinframes.kinematics._sampling.KERNEL_CHUNK`.

Per chunk, everything that is not solved for is sampled into Pinocchio configurations (the
solved joints held; :func:`~pinframes.kinematics._sampling.sample_configurations`) and the
target into ``x y z qx qy qz qw`` rows; :mod:`._newton_tracking` solves sample after sample,
each from the one before (the first chunk without a seed from the start :mod:`._starts`
takes); :mod:`._batch_check` measures the samples the loop took as solved, all at once.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import TargetNotReachedError
from ...values.pose import Pose
from ...values.rotations import quaternion_from_matrix
from ...values.se3 import Transform, samples_last
from .._plan import QueryPlan
from .._sampling import KERNEL_CHUNK, sample_configurations
from ._batch_check import check_unmeasured, tilts_at, tools_in_targets
from ._bounded_step import LeastSquares
from ._newton_tracking import Tracked, TrackingHistory, TrackingProblem, track_targets
from ._null_space import NullSpaceObjective
from ._solved_joints import SolvedJoints
from ._starts import track_from_the_best_start
from ._tool_error import ToolMatch, WindowMatch

__all__ = ["STILL", "TARGET_SOURCE", "PathToSolve", "problem_of", "raise_unreached", "targets_at",
           "targets_last", "track_in_chunks"]

FloatArray = NDArray[np.float64]

STILL = 1e-12
"""Metres, radians or quaternion components by which a sample may differ from the one
before and still stand still (interpolation between equal keyframes rounds)."""

TARGET_SOURCE = "<target pose>"
"""Name of a time-dependent target pose among the timeline's sources."""


@dataclass(frozen=True)
class PathToSolve:
    """What a solve asks on its plan.

    Attributes
    ----------
    plan : QueryPlan
        The path from the tool to the reference frame (moving), and the solve's times.
    joints : SolvedJoints
        The unknowns, held out of the sampled configurations.
    target : Pose or None
        The target in the reference frame (None: the reference frame itself).
    error : ToolMatch
        What must match.
    position_tolerance, orientation_tolerance : float
        Metres and radians.
    objective : NullSpaceObjective
        The secondary objective.
    solver : LeastSquares
        The linear algebra of the steps (shared with the objective).
    """

    plan: QueryPlan
    joints: SolvedJoints
    target: Pose | None
    error: ToolMatch
    position_tolerance: float
    orientation_tolerance: float
    objective: NullSpaceObjective
    solver: LeastSquares

    @cached_property
    def reference_id(self) -> int | None:
        """The Pinocchio frame id of the frame the target is given in, or None when that is
        the compiled model's root (its placements are already in it)."""
        path = self.plan.path
        assert path.model is not None
        frame_ids = path.model.frame_ids
        frame = path.model.model.frames[frame_ids[path.relative_to]]
        return None if frame.parentJoint == 0 and frame.placement.isIdentity() else (
            frame_ids[path.relative_to])

    def at(self, rows: NDArray[np.intp] | NDArray[np.bool_] | slice) -> PathToSolve:
        """This request on some samples of its plan (indices in any order, a mask or a
        slice)."""
        return replace(self, plan=self.plan.at(rows))

    def tools_in_targets(self, times: NDArray[np.int64], positions: FloatArray) -> Transform:
        """The tool in its targets at ``times`` (timeline basis, ns) with the solved joints
        at ``positions`` (N, n): ``(N, 3, 3)`` rotations and ``(N, 3)`` translations
        (metres)."""
        plan = self.plan
        targets = targets_last(self.target, times, plan.shifts.get(TARGET_SOURCE, 0))
        return tools_in_targets(plan.path, times, plan.shifts, self.joints.names, positions,
                                targets)

    def require_reached(self, tracked: Tracked, frame: str) -> None:
        """The :class:`TargetNotReachedError` of ``strict=True`` (naming ``frame``) at the
        first sample of this request's plan that ``tracked`` did not reach, if any."""
        if not tracked.reached.all():
            index = int(np.argmin(tracked.reached))
            raise_unreached(self, index, float(tracked.position_error[index]),
                            float(tracked.orientation_error[index]), frame)


def track_in_chunks(request: PathToSolve, start: FloatArray, search_starts: bool,
                    strict: bool, frame: str) -> tuple[Tracked, FloatArray | None]:
    """The solutions of every sample of ``request``'s plan, from ``start`` (with
    ``search_starts``: the default of the first sample's several starts), and per sample
    the tool's tilts about its target's x and y (radians, (T, 2)) with a
    :class:`WindowMatch` (else None).

    The starts are compared on the first chunk in which the path moves: whole chunks that
    stand on the first sample (its target and everything not solved for, to :data:`STILL`)
    tell no branch from another, so the search takes the first sample and then that chunk,
    and the standing samples take the first sample's solution.

    With ``strict``, raises :class:`~pinframes.errors.TargetNotReachedError` (naming
    ``frame``) at the first sample not reached.
    """
    moments = request.plan.sample_times
    count = moments.shape[0]
    ratios = _step_ratios(moments)
    parts: list[Tracked] = []
    tilts: list[FloatArray] = []
    history: TrackingHistory | None = None
    first: _Chunk | None = None  # the first chunk, while it and those after it stand
    standing = 0  # samples standing on the first sample, before the search
    for begin in range(0, count, KERNEL_CHUNK):
        chunk = _Chunk.sampled(request, slice(begin, begin + KERNEL_CHUNK), ratios)
        if history is None and search_starts:
            first = first or chunk
            if begin + KERNEL_CHUNK < count and first.stands_on(chunk):
                standing += chunk.moments.shape[0]
                continue
            if standing:
                chunk = first.leading(chunk)
            problem = chunk.problem(request)
            tracked, history = track_from_the_best_start(problem, start, strict)
        else:
            problem = chunk.problem(request)
            if history is None:
                history = TrackingHistory(start)
            tracked = track_targets(problem, history, stop_when_unreached=strict)
        check_unmeasured(request.plan.path, chunk.moments, request.plan.shifts, chunk.targets,
                         problem, tracked)
        chunk_tilts = None if not isinstance(request.error, WindowMatch) else tilts_at(
            request.plan.path, chunk.moments, request.plan.shifts, request.joints.names,
            tracked.positions, chunk.targets)
        if standing:  # the lead stands for every standing sample
            lead = 1 if strict and not tracked.reached[0] else standing
            rows = np.concatenate([np.zeros(lead, dtype=np.intp),
                                   np.arange(1, tracked.reached.shape[0])])
            tracked = tracked.taken(rows)
            chunk_tilts = None if chunk_tilts is None else chunk_tilts[rows]
            standing = 0
        if chunk_tilts is not None:
            tilts.append(chunk_tilts)
        parts.append(tracked)
        if strict and not tracked.reached.all():
            _raise_unreached(parts, request, frame)
    whole = Tracked(*(np.concatenate([getattr(part, name) for part in parts])
                      for name in _TRACKED))
    return whole, np.concatenate(tilts) if tilts else None


_TRACKED = ("positions", "position_error", "orientation_error", "reached", "measured")
"""The per-sample fields of :class:`Tracked`, in its order."""


@dataclass(frozen=True)
class _Chunk:
    """The samples of one chunk: their times (timeline basis, ns), step ratios, targets in
    the reference frame (``(N, 3, 3)`` rotations, ``(N, 3)`` translations; None: the frame
    itself) and their rows ``x y z qx qy qz qw``, and Pinocchio's configurations with
    everything not solved for."""

    moments: NDArray[np.int64]
    ratios: FloatArray
    targets: Transform | None
    target_rows: FloatArray | None
    configurations: FloatArray

    @classmethod
    def sampled(cls, request: PathToSolve, part: slice, ratios: FloatArray) -> _Chunk:
        """The samples ``part`` of ``request``'s plan (``ratios``: of the whole plan)."""
        plan = request.plan
        model = plan.path.model
        assert model is not None
        moments = plan.sample_times[part]
        targets = targets_at(request.target, moments, plan.shifts.get(TARGET_SOURCE, 0))
        target_rows = None if targets is None else np.concatenate(
            [targets[1], quaternion_from_matrix(targets[0])], axis=1)
        configurations = sample_configurations(model, plan.path.samplers, moments, plan.shifts,
                                               dict.fromkeys(request.joints.names, 0.0))
        return cls(moments, ratios[part], targets, target_rows, configurations)

    def stands_on(self, other: _Chunk) -> bool:
        """Whether every sample of ``other`` is this chunk's first, to :data:`STILL`."""
        still = bool(np.all(np.abs(other.configurations - self.configurations[0]) <= STILL))
        if self.target_rows is not None and other.target_rows is not None:
            still &= bool(np.all(np.abs(other.target_rows - self.target_rows[0]) <= STILL))
        return still

    def leading(self, other: _Chunk) -> _Chunk:
        """``other`` led by this chunk's first sample, which it stands on up to ``other``
        (so ``other``'s step ratios hold as they are)."""
        def led(first: NDArray[Any], rest: NDArray[Any]) -> NDArray[Any]:
            return np.concatenate([first[:1], rest])
        targets = None if self.targets is None or other.targets is None else (
            led(self.targets[0], other.targets[0]), led(self.targets[1], other.targets[1]))
        target_rows = None if self.target_rows is None or other.target_rows is None else led(
            self.target_rows, other.target_rows)
        return _Chunk(led(self.moments, other.moments), led(np.ones(1), other.ratios), targets,
                      target_rows, led(self.configurations, other.configurations))

    def problem(self, request: PathToSolve) -> TrackingProblem:
        """The :class:`TrackingProblem` of these samples."""
        path = request.plan.path
        model = path.model
        assert model is not None
        return TrackingProblem(
            model.model, model.data, model.frame_ids[path.frame], request.reference_id,
            self.configurations, self.target_rows, request.joints, request.error,
            request.position_tolerance, request.orientation_tolerance, self.ratios,
            request.solver, request.objective,
            _standing_still(self.configurations, self.target_rows))


def problem_of(request: PathToSolve) -> TrackingProblem:
    """The :class:`TrackingProblem` of every sample of ``request``'s plan at once (a few:
    one chunk)."""
    moments = request.plan.sample_times
    return _Chunk.sampled(request, slice(0, moments.shape[0]), _step_ratios(moments)).problem(
        request)


def _step_ratios(moments: NDArray[np.int64]) -> FloatArray:
    """Per sample, its time step over the previous one (1 where there is none)."""
    ratios = np.ones(moments.shape[0])
    if moments.shape[0] > 2:
        steps = np.abs(np.diff(moments)).astype(float)  # (times in reverse: a path back)
        before = steps[:-1]
        # a step after a repeated time (none before it) is not predicted: inf
        ratios[2:] = np.divide(steps[1:], before, out=np.full(before.shape, np.inf),
                               where=before > 0)
    return ratios


def targets_at(target: Pose | None, moments: NDArray[np.int64], shift: int
             ) -> Transform | None:
    """The target in the reference frame at each of ``moments``: ``(N, 3, 3)`` rotations
    and ``(N, 3)`` translations (None: the frame itself)."""
    if target is None:
        return None
    if target.is_time_dependent:
        return target.keyframes.sample(moments - shift)
    count = moments.shape[0]
    return (np.broadcast_to(target.rotation, (count, 3, 3)),
            np.broadcast_to(target.translation, (count, 3)))


def targets_last(target: Pose | None, moments: NDArray[np.int64], shift: int
                  ) -> Transform | None:
    """:func:`targets_at` with the samples last, ``(3, 3, N)`` and ``(3, N)``: a moving
    target as interpolated, uncopied."""
    if target is not None and target.is_time_dependent:
        return target.keyframes.transform_at(moments - shift)
    targets = targets_at(target, moments, shift)
    return None if targets is None else samples_last(targets)


def _standing_still(configurations: FloatArray, targets: FloatArray | None
                    ) -> NDArray[np.bool_]:
    """Per sample, whether its configuration (everything not solved for) and its target
    rows are those of the sample before, to :data:`STILL` (False for the first)."""
    still = np.zeros(configurations.shape[0], dtype=bool)
    still[1:] = np.all(np.abs(configurations[1:] - configurations[:-1]) <= STILL, axis=1)
    if targets is not None:
        still[1:] &= np.all(np.abs(targets[1:] - targets[:-1]) <= STILL, axis=1)
    return still


def _raise_unreached(parts: list[Tracked], request: PathToSolve, frame: str) -> None:
    """The :class:`TargetNotReachedError` of ``strict=True`` at the last sample solved."""
    last = parts[-1]
    raise_unreached(request, sum(part.reached.shape[0] for part in parts) - 1,
                    float(last.position_error[-1]), float(last.orientation_error[-1]), frame)


def raise_unreached(request: PathToSolve, index: int, position_error: float,
                    orientation_error: float, frame: str) -> None:
    """The :class:`TargetNotReachedError` of ``strict=True`` at sample ``index`` of
    ``request``'s plan, with its errors (m, rad)."""
    plan = request.plan
    offsets = np.zeros(1, dtype=np.int64) if plan.offsets is None else plan.offsets
    when = f"{offsets[index] / 1e9:.9g} s" + (
        "" if plan.reference_time is None else f" after {plan.reference_time}")
    raise TargetNotReachedError(
        f"target not reached at {when} (sample {index + 1} of {offsets.shape[0]}): position "
        f"error {position_error:.3g} m, orientation error {orientation_error:.3g} rad "
        f"(tolerances {request.position_tolerance:g} m, {request.orientation_tolerance:g} "
        "rad)", frame=frame, field="target")
