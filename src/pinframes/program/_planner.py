"""Planning a program move by move: each target resolved where the program then stands,
the joint path of a linear or seam move solved with ``FrameTree.solve_joints`` at dense
nodes, and each move timed (point to point, or along its path) within the joints' limits.

The program's clock is the tree's: a frame target is taken where it is when its move starts
(the program's first sample is the tree's time 0). The tree is taken as standing still
during a move but for the program's joints; a seam is followed on its own times.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import (
    ArgumentTypeError,
    InvalidDataError,
    JointError,
    PinframesError,
    TargetNotReachedError,
)
from ..kinematics import JointSolution
from ..kinematics.timing import MotionLimits, time_along_path, time_point_to_point
from ..tree import FrameTree
from ..tree.robot_semantics import group_state_values
from ..values.pose import Pose
from ._limits import named_joint_values
from ._planned_moves import PlannedMove, steps_of
from .cartesian_paths import TargetPath, filled_times, line_path, offset_along_z, seam_path
from .moves import JointMove, LinearMove, Move, WaitMove, WeldMove

__all__ = ["ProgramPlanner", "in_move"]

FloatArray = NDArray[np.float64]

CONTINUITY_RAD = 1e-3
"""Largest gap (radians or metres) between where a path's first node is solved and where the
program stands; within it the first node is taken as where the program stands."""


def in_move(error: PinframesError, move: str) -> PinframesError:
    """``error`` with its message prefixed by the move's name."""
    return type(error)(f"move {move!r}: {error.message}", file=error.file, frame=error.frame,
                       field=error.field, joint=error.joint)


