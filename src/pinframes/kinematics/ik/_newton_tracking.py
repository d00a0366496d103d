"""The solver loop of ``FrameTree.solve_joints``: damped Newton on Pinocchio, sample by sample.

Each sample starts from the previous solution carried on by the step between the last two
(scaled by the ratio of the time steps; on the quadratic through the last three where the
steps change smoothly), when both reached their targets and the time step is at most
:data:`LONGEST_PREDICTION` times the one before; else from the previous solution; the first
sample starts from the seed (:class:`TrackingHistory`). The carried step keeps only its
part that moves the tool (all of the step when the secondary objective
``carries_self_motion``, as a frame kept flat does), and every Newton step is the smallest:
with more joints than rows (a 7-axis arm, a free tool axis, a positioner solved with the
robot) the solution is the smallest joint motion from the previous sample, with no
self-motion carried on. There the first Newton step from a prediction is the smallest motion
from the previous solution that the rows at the prediction take onto the target: it drops
the part of the carried step that the tool does not feel there, and the motion it leaves
lies in their row space, so that the next sample carries it on as it is. A motion taken any
other way (served to the secondary objective, in a second iteration, bridged) is projected
on the rows of its latest linearisation before it is carried on (damped by
:data:`._bounded_step.NEAR_SINGULAR_DAMPING` after a damped step; with as many joints as
rows all of it is kept). So it follows one branch (no elbow or wrist flips), usually with
one Newton step per sample. A sample whose target and everything else stand still starts
from the last solution, already on it: a static target gives a static solution. The
prediction comes with a lower bound of how far it lies inside the joint limits, carried from
sample to sample: the limits are checked joint by joint only when that bound runs out.

A start whose tool lies far from its target (more than :data:`BRIDGE_LENGTH` or
:data:`BRIDGE_ANGLE`: after a long gap between samples, from a seed, on the way back after
an unreachable stretch) is bridged: Newton solves for intermediate targets along the
straight screw motion from where the tool is to the target (metres and radians in
proportion), each from the one before, then for the target. The branch the motion is on is
kept, where one large step could cross to another.

An iteration sets the configuration, runs Pinocchio's ``forwardKinematics``, and measures the
tool in the target (:mod:`._tool_error`); when both errors are within their tolerances the
sample is reached. Otherwise ``computeFrameJacobian`` (``LOCAL``) gives the rows and
:func:`._bounded_step.bounded_step` the step within the limits, at most
:data:`LONGEST_STEP` per joint. A step that does not lower the error is taken back and tried
again with more damping (Levenberg-Marquardt), less after one that does: near a singular
configuration the damped step still lowers the error, and the damping falls back to zero
once it is past. A full Newton step (undamped, not shortened, within the limits) taken from
errors within :func:`quadratic_region` lands within the tolerances: the sample is taken as
solved there without measuring it again, and :mod:`._batch_check` measures such samples
afterwards, many at once, and solves again the rare one that missed (:func:`solve_again`). A
sample that is not reached after :data:`MAX_ITERATIONS`, or whose damping grows past
:data:`MAX_DAMPING`, keeps the best configuration found (the closest within the limits); the
next sample starts from the last solution that reached its target, then from that closest
configuration: the solver finds its way back, onto the branch it left, when the target comes
back into reach. With more joints than rows, a sample missed with a joint on its limit is
first solved again along the last solution's self-motion (:mod:`._self_motion_escape`).

A reached sample is then offered to the secondary objective (:mod:`._null_space`: keeping
the joints out of the bands along their limits), exactly in the null space of the task and
only where the tool gets back within its tolerances.

Measured against a per-sample loop of pink with a QP solver (benchmarks/bench_ik.py): the
QP pink solves per iteration costs more than this whole step; the limits need a QP only on
the rare steps that cross them, which the active set of :mod:`._bounded_step` handles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ._bounded_step import AMPLIFICATION, LeastSquares, bounded_step
from ._null_space import NullSpaceObjective, null_space_motion
from ._self_motion_escape import escape_along_self_motion
from ._solved_joints import SolvedJoints
from ._tool_error import PoseMatch, ToolMatch
from ._tracking_history import LONGEST_PREDICTION, StepBack, TrackingHistory

__all__ = ["BRIDGE_ANGLE", "BRIDGE_LENGTH", "LONGEST_PREDICTION", "LONGEST_STEP",
           "MAX_DAMPING", "MAX_ITERATIONS", "Tracked", "TrackingHistory", "TrackingProblem",
           "quadratic_region", "solve_again", "track_targets"]

FloatArray = NDArray[np.float64]

Solution = tuple[FloatArray, float, float, bool]
"""A sample's solution (n,), its position and orientation errors (m, rad; NaN when not
measured) and whether it reached its target."""

Solved = tuple[FloatArray, float, float, bool, float]
"""A :data:`Solution` and a lower bound of how far it lies inside the limits
(:meth:`JointLimits.margin`; 0: not known)."""

Carried = tuple[FloatArray, FloatArray, float, float]
"""A prediction's making: the last solution (n,), the step it is carried on by, reversed
(n,: the prediction is the last solution less it), a lower bound of the last solution's
margin inside the limits and the sum of the step's joint changes (radians or metres)."""

