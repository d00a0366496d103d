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

from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from ..values.joint import Joint
from ._model import CompiledModel

__all__ = ["cross", "jacobian_columns", "joint_signs", "robot_joint_axes", "velocity_sum"]

FloatArray = NDArray[np.float64]
Twist = tuple[FloatArray | None, FloatArray | None]
"""``(linear, angular)``: velocity of a point in m/s and angular velocity in rad/s; a None
part is zero."""


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
    ``(None, R @ axis)`` for a turning joint, ``(R @ axis, None)`` for a sliding one (None:
    zero), where ``R`` is the joint frame's rotation in the root."""
    axis = np.asarray(joint.axis)
    aligned = np.flatnonzero(axis == 1.0)
    if aligned.size:  # a unit axis picks a column of R (a copy: a view would hold all of R)
        turned = np.ascontiguousarray(rotation_in_root[..., :, int(aligned[0])])
    else:
        turned = rotate(rotation_in_root, axis)
    return (turned, None) if joint.kind == "prismatic" else (None, turned)


def velocity_sum(
    signs: dict[int, float], joint_origins: Mapping[int, FloatArray],
    twists: Mapping[int, Twist], point: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """``(v, w)`` of the formula above at ``point`` (``p_A``), in the root's axes.

    ``twists[j]`` is joint ``j``'s ``(u_j, w_j)`` (a None part is zero; a joint that does
    not move has none); ``joint_origins[j]`` is ``p_j``. Uses
    ``sum (u_j - w_j x p_j) + (sum w_j) x p_A``.
    """
    linear: FloatArray | None = None
    angular: FloatArray | None = None
    for joint, sign in signs.items():
        twist = twists.get(joint)
        if twist is None:
            continue
        u, w = twist
        if u is not None:
            linear = _accumulate(linear, u, sign)
        if w is not None:
            angular = _accumulate(angular, w, sign)
            linear = _accumulate(linear, cross(w, joint_origins[joint]), -sign)
    if angular is not None:
        linear = _accumulate(linear, cross(angular, point), 1.0)
    zero = np.zeros(np.shape(point))
    return (zero if linear is None else linear), (zero if angular is None else angular)


def jacobian_columns(
    signs: dict[int, float], joint_origins: Mapping[int, FloatArray],
    unit_twists: dict[int, Twist], point: FloatArray,
) -> dict[int, tuple[FloatArray, FloatArray]]:
    """Per robot joint ``j`` of ``unit_twists``: ``(dv/dq_j, dw/dq_j)`` at ``point``."""
    columns = {}
    zero = np.zeros(3)
    for joint, (u, w) in unit_twists.items():
        sign = signs.get(joint, 0.0)
        if not sign:
            continue
        if w is None:
            columns[joint] = (sign * u, zero) if u is not None else (zero, zero)
        else:
            linear = cross(w, point - joint_origins[joint])
            if u is not None:
                linear = linear + u
            columns[joint] = (sign * linear, sign * w)
    return columns


def _accumulate(total: FloatArray | None, value: FloatArray, sign: float) -> FloatArray:
    """``total + sign * value`` (``sign`` is +1 or -1), a new array; None counts as 0."""
    if total is None:
        return value.copy() if sign > 0 else -value
    return total + value if sign > 0 else total - value
