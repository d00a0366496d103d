"""``FrameTree.ik_solutions``: every solution of a 6-axis arm of a closed-form family
(:mod:`..closed_form`) at every sample, at once.

The arguments are those of ``solve_joints`` and checked the same way; the path is planned as
for ``solve_joints`` (the solved joints held out of the times), the arm recognised from its
screws at zero (:mod:`._closed_form_arm`), and each chunk of samples solved at once.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...values.pose import Pose
from .._description import TreeDescription
from .._joint_argument import named_joints
from .._sampling import KERNEL_CHUNK
from ..closed_form.solutions import IkSolutions, every_solution
from ._closed_form_arm import arm_order, closed_form_arm, flange_motions
from ._path_chunks import TARGET_SOURCE, targets_last
from .solve_joints import _reference, planned_solve

__all__ = ["evaluate_ik_solutions"]


def evaluate_ik_solutions(tree: TreeDescription, frame: str, target: str | Pose, *,
                          relative_to: str | None, times: Any, time_ref: Any, joints: Any,
                          whole_turns: bool) -> IkSolutions:
    """``tree.ik_solutions(...)``; ``frame`` (and a target frame name) already checked."""
    reference, target_pose = _reference(tree, frame, target, relative_to)
    names = None if joints is None else named_joints(joints, tree.joints_by_name, frame)
    path, solved, plan = planned_solve(tree, frame, reference, target_pose, times, time_ref,
                                       names)
    shape = closed_form_arm(path, solved, frame)
    order = arm_order(shape, solved.names)
    lower, upper = solved.limits.lower[order], solved.limits.upper[order]
    moments = plan.sample_times
    shift = plan.shifts.get(TARGET_SOURCE, 0)
    columns: NDArray[np.float64] | None = None  # (T, k, n): every chunk written into it
    valid: NDArray[np.bool_] | None = None
    branches: NDArray[np.str_] | None = None
    for begin in range(0, moments.shape[0], KERNEL_CHUNK):
        chunk = moments[begin:begin + KERNEL_CHUNK]
        motions = flange_motions(path, chunk, plan.shifts, solved.names,
                                 targets_last(target_pose, chunk, shift))
        positions, branches, chunk_valid = every_solution(shape, *motions, lower, upper,
                                                       whole_turns)
        if columns is None or valid is None:
            columns = np.empty((moments.shape[0], *positions.shape[1:]))
            valid = np.empty((moments.shape[0], positions.shape[1]), dtype=bool)
        part = slice(begin, begin + chunk.shape[0])
        if order == sorted(order):
            columns[part] = positions
        else:
            columns[part][..., order] = positions
        valid[part] = chunk_valid
    assert columns is not None and valid is not None and branches is not None
    offsets = np.zeros(1, dtype=np.int64) if plan.offsets is None else plan.offsets
    rotation, translation = flange_motions(path, moments[:1], plan.shifts, solved.names, None)
    return IkSolutions(solved.names, columns, branches, valid,
                       offsets.astype("timedelta64[ns]"), plan.reference_time, shape,
                       (rotation[..., 0].copy(), translation[..., 0].copy()))
