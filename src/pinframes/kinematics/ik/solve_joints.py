"""``FrameTree.solve_joints``: joint values that put a tool frame on a target, per sample
(inverse kinematics along a path).

The caller's arguments are checked here and made into one request: the path from the tool
to the frame the target is given in is prepared as for a pose query (:mod:`.._plan`: a
Pinocchio model rooted at their lowest common ancestor), the solved joints found on it
(:mod:`._solved_joints`), its times planned from every moving thing on it but the solved
joints, whose samples are what is being solved for, and the first sample's start taken
(:mod:`._starts`). The request goes down once, to the tracker picked here
(:mod:`._trackers`: the numeric solver, or an arm's closed form, its jumps bridged) on times
made dense enough (:mod:`._between_samples`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentTypeError, InvalidDataError, JointError, TargetNotReachedError
from ...values.joint import Joint
from ...values.pose import Pose
from ...values.timeline import TimedSource
from .._description import TreeDescription
from .._joint_argument import named_joints
from .._plan import PreparedPath, QueryPlan, plan_query, prepare_path
from ..closed_form.arm_shapes import ArmShape
from ..closed_form.configurations import BRANCH_NAMES, branch_flags, requested_branch
from ._batch_check import flat_errors
from ._between_samples import DEFAULT_PATH_TOLERANCE, densely_tracked
from ._bounded_step import LeastSquares
from ._closed_form_arm import arm_order, closed_form_arm
from ._flat import FLAT_TOLERANCE, FlatFrame, flat_objective
from ._newton_tracking import Tracked
from ._null_space import AwayFromLimits, NullSpaceObjective
from ._path_chunks import TARGET_SOURCE, PathToSolve, problem_of
from ._solved_joints import SolvedJoints, solved_joints
from ._starts import first_start
from ._tool_error import AXES, AxisMatch, PoseMatch, ToolMatch, WindowMatch
from ._trackers import NEWTON, ClosedForm, JumpsBridged
from ._windows_where_needed import nominal_where_reachable
from .joint_jumps import DEFAULT_JUMP_FACTOR, jumps_of, require_no_jumps
from .joint_solution import JointSolution
from .joint_speeds import require_within_speed

__all__ = ["DEFAULT_PATH_TOLERANCE", "FLAT_TOLERANCE", "SMALLEST_TOLERANCE",
           "evaluate_solve_joints"]

FloatArray = NDArray[np.float64]

SMALLEST_TOLERANCE = 1e-12
"""The smallest position (m) and orientation (rad) tolerance: errors of poses a few metres
from their origin are not resolved much below it in double precision."""


def evaluate_solve_joints(
    tree: TreeDescription, frame: str, target: str | Pose, *, relative_to: str | None,
    times: Any, time_ref: Any, joints: Any, free_axis: str | None, seed: Any,
    position_tolerance: float, orientation_tolerance: float, strict: bool,
    flat: str | None = None, up: Any = None, tilt: Any = None, add_joints: Any = None,
    configuration: Any = None,
    path_tolerance: Any = DEFAULT_PATH_TOLERANCE, jump_threshold: Any = DEFAULT_JUMP_FACTOR,
    flat_tolerance: Any = FLAT_TOLERANCE,
) -> JointSolution:
    """``tree.solve_joints(...)``; ``frame`` (and a target frame name) already checked."""
    branch = None if configuration is None else requested_branch(configuration, frame=frame)
    between = _path_tolerance(path_tolerance, frame)
    jump_factor = _tolerance(jump_threshold, "jump_threshold", frame)
    reference, target_pose = _reference(tree, frame, target, relative_to)
    error = _tool_match(free_axis, tilt, frame)
    if up is not None and flat is None:
        raise ArgumentTypeError("up= is the direction flat= turns its frame toward; give flat= "
                                "too", frame=frame, field="up")
    tolerances = (_tolerance(position_tolerance, "position_tolerance", frame),
                  _tolerance(orientation_tolerance, "orientation_tolerance", frame))
    names = None if joints is None else _to_solve(joints, tree.joints_by_name, frame, "joints")
    added = () if add_joints is None else _to_solve(add_joints, tree.joints_by_name, frame,
                                                    "add_joints")
    path, solved, plan = planned_solve(tree, frame, reference, target_pose, times, time_ref,
                                       names, added)
    assert path.model is not None  # planned_solve refuses a path that no joint moves
    start = first_start(solved, seed, plan, tree.joints_by_name, tree.joint_trajectories,
                        frame)
    solver = LeastSquares()
    objective: NullSpaceObjective = (
        AwayFromLimits(solved.limits) if flat is None
        else flat_objective(tree, path.model, solved, flat, up, frame, solver,
                            _tolerance(flat_tolerance, "flat_tolerance", frame)))
    request = PathToSolve(plan, solved, target_pose, error, *tolerances, objective, solver)
    arm = _closed_form(path, solved, frame, branch is not None)
    closed = arm is not None and flat is None and isinstance(error, PoseMatch)
    if branch is not None and not closed:
        raise ArgumentTypeError("configuration= keeps a whole pose on a branch of the closed "
                                "form; it does not combine with free_axis=, tilt= or flat=",
                                frame=frame, field="configuration")
    track = JumpsBridged(ClosedForm(arm, branch, jump_factor) if closed and arm is not None
                         else NEWTON, jump_factor)
    # given times are the samples; without, they are made dense enough for the tolerance
    tolerance = between if times is None else None
    tilts: FloatArray | None
    if isinstance(error, WindowMatch):  # the nominal orientation where it is reachable
        request, tracked, tilts, deviation = nominal_where_reachable(
            request, error, start, seed is None, strict, frame, tolerance, track)
    else:
        request, tracked, tilts, deviation = densely_tracked(
            request, start, seed is None, strict, frame, tolerance, track)
    plan = request.plan
    flat_error = None if not isinstance(objective, FlatFrame) else _flat_errors(
        request, objective, tracked, strict, frame)
    branches = None if arm is None else branch_flags(
        arm, tracked.positions[:, arm_order(arm, solved.names)])
    offsets = np.zeros(1, dtype=np.int64) if plan.offsets is None else plan.offsets
    solution = JointSolution(
        solved.names, tracked.positions, offsets.astype("timedelta64[ns]"),
        plan.reference_time, tracked.position_error, tracked.orientation_error,
        tracked.reached, solved.velocity_limits, solved.velocity_limit_joints, tilt=tilts,
        configurations=None if branches is None else np.array(BRANCH_NAMES)[branches],
        path_deviation=deviation.position, path_angle_deviation=deviation.orientation,
        jumps=jumps_of(tracked.positions, jump_factor), flat_error=flat_error)
    if strict:
        require_no_jumps(solution, jump_factor, frame)
        require_within_speed(solution, tree.joints_by_name, frame)
    return solution


def _closed_form(path: PreparedPath, solved: SolvedJoints, frame: str, needed: bool
                 ) -> ArmShape | None:
    """The solved joints' arm when they form one of a closed-form family, else None (or,
    when ``needed``, the error saying why not)."""
    try:
        return closed_form_arm(path, solved, frame)
    except JointError:
        if needed:
            raise
        return None


def _flat_errors(request: PathToSolve, flat: FlatFrame, tracked: Tracked, strict: bool,
                 frame: str) -> FloatArray:
    """Per sample, the flat frame's angle from up (radians); a reached sample beyond the
    tolerance where the solved joints could turn it up (:meth:`FlatFrame.could_turn_up`)
    is made not reached (``strict``: an error)."""
    plan = request.plan
    assert plan.offsets is not None  # a path that moves
    errors = flat_errors(plan.path, plan.sample_times, plan.shifts, request.joints.names,
                         tracked.positions, flat.carrier, flat.z_on_carrier, flat.up)
    beyond = np.flatnonzero(tracked.reached & (errors > flat.tolerance))
    if beyond.shape[0]:
        configurations = problem_of(request.at(beyond)).configurations
        for index, configuration in zip(beyond.tolist(), configurations, strict=True):
            if flat.could_turn_up(tracked.positions[index], configuration):
                tracked.reached[index] = False
                if strict:
                    raise TargetNotReachedError(
                        f"the flat frame could be flat at {plan.offsets[index] / 1e9:.9g} s "
                        f"(sample {index + 1}) but its z is {errors[index]:.3g} rad from up "
                        f"(flat_tolerance {flat.tolerance:.3g} rad)", frame=frame,
                        field="flat")
    return errors


def planned_solve(tree: TreeDescription, frame: str, reference: str, target_pose: Pose | None,
                  times: Any, time_ref: Any, names: list[str] | None,
                  added: Sequence[str] = ()) -> tuple[PreparedPath, SolvedJoints, QueryPlan]:
    """The path from ``frame`` to ``reference``, the joints solved on it (``names``, else
    the default set, then ``added``) and the plan of the solve: a time-dependent target's
    times beside those of what moves, the solved joints' own samples not among them."""
    target_times = None if target_pose is None else target_pose.times
    extra = () if target_pose is None or target_times is None else (
        TimedSource(TARGET_SOURCE, target_times.astype(np.int64), target_pose.reference_time),)
    path = prepare_path(tree, frame, reference)
    if path.model is None:
        raise JointError(f"no robot joint moves {frame!r} relative to {reference!r}",
                         frame=frame, field="joints")
    solved = solved_joints(path, tree.joints_by_name, tree.drives, names, added)
    plan = plan_query(tree, frame, reference, times, time_ref, "clamp", held=solved.names,
                      extra=extra)
    return path, solved, plan


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


def _path_tolerance(value: Any, frame: str) -> tuple[float, float] | None:
    """``path_tolerance`` as (metres, radians): a pair, or one length (the angle then the
    default's); None: the default times as they are."""
    if value is None:
        return None
    pair = (value, DEFAULT_PATH_TOLERANCE[1]) if isinstance(value, (int, float)) else value
    try:
        length, angle = pair
    except (TypeError, ValueError):
        raise ArgumentTypeError(f"expected metres or (metres, radians), got {value!r}",
                                frame=frame, field="path_tolerance") from None
    return (_tolerance(length, "path_tolerance", frame),
            _tolerance(angle, "path_tolerance", frame))


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


def _to_solve(requested: object, joints: Mapping[str, Joint], frame: str,
              field: str) -> list[str]:
    """``requested`` (the ``joints=`` or ``add_joints=`` argument) as :func:`named_joints`
    checks it, and not empty."""
    names = named_joints(requested, joints, frame, field)
    if not names:
        raise JointError("no joints to solve for", frame=frame, field=field)
    return names
