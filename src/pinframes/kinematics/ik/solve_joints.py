"""``FrameTree.solve_joints``: joint values that put a tool frame on a target, per sample
(inverse kinematics along a path).

The path from the tool to the frame the target is given in is prepared as for a pose query
(:mod:`._plan`: a Pinocchio model rooted at their lowest common ancestor) and its times
planned from every moving thing on it but the solved joints, whose samples are what is
being solved for. Per chunk of samples, everything that is not solved for is
sampled into Pinocchio configurations (:func:`._sampling.sample_configurations`), then
:mod:`._newton_tracking` solves sample after sample, each from the one before; without a
seed, the first stretch from the start :mod:`._starts` takes.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentTypeError, InvalidDataError, JointError, TargetNotReachedError
from ...values.pose import Pose
from ...values.rotations import quaternion_from_matrix
from ...values.se3 import Transform
from ...values.timeline import TimedSource
from .._description import TreeDescription
from .._model import CompiledModel
from .._plan import PreparedPath, plan_query, prepare_path
from .._sampling import KERNEL_CHUNK, sample_configurations
from ._batch_check import measure_solutions, tools_in_targets
from ._bounded_step import LeastSquares
from ._flat import FlatFrame, flat_objective
from ._newton_tracking import (
    Tracked,
    TrackingHistory,
    TrackingProblem,
    solve_again,
    track_targets,
)
from ._null_space import AwayFromLimits, NullSpaceObjective
from ._solved_joints import SolvedJoints, solved_joints
from ._starts import track_from_the_best_start
from ._tool_error import AXES, AxisMatch, PoseMatch, ToolMatch, WindowMatch, tilts_of
from .joint_solution import JointSolution
from .joint_speeds import require_within_speed, velocity_limits

__all__ = ["SMALLEST_TOLERANCE", "STILL", "evaluate_solve_joints"]

FloatArray = NDArray[np.float64]

SMALLEST_TOLERANCE = 1e-12
"""The smallest position (m) and orientation (rad) tolerance: errors of poses a few metres
from their origin are not resolved much below it in double precision."""

STILL = 1e-12
"""Metres, radians or quaternion components by which a sample may differ from the one
before and still stand still (interpolation between equal keyframes rounds)."""

_TARGET_SOURCE = "<target pose>"
"""Name of a time-dependent target pose among the timeline's sources."""


