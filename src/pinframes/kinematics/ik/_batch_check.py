"""Measuring many solutions at once: the tool in its target at the samples the solver loop
took as solved without measuring them (a full Newton step from close by, see
:mod:`._newton_tracking`), from one pass of the compiled path's numpy forward kinematics
instead of Pinocchio's sample by sample."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ...values.se3 import Transform, compose, inverse, samples_last, to_stacks
from .._description import TreeDescription
from .._plan import PreparedPath
from .._sampling import sample_joints
from ._tool_error import ToolMatch

__all__ = ["measure_solutions"]

FloatArray = NDArray[np.float64]


def measure_solutions(
    tree: TreeDescription, path: PreparedPath, times: NDArray[np.int64], shifts: dict[str, int],
    joint_names: tuple[str, ...], positions: FloatArray, targets: Transform | None,
    error: ToolMatch,
) -> tuple[FloatArray, FloatArray]:
    """Position (m) and orientation (rad) errors, shape (N,), of the tool of ``path`` with
    the solved joints at ``positions`` (N, n) at ``times`` (timeline basis, ns).

    ``targets``: the targets in the path's reference frame, ``(N, 3, 3)`` rotations and
    ``(N, 3)`` translations (None: the reference frame itself).
    """
    model = path.model
    assert model is not None
    count = times.shape[0]
    held = {name: positions[:, column] for column, name in enumerate(joint_names)}
    samples = sample_joints(path.samplers, times, shifts, held=held)
    tool, reference = model.forward_kinematics(samples, [path.frame, path.relative_to])
    tool_in_target = compose(inverse(reference), tool)
    if targets is not None:
        tool_in_target = compose(inverse(samples_last(targets)), tool_in_target)
    return error.errors(*to_stacks(tool_in_target, count))
