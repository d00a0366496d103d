"""One Newton step of an inverse-kinematics solve, kept within the joints' position limits.

The step ``d`` (radians or metres per joint) makes the linearised error vanish,
``rows @ d = -error``, in the least-squares sense and with the smallest norm: with as many
joints as error rows it is the solution of the square system (LU), with more (a redundant
arm, a free tool axis) the smallest step (through ``rows @ rows.T``: the least joint motion),
with fewer the best fit (through ``rows.T @ rows``).
``damping > 0`` adds ``damping * |d|^2`` to what is minimised (Levenberg-Marquardt: shorter,
safer steps near a singularity or when the target is out of reach); a step that turns a
small error into a large motion is taken again damped (:data:`AMPLIFICATION`). The normal equations
square the condition number; the next Newton iteration corrects what that costs, and a
singular system is taken again with damping.

Limits by an active set: a joint that the step would carry past a limit is put on that limit
and the other joints solve for what remains; at most one round per joint. The small dense
systems are solved by Eigen through eigenpy (Pinocchio's own binding of it): a 6 x 6 solve
there costs a third of ``numpy.linalg.solve``'s overhead, which the solver pays per sample.
"""

from __future__ import annotations

import operator
from typing import Any

import eigenpy
import numpy as np
from numpy.typing import NDArray

__all__ = ["JointLimits", "LeastSquares", "bounded_step"]

FloatArray = NDArray[np.float64]

_LARGEST_STEP = 1e6
"""A step longer than this (radians or metres) comes from a singular system: it is taken
again with damping."""

_SINGULAR_DAMPING = 1e-9
"""The damping of a step whose undamped system is singular (error units squared)."""

AMPLIFICATION = 1e3
"""A step whose joint changes sum to more than this times the error's size (radians or
metres per metre or radian) comes from a system near a singular configuration: its
smallest singular values turn small errors into large motions along the directions the tool
barely feels (a wrist's two axes in line trading turns). It is taken again with
:data:`NEAR_SINGULAR_DAMPING`."""

NEAR_SINGULAR_DAMPING = 1e-6
"""The damping of a step near a singular configuration (metres or radians squared): it
leaves directions whose singular value is well above its square root (1e-3) as they are
and holds still the ones below."""


class JointLimits:
    """Position limits of the solved joints, radians or metres (infinite where unbounded).

    Attributes
    ----------
    lower, upper : ndarray, shape (n,)
        The limits, ``lower <= upper``.
    """

    def __init__(self, lower: FloatArray, upper: FloatArray) -> None:
        self.lower, self.upper = lower, upper
        self._lower, self._upper = lower.tolist(), upper.tolist()

    def contain(self, values: list[float]) -> bool:
        """Whether every value lies within its joint's limits (NaN does not); Python floats,
        whose comparisons cost a fraction of numpy's per call for a handful of joints."""
        return all(map(operator.le, self._lower, values)) and all(
            map(operator.le, values, self._upper))

    def margin(self, values: list[float]) -> float:
        """How far the values (finite) lie inside their joints' limits: the distance
        (radians or metres) from the nearest value to its limit; below zero when one lies
        outside, infinite when no joint is bounded."""
        return min(min(map(operator.sub, values, self._lower)),
                   min(map(operator.sub, self._upper, values)))

    def clipped(self, theta: FloatArray) -> FloatArray:
        """``theta`` moved onto the limits where it lies outside them (a new array)."""
        return np.minimum(np.maximum(theta, self.lower), self.upper)


class LeastSquares:
    """The correction ``c`` with ``rows @ c ~ error`` (the Newton step is ``-c``; see the
    module docstring), no limits.

    Keeps one Eigen decomposition per kind and size and computes it again in place for each
    system: half the cost of building one per step. (Eigen's complete orthogonal
    decomposition, the exact smallest-norm solution, took twice the normal equations' time
    on the Panda's 6 x 7 systems.)
    """

    def __init__(self) -> None:
        self._lu: dict[int, Any] = {}  # Eigen's partial-pivoting LU, by size
        self._llt: dict[int, Any] = {}  # Eigen's Cholesky, by size
        self._undamped: FloatArray | None = None  # the rows of the latest undamped solve

    def row_space_part(self, rows: FloatArray, motion: FloatArray) -> FloatArray:
        """The part of ``motion`` (n,) that ``rows`` (m, n) feel, ``A^+ A motion``, with
        :data:`NEAR_SINGULAR_DAMPING`; for the rows of the latest solve when it was
        undamped (so not near a singular configuration) from its decomposition: all of
        ``motion`` for a square system, one Cholesky solve for a redundant one."""
        count, joints = rows.shape
        if rows is self._undamped:
            if joints == count:
                return motion
            if joints > count:
                return self._llt[count].solve(rows.dot(motion)).dot(rows)  # type: ignore[no-any-return]
        return self.correction(rows, rows.dot(motion), NEAR_SINGULAR_DAMPING)

    def correction(self, rows: FloatArray, error: FloatArray, damping: float) -> FloatArray:
        """``c`` (n,) for ``rows`` (m, n) and ``error`` (m,)."""
        count, joints = rows.shape
        self._undamped = rows if damping == 0.0 and joints >= count else None
        if damping == 0.0 and count == joints:
            lu = self._lu.get(count) or _of_size(self._lu, eigenpy.PartialPivLU, count)
            correction = lu.compute(rows).solve(error)
        elif joints > count:  # c = A^T (A A^T + damping I)^-1 e
            normal = rows.dot(rows.T)  # .dot: a third of matmul's cost on these sizes
            if damping:
                normal.flat[::count + 1] += damping
            llt = self._llt.get(count) or _of_size(self._llt, eigenpy.LLT, count)
            # (y^T A)^T, not A^T y: the same numbers, a quarter less numpy overhead
            correction = llt.compute(normal).solve(error).dot(rows)
        else:  # c = (A^T A + damping I)^-1 A^T e
            transposed = rows.T
            normal = transposed.dot(rows)
            if damping:
                normal.flat[::joints + 1] += damping
            llt = self._llt.get(joints) or _of_size(self._llt, eigenpy.LLT, joints)
            correction = llt.compute(normal).solve(transposed.dot(error))
        # eigenpy returns a one-element solution as a (1, 1) matrix
        return correction if joints > 1 else correction.reshape(1)