MAX_ITERATIONS = 100
"""Newton iterations at most per sample (a tracked sample takes one or two)."""

LONGEST_STEP = 0.5
"""Largest change of one joint in one iteration, radians or metres: far from the target, a
Newton step is only a direction."""

BRIDGE_LENGTH = 0.05
"""Metres of the tool's travel per intermediate target of a bridge."""

BRIDGE_ANGLE = 0.2
"""Radians of the tool's turn per intermediate target of a bridge."""

BRIDGE_TOLERANCE = 1e-4
"""Metres and radians within which an intermediate target counts as reached."""

BRIDGE_ITERATIONS = 20
"""Newton iterations at most per intermediate target; one not reached ends the bridge."""

MAX_BRIDGE_PARTS = 1000
"""Intermediate targets at most (a target kilometres away, out of reach anyway)."""

FIRST_DAMPING = 1e-6
"""Damping of the first retried step (error units squared, after the tolerances scale the
errors to 1)."""

MAX_DAMPING = 1e8
"""Damping past which a sample stops: the error no longer falls (a target out of reach)."""

CURVATURE = 100.0
"""Bound on how fast the tool's error departs from its linearisation, per metre or radian:
a full Newton step from an error ``e`` leaves about ``CURVATURE * e**2``."""


_LOCAL = pin.ReferenceFrame.LOCAL
"""Pinocchio's frame of a Jacobian in the tool's own axes."""

_WHOLE_POSE = PoseMatch()
"""What intermediate targets of a bridge match."""


def quadratic_region(tolerance: float) -> float:
    """The error (m or rad) below which a full Newton step leaves less than ``tolerance``."""
    return math.sqrt(tolerance / CURVATURE)


@dataclass(frozen=True)
class TrackingProblem:
    """One stretch of samples to solve.

    Attributes
    ----------
    model, data : pinocchio.Model, pinocchio.Data
        The compiled path, rooted at the lowest common ancestor of the two frames.
    frame_id : int
        Pinocchio frame id of the tool.
    reference_id : int or None
        Pinocchio frame id of the frame the target is given in; None when that is the
        model's root (its placements are already in it).
    configurations : ndarray, shape (N, nq)
        Per sample, the model's configuration with everything that is not solved for; the
        solver writes the solved joints into it (no copy per sample), but where they are the
        whole configuration (Pinocchio then takes the solution itself).
    targets : ndarray, shape (N, 7), or None
        Per sample, the target in the reference frame as ``x y z qx qy qz qw`` (metres, unit
        quaternion); None: the reference frame itself.
    joints : SolvedJoints
        The unknowns and their limits.
    error : PoseMatch or AxisMatch
        What must match.
    position_tolerance, orientation_tolerance : float
        Metres and radians.
    step_ratios : ndarray, shape (N,)
        Per sample, its time step over the previous one (for the prediction).
    solver : LeastSquares
        The linear algebra of the steps (kept from one stretch to the next).
    objective : NullSpaceObjective or None
        The secondary objective, served in the task's null space.
    still : ndarray of bool, shape (N,), or None
        Per sample, whether its target and everything not solved for are those of the
        sample before (it starts from the last solution, not a prediction); None: none is.
    """

    model: pin.Model
    data: pin.Data
    frame_id: int
    reference_id: int | None
    configurations: FloatArray
    targets: FloatArray | None
    joints: SolvedJoints
    error: ToolMatch
    position_tolerance: float
    orientation_tolerance: float
    step_ratios: FloatArray
    solver: LeastSquares
    objective: NullSpaceObjective | None = None
    still: NDArray[np.bool_] | None = None

    @cached_property
    def position_region(self) -> float:
        """:func:`quadratic_region` of the position tolerance (m)."""
        return quadratic_region(self.position_tolerance)

    @cached_property
    def orientation_region(self) -> float:
        """:func:`quadratic_region` of the orientation tolerance (rad)."""
        return quadratic_region(self.orientation_tolerance)


