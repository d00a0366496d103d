"""`WeldProgram`: what a welding cell runs, written as moves (point to point, linear, welds,
waits) and planned into one :class:`~pinframes.values.motion.Motion` timed within the
joints' limits."""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import (
    ArgumentTypeError,
    CollisionError,
    InvalidDataError,
    JointError,
    JointSpeedError,
    JointWithoutSamplesWarning,
    joint_not_found,
)
from ..tree import FrameTree
from ..tree.robot_semantics import group_joints, group_state_values
from ..tree.urdf_names import urdf_joint_names
from ..values.motion import Motion
from ..values.pose import Pose
from ..values.weave import Weave
from ._fixed_step import Assembled, assemble
from ._limits import motion_limits, named_joint_values
from ._planner import ProgramPlanner, in_move
from .clearance_check import collisions, parse_check
from .moves import JointMove, LinearMove, Move, WaitMove, WeldMove

__all__ = ["LIMIT_TOLERANCE", "MOVE_KINDS", "WeldProgram"]

MOVE_KINDS = ("move_joints", "move_linear", "weld", "wait")
"""The moves a program is written with (its methods)."""

LIMIT_TOLERANCE = 0.01
"""How far (a fraction) a sampled velocity or acceleration may exceed its limit before
``strict=True`` refuses the motion: the timing's own rounding."""


