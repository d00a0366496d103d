"""`IkSolutions`: every solution of a recognised arm at every sample, what
``FrameTree.ik_solutions`` returns, and :func:`every_solution`, which makes them from the
eight branches of the closed form, the joint limits and the whole turns a joint may make.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...values.timed import Timed
from ._arm_steps import SINGULAR, Arm, wrapped
from .arm_shapes import ArmShape, OpwParameters
from .configurations import BRANCH_NAMES, abb_cfx, abb_quadrants, kuka_status, kuka_turn
from .opw import opw_solutions
from .ur_type import ur_solutions

__all__ = ["LIMIT_SLACK", "STRAIGHT_WRIST", "IkSolutions", "branch_angles", "every_solution",
           "free_wrist_joint", "straight_wrists", "turn_periods"]

FloatArray = NDArray[np.float64]

LIMIT_SLACK = 1e-12
"""Radians by which a solution may pass a joint limit (rounding) and still be within it."""


@dataclass(frozen=True)
class IkSolutions(Timed):
    """Every solution of a 6-axis arm of a closed-form family at every sample.

    Attributes
    ----------
    joint_names : tuple of str
        The solved joints, the last axis of :attr:`positions`.
    positions : ndarray, shape (T, k, n)
        Joint values, radians, per sample and branch; NaN where the branch has no solution
        within the joint limits.
    configurations : ndarray of str, shape (k,)
        Each branch's name: its flags (``"front,up,noflip"``, see docs/closed-form-ik.md),
        followed, when a joint's range spans more than a turn, by ``/`` and one digit per
        such joint (in chain order): which of its values within the range (0 the lowest).
    valid : ndarray of bool, shape (T, k)
        Where :attr:`positions` hold a solution.
    times : ndarray of timedelta64[ns], shape (T,)
        Sample times after :attr:`reference_time` (or plain offsets when it is None).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    arm : ArmShape
        The recognised arm: its family, its joints from the base out and their axes.
    reference_in_tool : (ndarray (3, 3), ndarray (3,))
        The frame the targets are given in, in the tool's axes at the zero configuration
        (at the first sample), metres: what :attr:`opw_parameters` are measured from.
    """

    joint_names: tuple[str, ...]
    positions: FloatArray
    configurations: NDArray[np.str_]
    valid: NDArray[np.bool_]
    times: NDArray[np.timedelta64]
    reference_time: np.datetime64 | None
    arm: ArmShape
    reference_in_tool: tuple[FloatArray, FloatArray]

    @property
    def opw_parameters(self) -> OpwParameters:
        """The OPW parameters of an OPW arm in the frame the targets are given in (its z
        along axis 1), as opw_kinematics names them (see :class:`OpwParameters`)."""
        return self.arm.opw_parameters(*self.reference_in_tool)

    @property
    def kuka_status(self) -> NDArray[np.int64]:
        """KUKA's Status (T, k) of each solution (-1 where none; see docs/closed-form-ik.md)."""
        order = [self.joint_names.index(name) for name in self.arm.joint_names]
        status = kuka_status(self.arm, self.positions[..., order])
        return np.where(self.valid, status, -1)

    @property
    def kuka_turn(self) -> NDArray[np.int64]:
        """KUKA's Turn (T, k) of each solution: bit ``i`` where joint ``i + 1`` (from the
        base) is below 0 (-1 where there is no solution)."""
        order = [self.joint_names.index(name) for name in self.arm.joint_names]
        return np.where(self.valid, kuka_turn(self.positions[..., order]), -1)

    @property
    def abb_quadrants(self) -> NDArray[np.int64]:
        """ABB's ``cf1``, ``cf4``, ``cf6`` (T, k, 3) of each solution: the quadrants
        ``floor(q / (pi / 2))`` of joints 1, 4 and 6 from the base (0 where there is no
        solution; see :attr:`valid`)."""
        order = [self.joint_names.index(name) for name in self.arm.joint_names]
        return np.where(self.valid[..., None],
                        abb_quadrants(np.nan_to_num(self.positions[..., order])), 0)

    @property
    def abb_cfx(self) -> NDArray[np.int64]:
        """ABB's ``cfx`` (T, k) of each solution, 0..7: 4 where the wrist centre is behind
        axis 1, 2 behind the lower arm, 1 where joint 5 is below 0 (-1 where there is no
        solution; see docs/closed-form-ik.md)."""
        order = [self.joint_names.index(name) for name in self.arm.joint_names]
        return np.where(self.valid, abb_cfx(self.arm, self.positions[..., order]), -1)

    def __len__(self) -> int:
        return int(self.positions.shape[0])