def evaluate_solve_joints(
    tree: TreeDescription, frame: str, target: str | Pose, *, relative_to: str | None,
    times: Any, time_ref: Any, joints: Any, free_axis: str | None, seed: Any,
    position_tolerance: float, orientation_tolerance: float, strict: bool,
    flat: str | None = None, up: Any = None, tilt: Any = None,
) -> JointSolution:
    """``tree.solve_joints(...)``; ``frame`` (and a target frame name) already checked."""
    reference, target_pose = _reference(tree, frame, target, relative_to)
    error = _tool_match(free_axis, tilt, frame)
    if up is not None and flat is None:
        raise ArgumentTypeError("up= is the direction flat= turns its frame toward; give flat= "
                                "too", frame=frame, field="up")
    tolerances = (_tolerance(position_tolerance, "position_tolerance", frame),
                  _tolerance(orientation_tolerance, "orientation_tolerance", frame))
    # a time-dependent target's times are the solve's, beside those of what moves
    target_times = None if target_pose is None else target_pose.times
    extra = () if target_pose is None or target_times is None else (
        TimedSource(_TARGET_SOURCE, target_times.astype(np.int64), target_pose.reference_time),)
    path = prepare_path(tree, frame, reference)
    if path.model is None:
        raise JointError(f"no robot joint moves {frame!r} relative to {reference!r}",
                         frame=frame, field="joints")
    model = path.model
    solved = _solved_joints(tree, path, joints)
    held = {name: 0.0 for name in solved.names}
    # the solved joints' samples are what is solved for: not among the solve's times
    plan = plan_query(tree, frame, reference, times, time_ref, "clamp", held=held, extra=extra)
    moments = plan.sample_times  # nothing moves: one sample
    offsets = np.zeros(1, dtype=np.int64) if plan.offsets is None else plan.offsets
    shifts = plan.shifts
    ratios = _step_ratios(moments)
    reference_id = _reference_id(model, reference)
    start = _seed(tree, solved, seed, int(moments[0]), shifts, frame)
    history = TrackingHistory(start)
    solver = LeastSquares()
    objective: NullSpaceObjective = (
        AwayFromLimits(solved.limits) if flat is None
        else flat_objective(tree, model, solved, flat, up, frame, solver))
    parts: list[Tracked] = []
    tilts: list[FloatArray] = []  # per chunk, with process windows
    for begin in range(0, moments.shape[0], KERNEL_CHUNK):
        part = slice(begin, begin + KERNEL_CHUNK)
        targets = _targets(target_pose, moments[part], shifts.get(_TARGET_SOURCE, 0))
        configurations = sample_configurations(model, path.samplers, moments[part], shifts,
                                               held)
        target_rows = None if targets is None else _xyz_quaternions(targets)
        problem = TrackingProblem(
            model.model, model.data, model.frame_ids[frame], reference_id, configurations,
            target_rows, solved, error, tolerances[0], tolerances[1], ratios[part], solver,
            objective, _standing_still(configurations, target_rows))
        if begin == 0 and seed is None:
            if isinstance(objective, FlatFrame):
                start = objective.turned_up(start, configurations[0])
            tracked, history = track_from_the_best_start(problem, start, strict)
        else:
            tracked = track_targets(problem, history, stop_when_unreached=strict)
        _measure_the_rest(tree, path, moments[part], shifts, targets, problem, tracked)
        if isinstance(error, WindowMatch):
            rotations, _ = tools_in_targets(tree, path, moments[part], shifts, solved.names,
                                            tracked.positions, targets)
            tilts.append(tilts_of(rotations))
        parts.append(tracked)
        if strict and not tracked.reached.all():
            _raise_unreached(parts, offsets, plan.reference_time, tolerances, frame)
    solution = JointSolution(
        solved.names, np.concatenate([part.positions for part in parts]),
        offsets.astype("timedelta64[ns]"), plan.reference_time,
        np.concatenate([part.position_error for part in parts]),
        np.concatenate([part.orientation_error for part in parts]),
        np.concatenate([part.reached for part in parts]),
        *velocity_limits(solved.names, tree.joints_by_name),
        tilt=np.concatenate(tilts) if tilts else None)
    if strict:
        require_within_speed(solution, tree.joints_by_name, frame)
    return solution


def _solved_joints(tree: TreeDescription, path: PreparedPath, joints: Any) -> SolvedJoints:
    """:func:`solved_joints` of a moving ``path``, prepared once per path (so per tree
    version) and request."""
    model = path.model
    assert model is not None
    if joints is None or (isinstance(joints, (list, tuple))
                          and all(isinstance(name, str) for name in joints)):
        key = "solve_joints: " + ("every joint" if joints is None
                                  else "named: " + "\0".join(joints))
        cached = path.plans.get(key)
        if cached is None:
            cached = path.plans[key] = solved_joints(model, tree.joints_by_name, joints,
                                                     path.frame, path.relative_to)
        assert isinstance(cached, SolvedJoints)
        return cached
    return solved_joints(model, tree.joints_by_name, joints, path.frame, path.relative_to)


def _reference(tree: TreeDescription, frame: str, target: str | Pose, relative_to: str | None
               ) -> tuple[str, Pose | None]:
    """The frame the target is given in, and the target pose in it (None: that frame)."""
    if isinstance(target, str):
        if relative_to is not None:
            raise ArgumentTypeError("relative_to is for a Pose target; a target frame is its "
                                    "own reference", frame=frame, field="relative_to")
        return target, None
    if isinstance(target, Pose):
        return (tree.root if relative_to is None else relative_to), target
    raise ArgumentTypeError(f"expected a frame name or a Pose, got {type(target).__name__}",
                            frame=frame, field="target")


