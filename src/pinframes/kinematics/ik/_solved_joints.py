"""The joints an inverse-kinematics solve moves: which they are, their limits, and how their
values enter the Pinocchio configuration of a compiled path.

The unknowns are the values ``theta`` (radians or metres) of ``n`` actuated joints. Every
joint of the compiled model that one of them drives (itself, or a mimic joint following it
through a chain of mimics) takes ``multiplier * theta + offset``; a continuous joint about an
aligned axis is stored by Pinocchio as ``(cos, sin)``. Moving frames and the other joints keep
their sampled values. Each solved joint is bounded by its own position limits and those of
the mimic joints that follow it, and moves at most as fast as its own URDF velocity limit and
theirs allow (a follower at ``m * theta + c`` with limit ``L`` allows ``theta`` ``L / |m|``).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping, Sequence

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ...errors import JointError
from ...values.joint import Drive, Joint
from .._model import CompiledModel
from .._plan import PreparedPath
from ._bounded_step import JointLimits

__all__ = ["TURN_SLACK", "SolvedJoints", "solved_joints"]

FloatArray = NDArray[np.float64]

_TURN = 2.0 * math.pi
"""One turn of a revolute joint, radians."""

TURN_SLACK = 1e-3
"""Radians by which a joint's range may fall short of a whole turn and still count as one
(URDFs write 3.1415 for pi)."""

_LOCAL = pin.ReferenceFrame.LOCAL
"""Pinocchio's frame of a Jacobian in the tool's own axes."""


class SolvedJoints:
    """``n`` actuated joints solved for, and where their values go in a compiled model.

    Attributes
    ----------
    names : tuple of str
        The joints, in the order of ``theta``.
    limits : JointLimits
        Position limits of ``theta``: each joint's own, narrowed by those of the mimic joints
        that follow it (continuous joints unbounded).
    tangent : ndarray, shape (nv, n)
        Velocity of the model per unit rate of each joint: the multipliers of the model
        joints it drives, in their velocity slots. ``J @ tangent`` is a Jacobian in ``theta``.
    moves_reference : bool
        Whether a solved joint moves the reference frame (joints on the target's side).
    whole_configuration : bool
        Whether ``theta`` is the model's whole configuration as it is (the solved joints are
        all its joints, in order, none continuous or mimicked): Pinocchio can take it as ``q``.
    velocity_limits : ndarray, shape (n,)
        Per joint, the largest rate (rad/s or m/s) its URDF velocity limit and those of its
        mimic followers allow (inf where none has one; a limit that is not a positive number,
        URDFs write 0 for "not given", counts as none).
    velocity_limit_joints : tuple of str
        Per joint, the joint whose limit that is: itself, or the tighter follower.
    whole_turns : ndarray of bool, shape (n,)
        Per joint, whether it is a revolute joint that no mimic joint follows and whose
        range covers a whole turn (to :data:`TURN_SLACK`): its value and that value plus or
        minus a turn put every frame in the same place.
    """

    def __init__(self, names: Sequence[str], model: CompiledModel, joints: Mapping[str, Joint],
                 drives: Mapping[str, Drive], reference: str) -> None:
        self.names = tuple(names)
        column_of = {name: column for column, name in enumerate(self.names)}
        pinocchio_model = model.model
        self.tangent = np.zeros((pinocchio_model.nv, len(self.names)))
        linear: list[tuple[int, int, float, float]] = []  # (q slot, column, multiplier, offset)
        turning: list[tuple[int, int, float, float]] = []  # (cos slot, column, mult., offset)
        reference_side = set(pinocchio_model.supports[
            pinocchio_model.frames[model.frame_ids[reference]].parentJoint])
        self.moves_reference = False
        for position, compiled in enumerate(model.joints):
            if compiled.joint is None:
                continue
            drive = drives[compiled.joint.name]
            column = column_of.get(drive.primary, -1)
            if column < 0:
                continue
            multiplier, offset = drive.multiplier, drive.offset
            joint_id = position + 1  # Pinocchio's joint 0 is the universe
            self.tangent[pinocchio_model.idx_vs[joint_id], column] = multiplier
            slot = pinocchio_model.idx_qs[joint_id]
            target = turning if pinocchio_model.nqs[joint_id] == 2 else linear
            target.append((slot, column, multiplier, offset))
            self.moves_reference |= joint_id in reference_side
        self._linear = _columns(linear)
        self._turning = _columns(turning)
        self._slice = _plain_slice(linear, turning, len(self.names))
        self.whole_configuration = self._slice == slice(0, pinocchio_model.nq)
        self._velocity_slice = _selected_slice(self.tangent)
        self._every_velocity = self._velocity_slice == slice(0, pinocchio_model.nv)
        self.velocity_limits, self.velocity_limit_joints = _velocity_limits(
            self.names, joints, drives)
        lower, upper = _bounds(self.names, joints, drives)
        self.limits = JointLimits(lower, upper)
        followed = {drive.primary for name, drive in drives.items() if drive.primary != name}
        self.whole_turns = np.array([joints[name].kind == "revolute" and name not in followed
                                     for name in self.names], dtype=bool) & (
            upper - lower >= _TURN - TURN_SLACK)

    def turning_freely(self) -> SolvedJoints:
        """These joints with the limits of the :attr:`whole_turns` joints taken away (a
        solve from far away then turns them the short way instead of stopping on a limit;
        :meth:`into_ranges` brings its solution back); themselves when there are none."""
        if not self.whole_turns.any():
            return self
        free = copy.copy(self)
        free.limits = JointLimits(np.where(self.whole_turns, -np.inf, self.limits.lower),
                                  np.where(self.whole_turns, np.inf, self.limits.upper))
        return free

    def into_ranges(self, theta: FloatArray) -> FloatArray:
        """``theta`` (n,) with each :attr:`whole_turns` joint outside its range moved by whole
        turns to within half a turn of the middle of the range (the same pose of every
        frame, and the most room either way; onto a limit where the range falls short of a
        turn by :data:`TURN_SLACK`); a new array."""
        lower, upper = self.limits.lower, self.limits.upper
        outside = self.whole_turns & ((theta < lower) | (theta > upper))
        moved = theta.copy()
        if outside.any():
            lower, upper = lower[outside], upper[outside]
            middle = 0.5 * (lower + upper)
            moved[outside] = np.clip(
                middle + np.mod(theta[outside] - middle + math.pi, _TURN) - math.pi, lower, upper)
        return moved

    def set_configuration(self, q: FloatArray, theta: FloatArray) -> None:
        """Put the solved joints of the configuration ``q`` (nq,) at ``theta``, in place."""
        if self._slice is not None:
            q[self._slice] = theta
            return
        slots, columns, multipliers, offsets = self._linear
        q[slots] = multipliers * theta[columns] + offsets
        slots, columns, multipliers, offsets = self._turning
        if slots.shape[0]:
            angles = multipliers * theta[columns] + offsets
            q[slots] = np.cos(angles)
            q[slots + 1] = np.sin(angles)

    def jacobian(self, model_jacobian: FloatArray) -> FloatArray:
        """The Jacobian (6, n) in ``theta`` from one in the model's velocity (6, nv)."""
        if self._every_velocity:  # theta is the model's velocity as it is
            return model_jacobian
        if self._velocity_slice is not None:
            return model_jacobian[:, self._velocity_slice]
        return model_jacobian.dot(self.tangent)

    def tool_jacobian(self, model: pin.Model, data: pin.Data, q: FloatArray, tool_id: int,
                      reference_id: int | None, tool_in_reference: pin.SE3) -> FloatArray:
        """The tool's ``LOCAL`` Jacobian (6, n) in ``theta`` relative to the reference frame
        at the configuration ``q`` (nq,), ``tool_in_reference`` its pose there: when solved
        joints move the reference too, its motion (seen in the tool's axes) counts against.
        (eigenpy hands a one-column matrix back as a vector: reshaped.)"""
        if not self.moves_reference:
            return self.jacobian(pin.computeFrameJacobian(model, data, q, tool_id, _LOCAL)
                                 .reshape(6, -1))
        pin.computeJointJacobians(model, data, q)
        tool = pin.getFrameJacobian(model, data, tool_id, _LOCAL).reshape(6, -1)
        reference = pin.getFrameJacobian(model, data, reference_id, _LOCAL).reshape(6, -1)
        return self.jacobian(tool - tool_in_reference.inverse().action.dot(reference))