def branch_angles(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                  arm: Arm = None, free: FloatArray | None = None) -> FloatArray:
    """The joint values (T, 8, 6) of the eight branches (in the shape's joint order, each
    within half a turn of 0) that move the tool from its zero configuration by
    ``rotations`` (3, 3, T) and ``translations`` (3, T); NaN out of reach. With ``arm`` (a
    branch index, or one per sample), the two wrists of its shoulder and elbow only
    (T, 2, 6). Where the wrist
    is singular its free joint (:func:`free_wrist_joint`) takes ``free`` (T,), else 0."""
    solve = opw_solutions if shape.family == "opw" else ur_solutions
    angles = solve(shape, rotations, translations, arm,
                   None if free is None else free * shape.scales[free_wrist_joint(shape)])
    return angles / shape.scales


STRAIGHT_WRIST = SINGULAR
"""The sine of joint 5's angle from the straight wrist below which the wrist is straight and
the closed form takes its free joint (:func:`free_wrist_joint`) as given."""


def straight_wrists(shape: ArmShape, fifth: FloatArray) -> NDArray[np.bool_]:
    """Where joint 5's values ``fifth`` (...) leave the wrist straight (:data:`STRAIGHT_WRIST`:
    the angle from the straight wrist that near a multiple of pi; numpy's sine takes 13 ns a
    number)."""
    return np.abs(wrapped(2.0 * (fifth * shape.scales[4] - shape.wrist_straight))
                  ) < 2.0 * STRAIGHT_WRIST


def free_wrist_joint(shape: ArmShape) -> int:
    """The joint (index from the base) that a singular wrist leaves free: joint 4 of an
    OPW arm (joint 6 turns for both), joint 6 of a UR-type arm."""
    return 3 if shape.family == "opw" else 5


def turn_periods(shape: ArmShape) -> FloatArray:
    """The value (6,) by which each joint turns its axis a whole turn, radians."""
    return 2.0 * math.pi / shape.scales


def every_solution(shape: ArmShape, rotations: FloatArray, translations: FloatArray,
                   lower: FloatArray, upper: FloatArray, whole_turns: bool
                   ) -> tuple[FloatArray, NDArray[np.str_], NDArray[np.bool_]]:
    """``(positions (T, k, 6), names (k,), valid (T, k))`` in the shape's joint order, for
    joint limits ``lower`` and ``upper`` (6,) (infinite: a continuous joint); with
    ``whole_turns``, a joint whose range spans more than a turn gives each of its values
    within the range as a further branch, else the one nearest the middle of its range."""
    base = branch_angles(shape, rotations, translations)  # (T, 8, 6)
    period = turn_periods(shape)
    span = upper - lower
    bounded = np.isfinite(span)
    counts = np.where(bounded & whole_turns,
                      np.maximum(1, np.ceil(np.where(bounded, span, 0.0) / period - 1e-9)),
                      1).astype(int)
    turns = np.indices(tuple(counts)).reshape(6, -1).T  # (M, 6): which value within the range
    count = base.shape[0]
    positions = np.empty((count, 8, turns.shape[0], 6))
    valid = np.ones((count, 8, turns.shape[0]), dtype=bool)
    for joint in range(6):  # a joint at a time: numpy reduces a last axis of 6 slowly
        angle, turn = base[..., joint], period[joint]
        if counts[joint] > 1:  # the lowest value within the range
            first = angle + turn * np.ceil((lower[joint] - angle) / turn)
        else:  # the one nearest the middle of the range (of a continuous joint: 0)
            middle = 0.5 * (lower[joint] + upper[joint]) if bounded[joint] else 0.0
            first = angle - turn * np.rint((angle - middle) / turn)
        for value in range(counts[joint]):
            moved = first + value * turn
            rows = turns[:, joint] == value
            positions[:, :, rows, joint] = moved[:, :, None]
            if bounded[joint]:
                valid[:, :, rows] &= ((moved >= lower[joint] - LIMIT_SLACK)
                                      & (moved <= upper[joint] + LIMIT_SLACK))[:, :, None]
            else:  # (NaN out of reach)
                valid[:, :, rows] &= ~np.isnan(moved)[:, :, None]
    positions = positions.reshape(count, -1, 6)
    valid = valid.reshape(count, -1)
    positions[~valid] = np.nan
    several = counts > 1
    suffixes = [""] if not several.any() else [
        "/" + "".join(str(turn) for turn in row[several]) for row in turns]
    names = np.array([name + suffix for name in BRANCH_NAMES for suffix in suffixes])
    return positions, names, valid