def _tool_match(free_axis: Any, tilt: Any, frame: str) -> ToolMatch:
    if free_axis is not None and free_axis not in AXES:
        raise ArgumentTypeError(f"expected one of {', '.join(AXES)} or None, got {free_axis!r}",
                                frame=frame, field="free_axis")
    if tilt is not None:
        if free_axis not in (None, "z"):
            raise ArgumentTypeError(f"tilt= tilts the tool's z, which free_axis={free_axis!r} "
                                    "leaves free; use free_axis='z' or None", frame=frame,
                                    field="free_axis")
        about_x, about_y = _windows(tilt, frame)
        return WindowMatch(about_x, about_y, free_spin=free_axis == "z")
    return PoseMatch() if free_axis is None else AxisMatch(free_axis)


def _windows(tilt: Any, frame: str) -> tuple[float, float]:
    """``tilt`` as two angles within ``[0, pi/2)`` radians."""
    try:
        about_x, about_y = (float(angle) for angle in tilt)
    except (TypeError, ValueError):
        raise ArgumentTypeError(f"expected two angles (about_x, about_y) in radians, got "
                                f"{tilt!r}", frame=frame, field="tilt") from None
    for angle in (about_x, about_y):
        if not 0.0 <= angle < math.pi / 2:
            raise InvalidDataError(f"expected angles from 0 to below pi/2 radians, got {tilt!r}",
                                   frame=frame, field="tilt")
    return about_x, about_y


def _tolerance(value: Any, field: str, frame: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, (str, bytes, bool)) or not (0.0 < number < math.inf):
        raise InvalidDataError(f"expected a positive number, got {value!r}", frame=frame,
                               field=field)
    if number < SMALLEST_TOLERANCE:
        raise InvalidDataError(f"{number:g} is below what double precision resolves on a "
                               f"robot (at least {SMALLEST_TOLERANCE:g})", frame=frame,
                               field=field)
    return number


def _seed(tree: TreeDescription, solved: SolvedJoints, seed: Any, first: int,
          shifts: dict[str, int], frame: str) -> FloatArray:
    """Joint values of the first sample's start: ``seed`` (a mapping by name, possibly
    partial, or one value per joint), else each joint's trajectory at the first time, else
    its rest value; defaults are put within the limits, a given seed must be."""
    names = solved.names
    defaults = np.empty(len(names))
    for column, name in enumerate(names):
        trajectory = tree.joint_trajectories.get(name)
        defaults[column] = (tree.joints_by_name[name].rest_value if trajectory is None else
                            trajectory.value_at(first - shifts.get(name, 0)))
    start = solved.limits.clipped(defaults)
    if seed is None:
        return start
    given: dict[int, Any]
    if isinstance(seed, Mapping):
        unknown = [name for name in seed if name not in names]
        if unknown:
            raise JointError(f"seed names {unknown[0]!r}, which is not solved for (joints: "
                             f"{', '.join(names)})", frame=frame, field="seed")
        given = {names.index(name): value for name, value in seed.items()}
    else:
        try:
            values = np.asarray(seed, dtype=float)
        except (TypeError, ValueError):
            raise ArgumentTypeError(f"expected joint values by name or one per joint, got "
                                    f"{seed!r}", frame=frame, field="seed") from None
        if values.shape != (len(names),):
            raise InvalidDataError(f"expected {len(names)} values (joints {', '.join(names)}), "
                                   f"got shape {values.shape}", frame=frame, field="seed")
        given = dict(enumerate(values.tolist()))
    for column, value in given.items():
        name = names[column]
        try:
            number = float(value)
        except (TypeError, ValueError):
            number = math.nan
        if not math.isfinite(number):
            raise InvalidDataError(f"expected a finite number for joint {name!r}, got {value!r}",
                                   frame=frame, field="seed")
        low, high = solved.limits.lower[column], solved.limits.upper[column]
        if not low <= number <= high:
            raise JointError(f"seed {number:.6g} of joint {name!r} is outside its limits "
                             f"[{low:.6g}, {high:.6g}]", frame=frame, field="seed")
        start[column] = number
    return start


