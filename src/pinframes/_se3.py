"""Rigid transforms as ``(rotation, translation)`` pairs, batched over time.

A rotation is ``(3, 3)`` (static) or ``(N, 3, 3)`` (one per sample); a translation is
``(3,)`` or ``(N, 3)``. Static and batched parts mix freely.

No kernel here hands BLAS a large product with an inner dimension of 3: OpenBLAS splits such
products across threads, and beside one busy process they ran 3-25x slower than with one
thread. Rotations multiply as stacks of 3 x 3 matrices (``np.matmul`` calls one small,
single-threaded product per sample), vectors rotate with ``np.einsum`` (numpy's own loops).
Measured with one thread and with the default threads next to a spinning process
(benchmarks/README.md).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["IDENTITY", "Transform", "canonical", "compose", "inverse"]

FloatArray = NDArray[np.float64]
Transform = tuple[FloatArray, FloatArray]
IDENTITY: Transform = (np.eye(3), np.zeros(3))
"""The identity; :func:`compose` skips it by object identity, so share this one object."""


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
    """Products of rotation matrices, static or batched, as stacked 3 x 3 products."""
    return np.matmul(left, right)


def _apply(rotation: FloatArray, vector: FloatArray) -> FloatArray:
    """Rotated vectors ``R @ v`` for static or batched ``R`` and ``v``."""
    if vector.ndim == 1:
        return np.matmul(rotation, vector)
    if rotation.ndim == 2:
        return np.einsum("ij,nj->ni", rotation, vector)
    return np.einsum("nij,nj->ni", rotation, vector)