class ProgramPlanner:
    """Plans moves one after another from the program's start.

    Parameters
    ----------
    tree : FrameTree
        The cell; it is not changed (a copy takes the joint values for the tool's pose).
    tool : str
        The frame that moves.
    joint_names : tuple of str
        The program's joints (what ``solve_joints`` solves for the tool).
    limits : MotionLimits
        Their limits.
    start : ndarray, shape (n,)
        Where the program starts.
    step : float
        The program's sample step, seconds.
    strict : bool
        Raise at the first target not reached.
    """

    def __init__(self, tree: FrameTree, tool: str, joint_names: tuple[str, ...],
                 limits: MotionLimits, start: FloatArray, step: float, strict: bool) -> None:
        self.tree, self.tool, self.joint_names = tree, tool, joint_names
        self.limits, self.step, self.strict = limits, step, strict
        self.current = np.array(start, dtype=float)
        self.clock = 0.0
        self._work: FrameTree | None = None  # a copy for the tool's poses, made when needed

    def plan(self, move: Move) -> list[PlannedMove]:
        """The planned parts of ``move`` (a weld has up to four), the program moved on to
        where they end."""
        try:
            parts = self._parts(move)
        except PinframesError as exc:
            raise in_move(exc, move.name) from None
        return parts

    def _parts(self, move: Move) -> list[PlannedMove]:
        if isinstance(move, WaitMove):
            return [self._advance(PlannedMove(move.name, "wait", self.current, None,
                                              move.seconds))]
        if isinstance(move, JointMove):
            return [self._joint_move(move.name, move.target, None)]
        if isinstance(move, LinearMove):
            reference, end = self._target(move.target)
            path = line_path(self.tool_pose(self.current, reference), end, move.speed,
                             self.clock)
            return [self._path_move(move.name, "linear", reference, path, None, None)]
        return self._weld(move)

    def _weld(self, move: WeldMove) -> list[PlannedMove]:
        torch = move.torch if move.torch is not None else move.seam
        root = self.tree.root
        axis = self.tree.sample_times(torch, root)
        if axis is None or axis.offsets.shape[0] < 2:
            raise InvalidDataError(f"{torch!r} does not move relative to {root!r}: a seam is "
                                   "a frame that travels along it", frame=torch, field="seam")
        seam_parent = self.tree.parent(move.seam)
        if seam_parent is None:
            raise InvalidDataError("the root is no seam", frame=move.seam, field="seam")
        own = axis.offsets / 1e9
        nodes = filled_times(self.tree.pose(torch, root, times=axis.as_numpy()), own,
                             move.weave)
        at_nodes = _times_like(axis.reference, nodes)
        travel = self.tree.pose(move.seam, seam_parent, times=at_nodes).translation
        seam_in_torch = np.asarray(self.tree.pose(move.seam, torch, times=at_nodes[:1]
                                                  ).rotation[0], dtype=float)
        seam = seam_path(nodes, travel, move.speed, move.weave, seam_in_torch)
        first, last = _static(seam.poses, 0), _static(seam.poses, -1)
        above = offset_along_z(first, move.approach)
        parts = [self._joint_move(f"{move.name}: to approach", (torch, above, nodes[0]),
                                  move.free_axis)]
        if move.approach > 0:
            approach = line_path(above, first, move.approach_speed, nodes[0], ending=True)
            parts.append(self._path_move(f"{move.name}: approach", "approach", torch,
                                         approach, move.free_axis, None))
        parts.append(self._path_move(f"{move.name}: seam", "seam", torch, seam,
                                     move.free_axis, move.tilt))
        if move.retract > 0:
            retract = line_path(last, offset_along_z(last, move.retract),
                                move.approach_speed, nodes[-1])
            parts.append(self._path_move(f"{move.name}: retract", "retract", torch, retract,
                                         move.free_axis, None))
        return parts

    # -- the three kinds of timing ---------------------------------------------------------
    def _joint_move(self, name: str, target: Any, free_axis: str | None) -> PlannedMove:
        goal, reached = self._joint_goal(target, free_axis, name)
        timing = time_point_to_point(self.current, goal, self.limits)
        return self._advance(PlannedMove(name, "joints", self.current, timing,
                                         float(timing.duration), None,
                                         None if reached is None else np.array([reached])))

    def _path_move(self, name: str, kind: str, reference: str, path: TargetPath,
                   free_axis: str | None, tilt: tuple[float, float] | None) -> PlannedMove:
        solution = self._solve(reference, path.poses, free_axis, tilt)
        self._require_reached(solution, name, path)
        positions = np.array(solution.positions, dtype=float)
        gap = np.abs(positions[0] - self.current)
        if gap.max() > CONTINUITY_RAD:
            column = int(gap.argmax())
            raise JointError(f"the path's first pose is solved {gap[column]:.4g} away from "
                             "where the program stands (another branch of the robot); move "
                             "there first", joint=self.joint_names[column], field="target")
        positions[0] = self.current
        timing = time_along_path(positions, path.parameter, self.limits,
                                 max_parameter_speed=path.parameter_speed)
        return self._advance(PlannedMove(name, kind, self.current, timing,
                                         float(timing.duration), path,
                                         np.asarray(solution.reached, bool)))

    def _advance(self, planned: PlannedMove) -> PlannedMove:
        """Move the program on to where ``planned`` ends."""
        self.current = planned.end
        self.clock += steps_of(planned.duration, self.step) * self.step
        return planned

    # -- targets ----------------------------------------------------------------------------
    def _joint_goal(self, target: Any, free_axis: str | None, name: str
                    ) -> tuple[FloatArray, bool | None]:
        """The joint values a point-to-point ``target`` asks for, and whether a pose target
        was reached (None for joint values). ``target`` may also be (a frame, a static pose
        in it, the time it is taken at)."""
        if isinstance(target, tuple):
            reference, pose, time = target
        elif isinstance(target, Pose) or (isinstance(target, str) and target in self.tree):
            (reference, pose), time = self._target(target), self.clock
        if isinstance(target, tuple | Pose) or (isinstance(target, str) and target in self.tree):
            solution = self._solve(reference, _at(pose, time), free_axis, None)
            reached = bool(solution.reached[0])
            if self.strict and not reached:
                raise TargetNotReachedError(
                    f"the tool cannot reach the target (position error "
                    f"{solution.position_error[0]:.3g} m, orientation error "
                    f"{solution.orientation_error[0]:.3g} rad)", frame=self.tool,
                    field="target")
            return np.array(solution.positions[0], dtype=float), reached
        if isinstance(target, str):
            values: Any = group_state_values(self.tree, target, [self.tool])
        else:
            values = target
        return self._joint_values(values), None

    def _joint_values(self, values: Any) -> FloatArray:
        goal = self.current.copy()
        if isinstance(values, Mapping):
            goal = named_joint_values(values, goal, self.joint_names, self.tree.joints,
                                      "target")
        elif isinstance(values, Sequence) or isinstance(values, np.ndarray):
            given = np.asarray(values, dtype=float)
            if given.shape != goal.shape:
                raise InvalidDataError(f"expected {goal.shape[0]} joint values (one per "
                                       f"program joint), got shape {given.shape}",
                                       field="target")
            goal = given.copy()
        else:
            raise ArgumentTypeError("expected joint values (a mapping or a sequence), an SRDF "
                                    f"group state, a frame or a Pose, got "
                                    f"{type(values).__name__}", field="target")
        for column, name in enumerate(self.joint_names):
            joint = self.tree.joints[name]
            value = goal[column]
            if not np.isfinite(value) or (
                    joint.kind != "continuous"
                    and ((joint.lower is not None and value < joint.lower - 1e-9)
                         or (joint.upper is not None and value > joint.upper + 1e-9))):
                raise JointError(f"target {value:.6g} is outside the limits "
                                 f"[{joint.lower}, {joint.upper}]", joint=name, field="target")
        return goal

    def _target(self, target: Any) -> tuple[str, Pose]:
        """Where a move's ``target`` puts the tool: (a frame, a static pose in it): a frame
        itself (the identity in it), or a ``Pose`` in the root."""
        if isinstance(target, Pose):
            if target.is_time_dependent:
                raise InvalidDataError("a move's target pose must be static (one pose)",
                                       field="target")
            return self.tree.root, target
        if not isinstance(target, str):
            raise ArgumentTypeError(f"expected a frame name or a Pose, got "
                                    f"{type(target).__name__}", field="target")
        if target not in self.tree:
            self.tree.pose(target, self.tree.root)  # the tree's own error, naming near misses
        return target, Pose()

    def tool_pose(self, positions: FloatArray, reference: str) -> Pose:
        """The tool's pose in ``reference`` now with the program's joints at ``positions``."""
        if self._work is None:
            self._work = self.tree.copy()
        self._work.set_joint_trajectory([self.clock], positions[None, :], self.joint_names)
        return _static(self._work.pose(self.tool, reference, times=[self.clock]), 0)

    def _solve(self, reference: str, targets: Pose, free_axis: str | None,
               tilt: tuple[float, float] | None) -> JointSolution:
        times = targets.seconds
        assert times is not None
        return self.tree.solve_joints(
            self.tool, targets, relative_to=reference, times=times,
            joints=list(self.joint_names), free_axis=free_axis, tilt=tilt,
            seed=dict(zip(self.joint_names, self.current.tolist(), strict=True)))

    def _require_reached(self, solution: JointSolution, name: str, path: TargetPath) -> None:
        if not self.strict or solution.all_reached:
            return
        node = int(np.flatnonzero(~solution.reached)[0])
        raise TargetNotReachedError(
            f"the tool cannot follow the path at {path.parameter[node]:.4g} (of "
            f"{path.parameter[-1]:.4g}) along it: position error "
            f"{solution.position_error[node]:.3g} m, orientation error "
            f"{solution.orientation_error[node]:.3g} rad", frame=self.tool, field="target")


def _static(pose: Pose, index: int) -> Pose:
    """Sample ``index`` of ``pose`` as a static pose."""
    if not pose.is_time_dependent:
        return pose
    return Pose(pose.translation[index], pose.rotation[index])


def _times_like(reference: np.datetime64 | None, seconds: FloatArray) -> NDArray[Any]:
    """``seconds`` after ``reference`` as numpy times (relative ones without it)."""
    offsets = np.round(seconds * 1e9).astype(np.int64).astype("timedelta64[ns]")
    return offsets if reference is None else reference + offsets


def _at(pose: Pose, seconds: float) -> Pose:
    """A static ``pose`` as a one-sample pose at ``seconds``."""
    return Pose(pose.translation[None], pose.rotation[None], times=[seconds])