@dataclass
class Tracked:
    """The solutions of a stretch: ``positions`` (N, n), ``position_error`` and
    ``orientation_error`` (N,) in m and rad (NaN where not ``measured``), ``reached`` (N,)
    (True where not ``measured``: a full Newton step from close by)."""

    positions: FloatArray
    position_error: FloatArray
    orientation_error: FloatArray
    reached: NDArray[np.bool_]
    measured: NDArray[np.bool_]

    def taken(self, rows: NDArray[np.intp] | NDArray[np.bool_]) -> Tracked:
        """The samples ``rows`` (indices or a mask) of these."""
        return Tracked(self.positions[rows], self.position_error[rows],
                       self.orientation_error[rows], self.reached[rows], self.measured[rows])


def track_targets(problem: TrackingProblem, history: TrackingHistory,
                  stop_when_unreached: bool = False) -> Tracked:
    """Solve every sample of ``problem`` in order, from and into ``history``.

    After a sample out of reach, the next starts from the last solution that reached its
    target (back on the branch the motion left), and only when that fails from the closest
    configuration before it; the better of the two counts. With ``stop_when_unreached`` the
    loop ends after the first sample that is not reached (the results stop there).
    """
    sample_solver = _SampleSolver(problem)
    solve, predicted = sample_solver.solve, sample_solver.predicted
    escape = sample_solver.redundant
    solutions: list[Solved] = []
    ratios = problem.step_ratios.tolist()
    stills = [False] * len(ratios) if problem.still is None else problem.still.tolist()
    for index, (ratio, still) in enumerate(zip(ratios, stills, strict=True)):
        if not history.after_a_miss:
            last, back, margin, changes = history.start(ratio)
            if still:  # nothing moved: the last solution stands (no objective either)
                solved = solve(index, last, margin, True, False, False)
            elif back is None:
                solved = solve(index, last, margin, True, True)
            else:
                theta, margin, carried = predicted(last, back, margin, changes)
                solved = solve(index, theta, margin, True, False, True, carried)
        else:
            solved = solve(index, history.last_on_target, 0.0, True, True)
            if not solved[3]:
                closer = solve(index, history.last, 0.0, True, True)
                if closer[3] or _cost(problem, closer) < _cost(problem, solved):
                    solved = closer
        escaped = None if solved[3] or not escape else sample_solver.escaped(
            index, history.last_on_target, solved[0])
        if escaped is not None:
            solved = escaped
        solutions.append(solved)
        history.add(solved[0], solved[3], solved[4], sample_solver.back, escaped is not None)
        if stop_when_unreached and not solved[3]:
            break
    thetas, position_error, orientation_error, reached, _ = zip(*solutions, strict=True)
    errors = np.array(position_error)
    return Tracked(np.array(thetas), errors, np.array(orientation_error),
                   np.array(reached, dtype=bool), ~np.isnan(errors))


def _cost(problem: TrackingProblem, solved: Solved) -> float:
    """The errors of a measured solution scaled by the tolerances, their Euclidean norm."""
    return math.hypot(solved[1] / problem.position_tolerance,
                      solved[2] / problem.orientation_tolerance)


def solve_again(problem: TrackingProblem, index: int, theta: FloatArray, serve: bool = True
                ) -> Solution:
    """Sample ``index`` solved from ``theta`` and measured (``serve``: offered to the secondary
    objective): the solution, its position and orientation errors (m, rad), if reached."""
    solution, position, orientation, reached, _ = _SampleSolver(problem).solve(
        index, theta, 0.0, trust_newton=False, bridge=True, serve=serve)
    return solution, position, orientation, reached


