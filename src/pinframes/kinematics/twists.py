"""Velocities and Jacobians of one frame relative to another, from a compiled model.

A query path is compiled into a model rooted at the lowest common ancestor ``C`` of the
frame ``A`` and the reference frame ``B``; every joint of it moves either ``A`` or ``B``.
Each joint ``j`` contributes a twist: the angular velocity ``w_j`` and the velocity ``u_j``
of its origin ``p_j`` that its own motion causes, written in ``C``'s axes. The velocity of
``A`` relative to ``B`` (as an observer fixed in ``B`` sees it), in ``C``'s axes, is

    w = sum_A w_j - sum_B w_j
    v = sum_A (u_j + w_j x (p_A - p_j)) - sum_B (u_j + w_j x (p_A - p_j))

which equals the derivative of ``R_CB.T @ (p_A - p_B)`` rotated back into ``C``. When ``B``
is ``C`` this is Pinocchio's ``getFrameVelocity(..., LOCAL_WORLD_ALIGNED)`` of ``A``; in
general it is that velocity in a model re-rooted at ``B``. A robot joint's Jacobian column
is the same twist per unit of joint velocity.

Arrays are batched over samples ``(N, 3)`` / ``(N, 3, 3)`` or static ``(3,)`` / ``(3, 3)``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from .._se3 import Transform
from ..joint import Joint
from ..pinocchio_model import CompiledModel

__all__ = ["cross", "jacobian_columns", "joint_signs", "robot_joint_axes", "velocity_sum"]

FloatArray = NDArray[np.float64]
Twist = tuple[FloatArray, FloatArray]
"""``(linear, angular)``: velocity of a point in m/s and angular velocity in rad/s."""


def cross(a: FloatArray, b: FloatArray) -> FloatArray:
    """Cross products ``a x b`` over the last axis, broadcast (faster than ``np.cross``)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def rotate(rotation: FloatArray, vectors: FloatArray) -> FloatArray:
    """``R @ v`` for static or batched ``R`` ``(3, 3)`` / ``(N, 3, 3)`` and ``v`` ``(3,)`` /
    ``(N, 3)``, element by element (no BLAS call with an inner dimension of 3)."""
    return (rotation[..., :, 0] * vectors[..., None, 0] + rotation[..., :, 1]
            * vectors[..., None, 1] + rotation[..., :, 2] * vectors[..., None, 2])


def joint_signs(model: CompiledModel, frame: str, relative_to: str) -> dict[int, float]:
    """Joint index -> +1 for the joints that move ``frame`` in the model's root, -1 for
    those that move ``relative_to`` (no joint moves both: the root is their common
    ancestor)."""
    signs: dict[int, float] = {}
    for name, sign in ((frame, 1.0), (relative_to, -1.0)):
        joint = model.model.frames[model.frame_ids[name]].parentJoint - 1
        while joint >= 0:
            signs[joint] = signs.get(joint, 0.0) + sign
            joint = model.joints[joint].parent
    return {joint: sign for joint, sign in signs.items() if sign}


def robot_joint_axes(joint: Joint, rotation_in_root: FloatArray) -> Twist:
    """The twist per unit of joint velocity of a robot joint, in the root's axes:
    ``(0, R @ axis)`` for a turning joint, ``(R @ axis, 0)`` for a sliding one, where ``R`` is
    the joint frame's rotation in the root."""
    axis = np.asarray(joint.axis)
    aligned = np.flatnonzero(axis == 1.0)
    if aligned.size:  # a unit axis picks a column of R
        turned = rotation_in_root[..., :, int(aligned[0])]
    else:
        turned = rotate(rotation_in_root, axis)
    zero = np.zeros(turned.shape)
    return (turned, zero) if joint.kind == "prismatic" else (zero, turned)


def velocity_sum(
    signs: dict[int, float], joint_origins: Sequence[FloatArray],
    twists: Sequence[Twist | None], point: FloatArray,
) -> Twist:
    """``(v, w)`` of the formula above at ``point`` (``p_A``), in the root's axes.

    ``twists[j]`` is joint ``j``'s ``(u_j, w_j)``, or None when it does not move;
    ``joint_origins[j]`` is ``p_j``. Uses ``sum (u_j - w_j x p_j) + (sum w_j) x p_A``.
    """
    linear: FloatArray | float = 0.0
    angular: FloatArray | float = 0.0
    for joint, sign in signs.items():
        twist = twists[joint]
        if twist is None:
            continue
        u, w = twist
        linear = linear + sign * (u - cross(w, joint_origins[joint]))
        angular = angular + sign * w
    if isinstance(angular, float):
        zero = np.zeros(np.shape(point))
        return zero, zero.copy()
    return linear + cross(angular, point), angular


def jacobian_columns(
    signs: dict[int, float], joint_origins: Sequence[FloatArray],
    unit_twists: dict[int, Twist], point: FloatArray,
) -> dict[int, Twist]:
    """Per robot joint ``j`` of ``unit_twists``: ``(dv/dq_j, dw/dq_j)`` at ``point``."""
    columns = {}
    for joint, (u, w) in unit_twists.items():
        sign = signs.get(joint, 0.0)
        if sign:
            columns[joint] = (sign * (u + cross(w, point - joint_origins[joint])), sign * w)
    return columns


def root_rotations(world: Sequence[Transform], model: CompiledModel) -> list[FloatArray]:
    """Per joint, its parent joint's rotation in the root (the identity at the root)."""
    return [np.eye(3) if joint.parent < 0 else world[joint.parent][0] for joint in model.joints]
