"""Rigid transforms as ``(rotation, translation)`` pairs, batched over time.

A rotation is ``(3, 3)`` (static) or ``(N, 3, 3)`` (one per sample); a translation is
``(3,)`` or ``(N, 3)``. Static and batched parts mix freely; the functions pick the cheapest
numpy route for each combination (a static factor becomes one matrix product over all
samples instead of N small ones).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["IDENTITY", "Transform", "canonical", "compose", "inverse"]

FloatArray = NDArray[np.float64]
Transform = tuple[FloatArray, FloatArray]
IDENTITY: Transform = (np.eye(3), np.zeros(3))
"""The identity; :func:`compose` skips it by object identity, so share this one object."""

_SMALL_BATCH = 64


def canonical(transform: Transform) -> Transform:
    """``transform``, or the shared :data:`IDENTITY` object when it is exactly the identity."""
    rotation, translation = transform
    if (rotation.ndim == 2 and translation.ndim == 1 and not translation.any()
            and np.array_equal(rotation, IDENTITY[0])):
        return IDENTITY
    return transform


def compose(first: Transform, second: Transform) -> Transform:
    """``first @ second``: the pose of C in A from the pose of B in A and of C in B."""
    if first is IDENTITY:
        return second
    if second is IDENTITY:
        return first
    rotation_1, translation_1 = first
    rotation_2, translation_2 = second
    return _rotate(rotation_1, rotation_2), _apply(rotation_1, translation_2) + translation_1


def inverse(transform: Transform) -> Transform:
    """The inverse transform."""
    if transform is IDENTITY:
        return IDENTITY
    rotation, translation = transform
    rotation_t = np.swapaxes(rotation, -1, -2)
    return rotation_t, -_apply(rotation_t, translation)


def _rotate(left: FloatArray, right: FloatArray) -> FloatArray:
    """Products of rotation matrices, with static factors done as one matrix product."""
    if left.ndim == 2 and right.ndim == 3 and right.shape[0] > _SMALL_BATCH:
        # (S @ A[n]) for all n: contract S's columns with A's rows in one BLAS call.
        return np.tensordot(right, left, axes=([1], [1])).transpose(0, 2, 1)
    if left.ndim == 3 and right.ndim == 2 and left.shape[0] > _SMALL_BATCH:
        count = left.shape[0]
        return (np.ascontiguousarray(left).reshape(count * 3, 3) @ right).reshape(count, 3, 3)
    return left @ right


def _apply(rotation: FloatArray, vector: FloatArray) -> FloatArray:
    """Rotated vectors ``R @ v`` for static or batched ``R`` and ``v``."""
    if rotation.ndim == 2:
        return vector @ rotation.T
    if vector.ndim == 1:
        return rotation @ vector
    return (rotation[:, :, 0] * vector[:, 0, None] + rotation[:, :, 1] * vector[:, 1, None]
            + rotation[:, :, 2] * vector[:, 2, None])