class _SampleSolver:
    """Damped Newton on the samples of one problem, one at a time.

    What every sample reads from the problem is looked up once here: the loop runs once per
    sample, and each attribute lookup in it costs per sample (benchmarks/README.md,
    "bench_ik.py").
    """

    def __init__(self, problem: TrackingProblem) -> None:
        self.model, self.data = problem.model, problem.data
        self.frame_id, self.reference_id = problem.frame_id, problem.reference_id
        self.configurations, self.targets = problem.configurations, problem.targets
        self.joints, self.limits, self.error = problem.joints, problem.joints.limits, problem.error
        self.position_tolerance = problem.position_tolerance
        self.orientation_tolerance = problem.orientation_tolerance
        self.position_region = problem.position_region
        self.orientation_region = problem.orientation_region
        self.least_squares = problem.solver
        self.objective = problem.objective
        self.carry_self_motion = self.objective is not None and (
            self.objective.carries_self_motion)
        self.objective_margin = -math.inf if self.objective is None else (
            self.objective.quiet_margin)
        self.one_column = problem.model.nv == 1  # eigenpy hands such a Jacobian back as (6,)
        # whether a step may have more joints than rows (a whole pose has six)
        self.redundant = not self.carry_self_motion and (
            len(problem.joints.names) > 6 or not isinstance(problem.error, PoseMatch))
        # the rows the next carried step is projected on: the task's at the latest
        # linearisation; None when there are none yet, or the latest solution's motion was
        # taken in their row space already (a step that carried on the step before)
        self.rows: FloatArray | None = None
        # the latest solution's step back to the one before, when one Newton step from that
        # one gave it
        self.back: StepBack | None = None
        self._asked_rows: FloatArray | None = None  # the rows at the solution being served
        self._asked_at = np.empty(0)  # and its configuration
        # what every Newton iteration reads, in one lookup
        self._newton_reads = (self.model, self.data, self.frame_id, self.reference_id,
                              self.joints, self.limits, self.least_squares,
                              self.joints.moves_reference, self.one_column,
                              self.joints.whole_configuration)

    def predicted(self, last: FloatArray, back: FloatArray, margin: float, changes: float
                  ) -> tuple[FloatArray, float, Carried | None]:
        """``last`` carried on by the part of the step ``-back`` that moves the tool (all of
        it for a square system far from a singular configuration, or a step taken in the row
        space already; else its damped least-squares projection on the last rows), and a
        lower bound of its margin inside the limits: ``last``'s less the sum of the changes
        of the joints (``changes`` when not NaN; NaN when one is); with more joints than rows
        possible, what was carried on (:data:`Carried`, for the first Newton step to keep
        the smallest motion)."""
        if self.rows is not None and not self.carry_self_motion:
            back, changes = self.least_squares.row_space_part(self.rows, back), math.nan
        if not changes >= 0.0:  # not known
            changes = sum(map(abs, back.tolist()))
        carried = (last, back, margin, changes) if self.redundant else None
        return last - back, margin - changes, carried

    def solve(self, index: int, theta: FloatArray, margin: float, trust_newton: bool,
              bridge: bool, serve: bool = True, carried: Carried | None = None) -> Solved:
        """Sample ``index`` from ``theta``, with ``bridge`` bridged when far from its target
        (see the module docstring; a prediction is not far), then with ``serve`` offered to
        the secondary objective: the solution (the best configuration when the target is
        not reached), its position and orientation errors, whether it is reached and a lower
        bound of its margin inside the limits. ``margin`` is one of ``theta`` (0: not known, then
        ``theta`` is checked joint by joint). With ``trust_newton``, a full step from
        within the quadratic region ends the sample unmeasured: errors NaN, reached True.
        ``carried``: ``theta`` is a prediction, the last solution carried on by this."""
        q = self.configurations[index]  # the solved joints are written into it
        target = None if self.targets is None else pin.XYZQUATToSE3(self.targets[index])
        self.back = None
        if not margin > 0.0:
            margin = self.limits.margin(theta.tolist())
            if not margin >= 0.0:  # a prediction past a limit
                theta, margin, carried = self.limits.clipped(theta), 0.0, None
        if bridge:
            bridged = self._bridge(q, target, theta)
            if bridged is not theta:
                theta, margin, carried = bridged, 0.0, None
        solved = self._newton(q, target, self.error, theta, margin, self.position_tolerance,
                              self.orientation_tolerance, MAX_ITERATIONS, trust_newton,
                              carried)
        if serve and solved[3] and solved[4] <= self.objective_margin:  # inf: always
            return self._served(q, target, solved, bridge)
        return solved

    def escaped(self, index: int, last: FloatArray, missed: FloatArray) -> Solved | None:
        """Sample ``index``, missed at ``missed`` with a joint on a limit, reached along
        another self-motion than ``last``'s (:mod:`._self_motion_escape`); None when it is
        not, or ``missed`` lies inside the limits."""
        if self.limits.margin(missed.tolist()) > 0.0:
            return None
        q = self.configurations[index]
        self.joints.set_configuration(q, last)
        self._asked_rows, self._asked_at = None, q
        return escape_along_self_motion(
            lambda start: self.solve(index, start, 0.0, True, True), self.limits,
            self._task_rows(), last)

    def _bridge(self, q: FloatArray, target: pin.SE3 | None, theta: FloatArray
                ) -> FloatArray:
        """``theta`` when its tool lies close to ``target``, else the last intermediate
        target's solution along the screw motion from the tool to it."""
        tool_in_target = self._tool_in_target(q, theta, target)
        aim = self.error.nearest_match(tool_in_target)
        twist = pin.log6(aim.actInv(tool_in_target))
        parts = max(math.hypot(*twist.linear.tolist()) / BRIDGE_LENGTH,
                    math.hypot(*twist.angular.tolist()) / BRIDGE_ANGLE)
        if not parts > 1.0:  # close by (or not finite)
            return theta
        count = math.ceil(min(parts, MAX_BRIDGE_PARTS))
        goal_in_reference = aim if target is None else target.act(aim)
        for part in range(1, count):
            goal = goal_in_reference.act(pin.exp6(twist * (1.0 - part / count)))
            reached = self._newton(q, goal, _WHOLE_POSE, theta, 0.0, BRIDGE_TOLERANCE,
                                   BRIDGE_TOLERANCE, BRIDGE_ITERATIONS, False)
            if not reached[3]:
                break
            theta = reached[0]
        return theta

    def _served(self, q: FloatArray, target: pin.SE3 | None, solved: Solved,
                from_a_start: bool) -> Solved:
        """``solved`` moved by the objective's motion in the task's null space, when the
        tool gets back within its tolerances from there; else ``solved`` (with its margin
        measured afresh when that is wide enough for the objective to ask nothing: the
        bound carried from sample to sample stays above it for a while). ``from_a_start``:
        served again while it asks, up to ``rounds_from_a_start`` (else ``rounds_tracked``)."""
        assert self.objective is not None
        theta = solved[0]
        margin = self.limits.margin(theta.tolist())
        if margin > self.objective_margin:
            return solved[0], solved[1], solved[2], solved[3], margin
        for _ in range(self.objective.rounds_from_a_start if from_a_start
                       else self.objective.rounds_tracked):
            theta = solved[0]
            self.joints.set_configuration(q, theta)
            self._asked_rows, self._asked_at = None, q
            motion = self.objective.motion(theta, q, self._task_rows, from_a_start)
            if motion is None:
                break
            moved = self.limits.clipped(theta + null_space_motion(self.least_squares,
                                                                  self._task_rows(), motion))
            if not np.any(moved != theta):  # no freedom left, or the limits took it all
                break
            served = self._newton(q, target, self.error, moved, 0.0, self.position_tolerance,
                                  self.orientation_tolerance, MAX_ITERATIONS, True)
            if not served[3]:
                break
            solved, self.back = served, None
        return solved

    def _task_rows(self) -> FloatArray:
        """The task's rows (m, n) at the configuration being served, computed once."""
        if self._asked_rows is None:
            q = self._asked_at
            tool_in_reference = self._tool_in_reference(q)
            self._asked_rows = self.error.rows(self.joints.tool_jacobian(
                self.model, self.data, q, self.frame_id, self.reference_id, tool_in_reference))
        return self._asked_rows

    def _tool_in_target(self, q: FloatArray, theta: FloatArray, target: pin.SE3 | None
                        ) -> pin.SE3:
        """The tool in ``target`` (None: the reference frame) with the solved joints at
        ``theta``; leaves ``q`` and Pinocchio's data at that configuration."""
        self.joints.set_configuration(q, theta)
        tool_in_reference = self._tool_in_reference(q)
        return tool_in_reference if target is None else target.actInv(tool_in_reference)

    def _tool_in_reference(self, q: FloatArray) -> pin.SE3:
        """Forward kinematics of ``q``: the tool in the reference frame."""
        model, data = self.model, self.data
        pin.forwardKinematics(model, data, q)
        tool_in_reference = pin.updateFramePlacement(model, data, self.frame_id)
        if self.reference_id is not None:
            tool_in_reference = pin.updateFramePlacement(model, data, self.reference_id).actInv(
                tool_in_reference)
        return tool_in_reference

    def _newton(self, q: FloatArray, target: pin.SE3 | None, error: ToolMatch,
                theta: FloatArray, margin: float, position_tolerance: float,
                orientation_tolerance: float, iterations: int, trust_newton: bool,
                carried: Carried | None = None) -> Solved:
        """Damped Newton from ``theta`` (within the limits, ``margin`` a lower bound of how
        far; 0: not known) until ``error`` is within the tolerances: the solution (the best
        configuration when not), its errors, whether reached, a lower bound of its margin.
        With ``trust_newton``, a full step from within the quadratic region ends unmeasured:
        errors NaN, reached True.

        ``carried``: ``theta`` is the last solution carried on by a step. With more joints
        than rows, the first step is then the smallest motion from the last solution that
        the rows at ``theta`` take onto the target, ``d = A^+ (A step - e)``: the Newton step
        less the part of the carried step the tool does not feel (of second order, a step
        of the step before), with one solve where projecting the carried step took another.
        Its joint changes count as near-singular only past those carried on."""
        (model, data, frame_id, reference_id, joints, limits, least_squares, moves_reference,
         one_column, whole_configuration) = self._newton_reads
        position_region = self.position_region if trust_newton else -1.0
        orientation_region = self.orientation_region
        best, best_margin = theta, margin
        best_position = best_orientation = math.inf
        rows = residual = step_from = theta  # set on the first iteration
        step_error, step_margin, error_size = residual, margin, 0.0
        first, folded = True, False
        back: StepBack | None = None  # the latest step's, when full
        damping = 0.0
        configuration = q
        for _ in range(iterations):
            if whole_configuration:  # (``q`` is left as it was)
                configuration = theta
            else:
                joints.set_configuration(q, theta)
            # as _tool_in_reference, inlined: per sample
            pin.forwardKinematics(model, data, configuration)
            tool_in_reference = pin.updateFramePlacement(model, data, frame_id)
            if reference_id is not None:
                tool_in_reference = pin.updateFramePlacement(model, data, reference_id).actInv(
                    tool_in_reference)
            tool_in_target = (tool_in_reference if target is None
                              else target.actInv(tool_in_reference))
            position, orientation, vector = error.measure(tool_in_target)
            if position <= position_tolerance and orientation <= orientation_tolerance:
                if folded:  # one step from the last solution, in the rows' row space
                    self.rows, self.back = None, back
                return theta, position, orientation, True, margin
            # the errors scaled by the tolerances, compared by their Euclidean norms (hypot:
            # no overflow for a target 1e155 m away; inf compares as the largest)
            if first or math.hypot(position / position_tolerance,
                                   orientation / orientation_tolerance) < math.hypot(
                    best_position / position_tolerance, best_orientation / orientation_tolerance):
                first = False
                best, best_margin, best_position, best_orientation = (
                    theta, margin, position, orientation)
                damping = 0.0 if damping <= FIRST_DAMPING else damping / 10.0
                if moves_reference:
                    jacobian = joints.tool_jacobian(model, data, configuration, frame_id,
                                                    reference_id, tool_in_reference)
                else:  # as SolvedJoints.tool_jacobian, inlined: per sample
                    jacobian = pin.computeFrameJacobian(model, data, configuration, frame_id,
                                                        _LOCAL)
                    jacobian = joints.jacobian(jacobian.reshape(6, 1) if one_column
                                               else jacobian)
                rows = error.rows(jacobian)
                self.rows = rows
                residual = step_error = vector
                step_from, step_margin = best, best_margin
                error_size = best_position + best_orientation
                folded = False
                if carried is not None:  # the first step, from a prediction
                    if rows.shape[0] < rows.shape[1]:  # the smallest motion from the last
                        last, carried_back, step_margin, changes = carried
                        step_from, step_error = last, vector + rows.dot(carried_back)
                        error_size += changes / AMPLIFICATION
                        folded = True
                    carried = None
            else:  # take the step back, and damp it more
                damping = max(10.0 * damping, FIRST_DAMPING)
                if damping > MAX_DAMPING:
                    break
                step_from, step_error, step_margin = best, residual, best_margin
                error_size = best_position + best_orientation
                folded = False
            theta, correction, margin, changes = bounded_step(
                least_squares, rows, step_error, step_from, limits, damping, LONGEST_STEP,
                step_margin, error_size)
            if correction is None:  # not the full step
                folded = False
                continue
            back = correction, changes
            if (damping == 0.0 and best_position <= position_region
                    and best_orientation <= orientation_region):
                if folded:
                    self.rows, self.back = None, back
                return theta, math.nan, math.nan, True, margin
        return best, best_position, best_orientation, False, best_margin