def _of_size(decompositions: dict[int, Any], kind: Any, size: int) -> Any:
    """The decomposition of ``kind`` (an eigenpy class) for ``size`` x ``size`` matrices in
    ``decompositions``, made on first use."""
    decomposition = decompositions.get(size)
    if decomposition is None:
        decomposition = decompositions[size] = kind(size)
    return decomposition


def bounded_step(solver: LeastSquares, rows: FloatArray, error: FloatArray, theta: FloatArray,
                 limits: JointLimits, damping: float, longest_step: float, margin: float,
                 error_size: float) -> tuple[FloatArray, FloatArray | None, float, float]:
    """The joint values after a least-squares Newton step from ``theta``: at most
    ``longest_step`` (radians or metres) per joint, within the ``limits`` (joints that would
    cross one are fixed on it); when that was the full step (not shortened, not limited, its
    system not singular) its correction ``c`` (the values are ``theta - c``), else None; a
    lower bound of their ``limits.margin`` (0: not known); and the sum of the joint changes
    of the full step (radians or metres).

    ``margin``: a lower bound of ``limits.margin`` of ``theta`` (0: not known). A step whose
    joint changes sum to less than half of it stays inside the limits, by at least the
    margin less that sum: no need to check them joint by joint (the usual tracked sample).

    ``error_size``: how large the error is (the position error in metres plus the
    orientation error in radians): a step whose joint changes sum to more than
    :data:`AMPLIFICATION` times it comes from a near-singular system."""
    correction = solver.correction(rows, error, damping)
    values = correction.tolist()
    total = sum(map(abs, values))  # NaN when one is
    near_singular = not total <= AMPLIFICATION * error_size
    if near_singular and damping < NEAR_SINGULAR_DAMPING:
        damping = NEAR_SINGULAR_DAMPING
        correction = solver.correction(rows, error, damping)
        values = correction.tolist()
        total = sum(map(abs, values))
    elif total <= longest_step and total < margin / 2:  # (half: a margin for rounding)
        return theta - correction, correction, margin - total, total
    longest = max(max(values), -min(values)) if values else 0.0
    if longest <= longest_step and not near_singular:
        stepped = theta - correction
        if limits.contain(stepped.tolist()):
            return stepped, correction, 0.0, total
    step = _within_limits(solver, rows, error, theta, -correction, limits, damping)
    values = step.tolist()
    longest = max(max(values), -min(values)) if values else 0.0
    if longest > longest_step:
        step *= longest_step / longest
    return theta + step, None, 0.0, total


def _within_limits(solver: LeastSquares, rows: FloatArray, error: FloatArray,
                   theta: FloatArray, step: FloatArray, limits: JointLimits, damping: float
                   ) -> FloatArray:
    """``step``, or where it would carry joints past their limits, the step with those
    joints fixed on them and the others solving for the rest (the active set)."""
    lower, upper = limits.lower, limits.upper
    if limits.contain((theta + step).tolist()):
        return step
    free = np.ones(theta.shape[0], dtype=bool)
    step = np.zeros_like(theta)
    remaining = error.copy()
    while free.any():
        columns = np.flatnonzero(free)
        partial = -solver.correction(rows[:, columns], remaining, damping)
        if not np.all(np.abs(partial) < _LARGEST_STEP):
            partial = -solver.correction(rows[:, columns], remaining,
                                         max(damping, _SINGULAR_DAMPING))
        reached = theta[columns] + partial
        crossing = (reached < lower[columns]) | (reached > upper[columns])
        if not crossing.any():
            step[columns] = partial
            break
        stopped = columns[crossing]
        step[stopped] = np.clip(reached[crossing], lower[stopped], upper[stopped]) - theta[stopped]
        remaining += rows[:, stopped].dot(step[stopped])
        free[stopped] = False
    return step
