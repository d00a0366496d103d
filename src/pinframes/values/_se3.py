"""Rigid transforms as ``(rotation, translation)`` pairs, batched over time, samples last.

A rotation is ``(3, 3)`` (static) or ``(3, 3, N)`` (one per sample); a translation is
``(3,)`` or ``(3, N)``. Static and batched parts mix freely.

The sample axis comes last so that every kernel is a handful of element-wise numpy passes
over long contiguous rows (``R[i, j]`` is one row of N numbers): a product of two rotation
stacks is three broadcast multiplies and two sums, about 3x faster than ``np.matmul`` over
(N, 3, 3) stacks, which calls one tiny BLAS product per sample. No kernel here hands BLAS a
product with an inner dimension of 3 (OpenBLAS threads those, and beside one busy process
they ran 3-25x slower than with one thread). Measured in benchmarks/ with one thread and with
the default threads beside a spinning process. :func:`samples_last` and
:func:`samples_first` convert from and to the ``(N, 3, 3)`` / ``(N, 3)`` stacks a
:class:`~pinframes.values.pose.Pose` holds; :func:`to_stacks` writes a result into them.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "IDENTITY",
    "Transform",
    "canonical",
    "compose",
    "inverse",
    "samples_first",
    "samples_last",
    "to_stacks",
]

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
    return _rotate(rotation_1, rotation_2), _add(_apply(rotation_1, translation_2),
                                                 translation_1)


def inverse(transform: Transform) -> Transform:
    """The inverse transform."""
    if transform is IDENTITY:
        return IDENTITY
    rotation, translation = transform
    rotation_t = np.swapaxes(rotation, 0, 1)
    return rotation_t, -_apply(rotation_t, translation)


def samples_last(transform: Transform) -> Transform:
    """Views of ``(N, 3, 3)`` / ``(N, 3)`` stacks with the sample axis last; static parts
    unchanged."""
    rotation, translation = transform
    return (rotation.transpose(1, 2, 0) if rotation.ndim == 3 else rotation,
            translation.T if translation.ndim == 2 else translation)


def samples_first(transform: Transform) -> Transform:
    """``(N, 3, 3)`` / ``(N, 3)`` stacks (new arrays) of a samples-last transform; static
    parts unchanged."""
    rotation, translation = transform
    return (np.ascontiguousarray(rotation.transpose(2, 0, 1)) if rotation.ndim == 3
            else rotation,
            np.ascontiguousarray(translation.T) if translation.ndim == 2 else translation)


def to_stacks(transform: Transform, count: int) -> Transform:
    """``(N, 3, 3)`` rotations and ``(N, 3)`` translations (new arrays) of ``count`` samples."""
    rotation, translation = transform
    rotations = np.empty((count, 3, 3))
    translations = np.empty((count, 3))
    rotations[...] = rotation.transpose(2, 0, 1) if rotation.ndim == 3 else rotation
    translations[...] = translation.T
    return rotations, translations


def _add(left: FloatArray, right: FloatArray) -> FloatArray:
    """``left + right`` for static ``(3,)`` or batched ``(3, N)`` vectors."""
    if left.ndim == right.ndim:
        return left + right
    return left[:, None] + right if left.ndim == 1 else left + right[:, None]


def _rotate(left: FloatArray, right: FloatArray) -> FloatArray:
    """Products of rotation matrices, static ``(3, 3)`` or batched ``(3, 3, N)``."""
    if left.ndim == 2 and right.ndim == 2:
        return left @ right
    if left.ndim == 2:
        left = left[:, :, None]
    if right.ndim == 2:
        right = right[:, :, None]
    # out[i, k] = sum_j left[i, j] * right[j, k], each term a (3, 3, N) broadcast product
    out = left[:, 0, None] * right[None, 0]
    out += left[:, 1, None] * right[None, 1]
    out += left[:, 2, None] * right[None, 2]
    return out


def _apply(rotation: FloatArray, vector: FloatArray) -> FloatArray:
    """Rotated vectors ``R @ v`` for static or batched ``R`` ``(3, 3[, N])`` and ``v``
    ``(3[, N])``."""
    if rotation.ndim == 2 and vector.ndim == 1:
        return rotation @ vector
    if rotation.ndim == 2:
        rotation = rotation[:, :, None]
    elif vector.ndim == 1:
        vector = vector[:, None]
    out = rotation[:, 0] * vector[0]
    out += rotation[:, 1] * vector[1]
    out += rotation[:, 2] * vector[2]
    return out