def _step_ratios(moments: NDArray[np.int64]) -> FloatArray:
    """Per sample, its time step over the previous one (1 where there is none)."""
    ratios = np.ones(moments.shape[0])
    if moments.shape[0] > 2:
        steps = np.diff(moments).astype(float)
        before = steps[:-1]
        # a step after a repeated time (none before it) is not predicted: inf
        ratios[2:] = np.divide(steps[1:], before, out=np.full(before.shape, np.inf),
                               where=before > 0)
    return ratios


def _standing_still(configurations: FloatArray, targets: FloatArray | None
                    ) -> NDArray[np.bool_]:
    """Per sample, whether its configuration (everything not solved for) and its target
    rows are those of the sample before, to :data:`STILL` (False for the first)."""
    still = np.zeros(configurations.shape[0], dtype=bool)
    still[1:] = np.all(np.abs(configurations[1:] - configurations[:-1]) <= STILL, axis=1)
    if targets is not None:
        still[1:] &= np.all(np.abs(targets[1:] - targets[:-1]) <= STILL, axis=1)
    return still


def _reference_id(model: CompiledModel, reference: str) -> int | None:
    """The Pinocchio frame id of ``reference``, or None when it is the model's root."""
    frame = model.model.frames[model.frame_ids[reference]]
    return None if frame.parentJoint == 0 and frame.placement.isIdentity() else (
        model.frame_ids[reference])


def _targets(target: Pose | None, moments: NDArray[np.int64], shift: int
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


def _xyz_quaternions(targets: Transform) -> FloatArray:
    """``x y z qx qy qz qw`` rows (Pinocchio's ``XYZQUAT``) of ``(N, 3, 3)`` rotations and
    ``(N, 3)`` translations."""
    rotations, translations = targets
    return np.concatenate([translations, quaternion_from_matrix(rotations)], axis=1)


def _measure_the_rest(tree: TreeDescription, path: PreparedPath, moments: NDArray[np.int64],
                      shifts: dict[str, int], targets: Transform | None,
                      problem: TrackingProblem, tracked: Tracked) -> None:
    """Measure the samples the loop took as solved unmeasured, all at once, and solve again
    (measuring) any that missed its tolerances; ``tracked`` is updated in place."""
    unmeasured = np.flatnonzero(~tracked.measured)
    if not unmeasured.shape[0]:
        return
    subset = None if targets is None else (targets[0][unmeasured], targets[1][unmeasured])
    position, orientation = measure_solutions(
        tree, path, moments[unmeasured], shifts, problem.joints.names,
        tracked.positions[unmeasured], subset, problem.error)
    tracked.position_error[unmeasured] = position
    tracked.orientation_error[unmeasured] = orientation
    missed = (position > problem.position_tolerance) | (
        orientation > problem.orientation_tolerance)
    for index in unmeasured[missed]:
        (tracked.positions[index], tracked.position_error[index],
         tracked.orientation_error[index], tracked.reached[index]) = solve_again(
            problem, int(index), tracked.positions[index])


def _raise_unreached(parts: list[Tracked], offsets: NDArray[np.int64],
                     reference: np.datetime64 | None, tolerances: tuple[float, float],
                     frame: str) -> None:
    """The :class:`TargetNotReachedError` of ``strict=True`` at the last sample solved."""
    index = sum(part.reached.shape[0] for part in parts) - 1
    last = parts[-1]
    seconds = offsets[index] / 1e9
    when = f"{seconds:.9g} s" + ("" if reference is None else f" after {reference}")
    raise TargetNotReachedError(
        f"target not reached at {when} (sample {index + 1} of {offsets.shape[0]}): position "
        f"error {last.position_error[-1]:.3g} m, orientation error "
        f"{last.orientation_error[-1]:.3g} rad (tolerances {tolerances[0]:g} m, "
        f"{tolerances[1]:g} rad)", frame=frame, field="target")
