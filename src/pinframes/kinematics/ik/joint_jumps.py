"""Jumps of a joint path: steps between two samples far larger than the path's usual step
(a branch flip, a wrist turned half a turn), found after the solve and raised by
``solve_joints(..., strict=True)``.

A sample's step is the largest change of one solved joint from the sample before (radians,
or metres for a prismatic joint). It jumps where that passes ``factor`` times the median
step of the path and :data:`SMALLEST_JUMP`, as MoveIt's relative ``jump_threshold`` does for
a Cartesian path (with the median, not the mean, so that one jump does not raise its own
bar).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...errors import JointJumpError
from .joint_solution import JointSolution

__all__ = ["DEFAULT_JUMP_FACTOR", "SMALLEST_JUMP", "jump_bar", "jumps_of", "require_no_jumps"]

FloatArray = NDArray[np.float64]

DEFAULT_JUMP_FACTOR = 10.0
"""Times the median step of the path past which a step jumps (``jump_threshold``)."""

SMALLEST_JUMP = 0.1
"""Radians (or metres): a step at most this large never jumps, however still the rest of the
path stands."""


def _steps(positions: FloatArray) -> FloatArray:
    """Per sample after the first, the largest change of one joint from the sample before
    (joint by joint: a maximum across a short last axis is several times slower)."""
    steps = np.zeros(max(positions.shape[0] - 1, 0))
    for joint in range(positions.shape[1]):
        column = positions[:, joint]
        np.maximum(steps, np.abs(column[1:] - column[:-1]), out=steps)
    return steps


def _bar(steps: FloatArray, factor: float) -> float:
    """The jump bar of a path whose :func:`_steps` are ``steps``."""
    usual = float(np.median(steps)) if steps.shape[0] else 0.0
    return max(factor * usual, SMALLEST_JUMP)


def jump_bar(positions: FloatArray, factor: float) -> float:
    """The step (radians or metres) past which a sample of ``positions`` (T, n) jumps."""
    return _bar(_steps(positions), factor)


def jumps_of(positions: FloatArray, factor: float) -> NDArray[np.intp]:
    """The samples of ``positions`` (T, n) whose step from the one before jumps."""
    steps = _steps(positions)
    return np.flatnonzero(steps > _bar(steps, factor)) + 1


def require_no_jumps(solution: JointSolution, factor: float, frame: str) -> None:
    """Raise :class:`~pinframes.errors.JointJumpError` at the first of the solution's
    :attr:`~JointSolution.jumps`, naming the time, the joint that moves most and its step."""
    if solution.jumps is None or not solution.jumps.shape[0]:
        return
    index = int(solution.jumps[0])
    changes = np.abs(solution.positions[index] - solution.positions[index - 1])
    column = int(np.argmax(changes))
    when = solution.when(index)
    raise JointJumpError(
        f"jumps by {changes[column]:.3g} at {when} (sample {index + 1} of {len(solution)}), "
        f"past {jump_bar(solution.positions, factor):.3g} ({factor:g} times the path's "
        f"median step, at least {SMALLEST_JUMP:g}); {solution.jumps.shape[0]} jump(s) in "
        "all", joint=solution.joint_names[column], frame=frame, field="jump_threshold")