def _columns(entries: list[tuple[int, int, float, float]]
             ) -> tuple[NDArray[np.intp], NDArray[np.intp], FloatArray, FloatArray]:
    slots, columns, multipliers, offsets = zip(*entries, strict=True) if entries else ((),) * 4
    return (np.array(slots, dtype=np.intp), np.array(columns, dtype=np.intp),
            np.array(multipliers, dtype=float), np.array(offsets, dtype=float))


def _plain_slice(linear: list[tuple[int, int, float, float]],
                 turning: list[tuple[int, int, float, float]], count: int) -> slice | None:
    """The slice of ``q`` that holds ``theta`` as it is (consecutive slots, in order, no mimic
    and no continuous joint), or None."""
    if turning or len(linear) != count or not linear:
        return None
    start = linear[0][0]
    for index, (slot, column, multiplier, offset) in enumerate(linear):
        if slot != start + index or column != index or multiplier != 1.0 or offset != 0.0:
            return None
    return slice(start, start + count)


def _selected_slice(tangent: FloatArray) -> slice | None:
    """The slice of velocity slots that ``tangent`` selects as it is (the identity on
    consecutive slots), or None."""
    column = tangent[:, 0] if tangent.shape[1] else np.zeros(0)
    if not np.any(column):
        return None
    start = int(np.argmax(column != 0.0))
    count = tangent.shape[1]
    plain = np.zeros_like(tangent)
    plain[start:start + count] = np.eye(count)[:tangent.shape[0] - start]
    return slice(start, start + count) if np.array_equal(tangent, plain) else None


