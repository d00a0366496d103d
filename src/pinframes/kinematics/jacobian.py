"""``FrameTree.jacobian``: frame Jacobians with respect to the tree's robot joints, per sample.

Column ``k`` is the velocity of ``frame`` relative to ``relative_to`` (as in
:mod:`.velocity`: linear velocity of the origin of ``frame``, then angular velocity, both
in the axes of ``relative_to``) per unit velocity of joint ``k``. A mimic joint adds its
column, times its multiplier, to its primary's. When ``relative_to`` is the root of the
query's model (an ancestor of ``frame``) this is Pinocchio's
``computeFrameJacobian(model, data, q, frame_id, LOCAL_WORLD_ALIGNED)``; otherwise it is
that Jacobian in the model re-rooted at ``relative_to``: joints that move ``relative_to``
count with the opposite sign, about the origin of ``frame``. ``J @ qdot`` is the part of
the velocity that the joints cause; moving (keyframed) frames on the path add the rest.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..values.se3 import IDENTITY
from ..values.timed import Timed
from ._description import TreeDescription
from ._joint_argument import named_joints
from ._plan import plan_query
from ._sampled_path import SampledPath, sampled_parts
from ._sampling import DrivenJoint
from ._twists import Twist, jacobian_columns, joint_signs

__all__ = ["FrameJacobian", "evaluate_jacobian"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class FrameJacobian(Timed):
    """Jacobians of ``frame`` relative to ``relative_to`` per sample.

    Attributes
    ----------
    matrix : ndarray, shape (T, 6, n)
        Rows: linear velocity (m/s) of the origin of ``frame``, then angular velocity
        (rad/s), in the axes of ``relative_to``; per unit velocity of each joint (rad/s or
        m/s).
    joints : tuple of str
        The joint of each column.
    times : ndarray of timedelta64[ns] or None
        Sample times after :attr:`reference_time` (None: a static path without times).
    reference_time : numpy.datetime64 or None
        What :attr:`times` count from.
    """

    matrix: FloatArray
    joints: tuple[str, ...]
    times: NDArray[np.timedelta64] | None
    reference_time: np.datetime64 | None


def evaluate_jacobian(tree: TreeDescription, frame: str, relative_to: str, times: Any,
                      time_ref: Any, extrapolation: str, joints: Sequence[str] | None
                      ) -> FrameJacobian:
    """``tree.jacobian(...)``; frame names already checked."""
    names = ([name for name, joint in tree.joints_by_name.items() if joint.is_actuated]
             if joints is None else named_joints(joints, tree.joints_by_name, frame))
    column_of = {name: column for column, name in enumerate(names)}
    plan = plan_query(tree, frame, relative_to, times, time_ref, extrapolation)
    matrix = np.zeros((plan.count, 6, len(names)))
    if plan.path.model is not None:
        signs = joint_signs(plan.path.model, frame, relative_to)
        for part, path in sampled_parts(plan):
            matrix[part] = _columns_in_reference(path, signs, frame, relative_to, column_of)
    return FrameJacobian(matrix, tuple(names), plan.result_times, plan.reference_time)


def _columns_in_reference(path: SampledPath, signs: dict[int, float], frame: str,
                          relative_to: str, column_of: dict[str, int]) -> FloatArray:
    """``(N, 6, n)`` Jacobians of one chunk, rows in the axes of the reference frame
    (``signs``: :func:`._twists.joint_signs` of the two)."""
    count = path.times.shape[0]
    unit_twists: dict[int, Twist] = {}
    targets: dict[int, tuple[int, float]] = {}
    for position, sampler in enumerate(path.samplers):
        if not isinstance(sampler, DrivenJoint) or position not in signs:
            continue
        column = column_of.get(sampler.primary)
        if column is None:
            continue
        unit_twists[position] = path.unit_twists[position]
        targets[position] = (column, sampler.multiplier)
    root_matrix = np.zeros((count, 6, len(column_of)))
    for position, (linear, angular) in jacobian_columns(signs, path.origins, unit_twists,
                                                        path.placements[frame][1]).items():
        column, multiplier = targets[position]
        root_matrix[:, :3, column] += multiplier * linear
        root_matrix[:, 3:, column] += multiplier * angular
    rotation = path.placements[relative_to][0]
    if rotation is IDENTITY[0]:  # the root's own axes
        return root_matrix
    # R.T @ (3, n) blocks, element by element: row i is sum_j R[j, i] * block[j]
    weights = rotation[..., None] if rotation.ndim == 3 else rotation[None, :, :, None]
    out = np.empty_like(root_matrix)
    for half in (slice(0, 3), slice(3, 6)):
        block = root_matrix[:, half]
        for row in range(3):
            out[:, half.start + row] = (weights[:, 0, row] * block[:, 0]
                                        + weights[:, 1, row] * block[:, 1]
                                        + weights[:, 2, row] * block[:, 2])
    return out