class WeldProgram:
    """A program for the robot (and positioner) that moves ``tool``.

    Parameters
    ----------
    tree : FrameTree
        The cell. Planning does not change it; ``tree.set_motion(motion)`` puts a plan on it.
    tool : str
        The frame that moves (``"torch_tcp"``).
    joints : str or sequence of str, optional
        The joints the program moves, as ``solve_joints`` takes them (an SRDF group's name
        too): a positioner's joints with the robot's, and then targets are taken in the
        frames they name, which the positioner moves. Default: every robot joint between the
        tool and the root.
    limits : mapping, optional
        Per joint name (the tree's or the URDF's), ``velocity``, ``acceleration`` and
        ``jerk`` (radians or metres per s, s^2, s^3), as records or mappings (what
        :func:`pinframes.read_joint_limits` returns). Velocities default to the URDF's; a
        joint without an acceleration is an error naming it.
    start : mapping, sequence or str, optional
        Where the program starts: joint values by name or one per joint, or an SRDF group
        state. Default: the joints' values in the tree at time 0.
    step, check
        What :meth:`plan` takes when it is given none (a scene's program section sets them).

    Moves are added in order (each returns the program, so calls chain) and planned by
    :meth:`plan`. Each has a ``name`` (default: its kind and number, ``"move 3"``).
    """

    def __init__(self, tree: FrameTree, tool: str, *, joints: Any = None,
                 limits: Mapping[str, Any] | None = None, start: Any = None,
                 step: float = 0.004, check: Any = None) -> None:
        if not isinstance(tree, FrameTree):
            raise ArgumentTypeError(f"expected a FrameTree, got {type(tree).__name__}",
                                    field="tree")
        if tool not in tree:
            tree.pose(tool, tree.root)  # the tree's own error, naming near misses
        self.tree, self.tool = tree, tool
        self.joint_names, velocities = self._joints(joints)
        self.limits = motion_limits(self.joint_names, velocities, limits)
        self.start = self._start(start)
        self.step = _positive(step, "step")
        self.check = parse_check(check)
        self.moves: list[Move] = []

    # -- the moves ---------------------------------------------------------------------------
    def move_joints(self, target: Any, *, name: str | None = None) -> WeldProgram:
        """Point to point in joint space, time-optimal within the velocity, acceleration
        (and jerk) limits, every joint arriving together, from rest to rest. ``target``:
        joint values by name or one per joint (radians or metres), an SRDF group state's
        name, or a frame / ``Pose`` (in the root) the tool is solved onto from where the
        program stands."""
        return self._add(JointMove(self._name(name, "move_joints"), target))

    def move_linear(self, target: str | Pose, *, speed: float,
                    name: str | None = None) -> WeldProgram:
        """The tool's origin on the straight line to ``target`` (a frame, or a static
        ``Pose`` in the root), its orientation slerped, at ``speed`` m/s where the joints
        allow it and slower where they do not; from rest to rest."""
        return self._add(LinearMove(self._name(name, "move_linear"), target,
                                    _positive(speed, "speed")))

    def weld(self, seam: str, *, torch: str | None = None, speed: float | None = None,
             approach: float = 0.05, retract: float = 0.05, approach_speed: float = 0.1,
             weave: Weave | None = None, tilt: tuple[float, float] | None = None,
             free_axis: str | None = "z", name: str | None = None) -> WeldProgram:
        """A seam welded, in four parts: to the approach point (point to point), approach
        (linear, ``approach`` m along the torch target's z down to the seam's start), the
        seam (on the seam frame's own times, or at ``speed`` m/s along it), retract (linear,
        ``retract`` m back along the torch target's -z from its end); the linear parts at
        ``approach_speed`` m/s. ``seam`` is the frame that travels along the seam, ``torch``
        the frame the tool must match on it (default: ``seam``); ``weave`` (a
        :class:`~pinframes.Weave`) moves the target across the seam's y; ``tilt`` and
        ``free_axis`` as in ``solve_joints``. Each part is a move named ``"<name>: seam"``
        and so on."""
        for frame in (seam, torch):
            if frame is not None and frame not in self.tree:
                self.tree.pose(frame, self.tree.root)  # the tree's own error
        if weave is not None and not isinstance(weave, Weave):
            raise ArgumentTypeError(f"expected a pinframes.Weave, got {type(weave).__name__}",
                                    field="weave")
        return self._add(WeldMove(
            self._name(name, "weld"), seam, torch,
            None if speed is None else _positive(speed, "speed"),
            _at_least_zero(approach, "approach"), _at_least_zero(retract, "retract"),
            _positive(approach_speed, "approach_speed"), weave,
            None if tilt is None else (float(tilt[0]), float(tilt[1])), free_axis))

    def wait(self, seconds: float, *, name: str | None = None) -> WeldProgram:
        """The joints held for ``seconds``."""
        return self._add(WaitMove(self._name(name, "wait"), _at_least_zero(seconds,
                                                                          "seconds")))

    # -- planning ----------------------------------------------------------------------------
    def plan(self, *, step: float | None = None, check: Any = None,
             strict: bool = False) -> Motion:
        """The whole program as one joint trajectory, sampled every ``step`` seconds
        (default: the program's, 0.004 s unless it was made with another).

        Continuous in position and velocity, at rest between moves, every sample within the
        position limits, every velocity and acceleration within its limits; the tool on the
        path of every linear and seam move. ``check=(a, b)`` or ``check=dict(a=..., b=...,
        exclude=..., margin=...)`` measures the clearance between the shapes of frames
        ``a`` and ``b`` (names or patterns, as :meth:`FrameTree.clearance` takes them) along
        the whole motion, between samples too; :attr:`Motion.collisions` lists each move that
        comes closer than ``margin`` metres (default 0); default: the program's own check.
        ``strict=True`` raises, naming the move, at the first target not reached, limit
        broken or collision.
        """
        step = self.step if step is None else _positive(step, "step")
        checked = self.check if check is None else parse_check(check)
        planner = ProgramPlanner(self.tree, self.tool, self.joint_names, self.limits,
                                 self.start, step, strict)
        planned = [part for move in self.moves for part in planner.plan(move)]
        assembled = assemble(planned, self.start, step)
        if strict:
            self._require_within_limits(assembled)
        found = () if checked is None else collisions(
            self.tree, self.joint_names, assembled.seconds, assembled.positions,
            assembled.records, assembled.rows, checked)
        if strict and found and checked is not None:
            first = found[0]
            raise CollisionError(f"move {first.move!r}: {first.frame_a!r} comes within "
                                 f"{first.distance:.4g} m of {first.frame_b!r} at "
                                 f"{first.time_s:.3f} s (margin {checked.margin:g} m)")
        nanoseconds = np.round(assembled.seconds * 1e9).astype(np.int64)
        named = urdf_joint_names(self.tree, self.joint_names)
        return Motion(self.joint_names, nanoseconds.astype("timedelta64[ns]"),
                      self.tree.reference_time, assembled.positions, assembled.velocities,
                      assembled.accelerations, assembled.records, found, assembled.reached,
                      None if named is None else tuple(named))

    # -- helpers -----------------------------------------------------------------------------
    def _add(self, move: Move) -> WeldProgram:
        if any(existing.name == move.name for existing in self.moves):
            raise InvalidDataError(f"a move is already named {move.name!r}", field="name")
        self.moves.append(move)
        return self

    def _name(self, name: str | None, kind: str) -> str:
        if name is None:
            return f"{kind} {len(self.moves) + 1}"
        if not isinstance(name, str) or not name:
            raise ArgumentTypeError(f"expected a non-empty move name, got {name!r}",
                                    field="name")
        return name

    def _joints(self, joints: Any) -> tuple[tuple[str, ...], np.ndarray]:
        """The program's joints and their URDF velocity limits (inf where none): those
        given (names, or an SRDF group), else what ``solve_joints`` solves for the tool in
        the root (a mimic joint's tighter limit counted)."""
        if joints is None:
            with warnings.catch_warnings():  # joints without samples: the program gives some
                warnings.simplefilter("ignore", JointWithoutSamplesWarning)
                probe = self.tree.solve_joints(
                    self.tool, self.tree.pose(self.tool, self.tree.root, times=[0.0]),
                    relative_to=self.tree.root, times=[0.0])
            return tuple(probe.joint_names), np.array(probe.velocity_limits, dtype=float)
        if isinstance(joints, str):
            joints = (group_joints(self.tree, joints, [self.tool]) if joints not in
                      self.tree.joints else [joints])
        names = tuple(str(name) for name in joints)
        for name in names:
            if name not in self.tree.joints:
                raise joint_not_found(name, self.tree.joints, field="joints")
            if not self.tree.joints[name].is_actuated:
                raise JointError("follows another joint (a mimic joint): name its primary",
                                 joint=name, field="joints")
        velocities = [self.tree.joints[name].velocity or math.inf for name in names]
        return names, np.array(velocities, dtype=float)

    def _start(self, start: Any) -> np.ndarray:
        if start is None:
            held = self.tree.snapshot(0.0).joint_values if self.tree.time_union() else {
                name: self.tree.joints[name].rest_value for name in self.joint_names}
            return np.array([held[name] for name in self.joint_names], dtype=float)
        if isinstance(start, str):
            return self._start(group_state_values(self.tree, start, [self.tool]))
        if isinstance(start, Mapping):
            return named_joint_values(start, self._start(None), self.joint_names,
                                      self.tree.joints, "start")
        given = np.asarray(start, dtype=float)
        if given.shape != (len(self.joint_names),):
            raise InvalidDataError(f"expected {len(self.joint_names)} joint values, got shape "
                                   f"{given.shape}", field="start")
        return given

    def _require_within_limits(self, assembled: Assembled) -> None:
        """A :class:`JointError` naming the move and joint of a sample outside the position
        limits; a :class:`JointSpeedError` naming those whose sampled velocity or
        acceleration exceeds its limit by more than :data:`LIMIT_TOLERANCE`."""
        for column, name in enumerate(self.joint_names):
            joint = self.tree.joints[name]
            if joint.kind == "continuous":
                continue
            values = assembled.positions[:, column]
            outside = np.zeros(values.shape[0], bool)
            if joint.lower is not None:
                outside |= values < joint.lower - 1e-9
            if joint.upper is not None:
                outside |= values > joint.upper + 1e-9
            if outside.any():
                sample = int(np.flatnonzero(outside)[0])
                raise in_move(JointError(
                    f"{values[sample]:.6g} is outside the limits [{joint.lower}, "
                    f"{joint.upper}] at {assembled.seconds[sample]:.3f} s", joint=name,
                    field="positions"), _move_at(assembled, sample))
        bound = 1.0 + LIMIT_TOLERANCE
        for kind, values, limit in (("velocity", assembled.velocities, self.limits.velocity),
                                    ("acceleration", assembled.accelerations,
                                     self.limits.acceleration)):
            over = np.abs(values) > bound * limit
            if not over.any():
                continue
            sample, column = (int(index[0]) for index in np.nonzero(over))
            move = _move_at(assembled, sample)
            error = JointSpeedError(
                f"its {kind} {values[sample, column]:.4g} exceeds its limit "
                f"{limit[column]:.4g} at {assembled.seconds[sample]:.3f} s",
                joint=self.joint_names[column], field=kind)
            raise in_move(error, move)


def _move_at(assembled: Assembled, sample: int) -> str:
    """The name of the move that sample ``sample`` belongs to."""
    return next(record.name for record, (first, last)
                in zip(assembled.records, assembled.rows, strict=True)
                if first <= sample <= last)


def _positive(value: Any, field: str) -> float:
    number = _number(value, field)
    if not number > 0:
        raise InvalidDataError(f"expected a positive number, got {value!r}", field=field)
    return number


def _at_least_zero(value: Any, field: str) -> float:
    number = _number(value, field)
    if number < 0:
        raise InvalidDataError(f"expected a number of at least 0, got {value!r}", field=field)
    return number


def _number(value: Any, field: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if isinstance(value, bool) or not math.isfinite(number):
        raise ArgumentTypeError(f"expected a finite number, got {value!r}", field=field)
    return number