def _bounds(names: Sequence[str], joints: Mapping[str, Joint], drives: Mapping[str, Drive]
            ) -> tuple[FloatArray, FloatArray]:
    """Limits of each solved joint: its own, narrowed by its mimic followers' (a follower
    at ``m * theta + c`` within ``[lower, upper]`` bounds ``theta`` by ``(lower - c) / m`` and
    ``(upper - c) / m``, swapped when ``m < 0``). Continuous joints are unbounded."""
    lower = np.full(len(names), -np.inf)
    upper = np.full(len(names), np.inf)
    column_of = {name: column for column, name in enumerate(names)}
    for joint in joints.values():
        if joint.kind == "continuous":
            continue
        drive = drives[joint.name]
        column, multiplier, offset = (column_of.get(drive.primary, -1), drive.multiplier,
                                      drive.offset)
        if column < 0 or multiplier == 0.0:
            continue
        sign = 1.0 if multiplier > 0 else -1.0
        ends = [sign * -np.inf if joint.lower is None else (joint.lower - offset) / multiplier,
                sign * np.inf if joint.upper is None else (joint.upper - offset) / multiplier]
        low, high = min(ends), max(ends)
        lower[column] = max(lower[column], low)
        upper[column] = min(upper[column], high)
    for column, name in enumerate(names):
        if lower[column] > upper[column]:
            raise JointError("its limits and those of the joints that mimic it leave no "
                             f"value ({lower[column]:.6g} > {upper[column]:.6g})", frame=name,
                             field="limit")
    return lower, upper


def _velocity_limits(names: Sequence[str], joints: Mapping[str, Joint],
                     drives: Mapping[str, Drive]) -> tuple[FloatArray, tuple[str, ...]]:
    """:attr:`SolvedJoints.velocity_limits` and :attr:`SolvedJoints.velocity_limit_joints`
    (the joint itself on ties)."""
    rates = np.full(len(names), np.inf)
    limiting = list(names)
    column_of = {name: column for column, name in enumerate(names)}
    for joint in joints.values():
        limit = joint.velocity
        drive = drives[joint.name]
        column = column_of.get(drive.primary)
        if limit is None or not 0.0 < limit < math.inf or column is None or (
                drive.multiplier == 0.0):
            continue
        allowed = limit / abs(drive.multiplier)
        if allowed < rates[column] or (allowed == rates[column] and joint.name == drive.primary):
            rates[column] = allowed
            limiting[column] = joint.name
    return rates, tuple(limiting)


def _joints_moving_frame(model: CompiledModel, drives: Mapping[str, Drive], frame: str
                         ) -> list[str]:
    """The actuated joints (mimic primaries) of the robot joints between ``frame`` and the
    root of ``model``, from the root out."""
    pinocchio_model = model.model
    support = pinocchio_model.supports[pinocchio_model.frames[model.frame_ids[frame]].parentJoint]
    names: list[str] = []
    for joint_id in list(support)[1:]:
        compiled = model.joints[joint_id - 1]
        if compiled.joint is not None:
            primary = drives[compiled.joint.name].primary
            if primary not in names:
                names.append(primary)
    return names


def solved_joints(path: PreparedPath, joints: Mapping[str, Joint],
                  drives: Mapping[str, Drive], names: Sequence[str] | None,
                  added: Sequence[str] = ()) -> SolvedJoints:
    """The joints to solve on the moving ``path`` (its tool ``frame``, its reference
    ``relative_to``): ``names`` (distinct actuated joints, checked by the caller), or every
    joint that moves the tool relative to the reference from the tool's side of the path;
    then those of ``added`` not among them; ``drives`` as
    :attr:`~pinframes.kinematics._description.TreeDescription.drives`. Kept with the path per
    request (so made once per tree version).

    Raises :class:`~pinframes.errors.JointError` (field ``joints`` or ``add_joints``) for a
    joint that moves neither frame, or nothing to solve.
    """
    key = ("solve_joints: " + ("every joint" if names is None else "named: " + "\0".join(names))
           + " added: " + "\0".join(added))
    cached = path.plans.get(SolvedJoints, key)
    if cached is None:
        cached = path.plans.keep(SolvedJoints, key,
                                 _solved_joints(path, joints, drives, names, added))
    return cached


def _solved_joints(path: PreparedPath, joints: Mapping[str, Joint],
                   drives: Mapping[str, Drive], names: Sequence[str] | None,
                   added: Sequence[str]) -> SolvedJoints:
    """:func:`solved_joints`, made afresh."""
    model, frame, reference = path.model, path.frame, path.relative_to
    assert model is not None
    own = _joints_moving_frame(model, drives, frame)
    if names is None and not own:
        raise JointError(f"no robot joint moves {frame!r} relative to {reference!r}",
                         frame=frame, field="joints")
    chosen = list(own if names is None else names)
    chosen += [name for name in added if name not in chosen]
    movers = own + _joints_moving_frame(model, drives, reference)
    for name in chosen:
        if name not in movers:
            raise JointError(f"joint {name!r} moves neither {frame!r} nor {reference!r}",
                             frame=frame, field="joints" if name in (names or own)
                             else "add_joints")
    return SolvedJoints(chosen, model, joints, drives, reference)
