"""Rigid transforms as ``(rotation, translation)`` pairs, batched over time, samples last.

A rotation is ``(3, 3)`` (static) or ``(3, 3, N)`` (one per sample); a translation is
``(3,)`` or ``(3, N)``. Static and batched parts mix freely.

The sample axis comes last so that every kernel is a handful of element-wise numpy passes
over long contiguous rows (``R[i, j]`` is one row of N numbers): a product of two rotation
stacks is three broadcast multiplies and two sums, about 3x faster than ``np.matmul`` over
(N, 3, 3) stacks, which calls one tiny BLAS product per sample. No kernel here hands BLAS a
product with an inner dimension of 3 (OpenBLAS threads those, and beside one busy process
they ran 3-25x slower than with one thread). Measured in benchmarks/ with one thread and with
the default threads beside a spinning process.

Static factors (joint placements, frame offsets) of real robots are mostly zeros and ones:
their joints sit at right angles. From a few hundred samples on, a product with a static
factor takes only its significant terms, so an axis-aligned placement costs a few copies,
and :func:`turned` applies a turn about a coordinate axis by mixing two columns: a Panda's
forward kinematics runs about 3x faster than with full products. :func:`samples_last` and
:func:`samples_first` convert from and to the ``(N, 3, 3)`` / ``(N, 3)`` stacks a
:class:`~pinframes.values.pose.Pose` holds; :func:`to_stacks` writes a result into them.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import NDArray

from ._readonly import readonly

__all__ = [
    "IDENTITY",
    "Transform",
    "canonical",
    "compose",
    "inverse",
    "rotated_vector",
    "rotation_product",
    "rotations_first",
    "samples_first",
    "samples_last",
    "to_stacks",
    "turned",
    "vectors_first",
]

FloatArray = NDArray[np.float64]
Transform = tuple[FloatArray, FloatArray]
IDENTITY: Transform = (readonly(np.eye(3)), readonly(np.zeros(3)))
"""The identity; :func:`compose` skips it by object identity, so share this one object
(read-only: queries hand its arrays out)."""


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
    return (rotation_product(rotation_1, rotation_2),
            _add(rotated_vector(rotation_1, translation_2), translation_1))


def inverse(transform: Transform) -> Transform:
    """The inverse transform."""
    if transform is IDENTITY:
        return IDENTITY
    rotation, translation = transform
    rotation_t = np.swapaxes(rotation, 0, 1)
    return rotation_t, -rotated_vector(rotation_t, translation)


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


def rotations_first(rotation: FloatArray) -> FloatArray:
    """A ``(N, 3, 3)`` view of ``(3, 3, N)`` rotations; a static one stays the same object
    (the shared identity is still recognised)."""
    return np.moveaxis(rotation, -1, 0) if rotation.ndim == 3 else rotation


def vectors_first(vector: FloatArray) -> FloatArray:
    """A ``(N, 3)`` view of ``(3, N)`` vectors; a static one stays as it is."""
    return vector.T if vector.ndim == 2 else vector


def to_stacks(transform: Transform, count: int) -> Transform:
    """``(N, 3, 3)`` rotations and ``(N, 3)`` translations (new arrays) of ``count`` samples."""
    rotation, translation = transform
    rotations = np.empty((count, 3, 3))
    translations = np.empty((count, 3))
    rotations[...] = rotation.transpose(2, 0, 1) if rotation.ndim == 3 else rotation
    translations[...] = translation.T
    return rotations, translations


def rotation_product(left: FloatArray, right: FloatArray) -> FloatArray:
    """``left @ right`` for static ``(3, 3)`` or batched ``(3, 3, N)`` rotations (or any
    3 x 3 matrices, such as a cross-product matrix)."""
    if left.ndim == 2 and right.ndim == 2:
        return left @ right
    if right.ndim == 2 and left.shape[2] >= _TERMS_FROM:
        out = np.empty(left.shape)  # column k: the columns of left, weighted
        for k, terms in enumerate(_significant_terms(right.T)):
            _weighted_sum([left[:, j] for j, _ in terms], [c for _, c in terms], out[:, k])
        return out
    if left.ndim == 2 and right.shape[2] >= _TERMS_FROM:
        out = np.empty(right.shape)  # row i: the rows of right, weighted
        for i, terms in enumerate(_significant_terms(left)):
            _weighted_sum([right[j] for j, _ in terms], [c for _, c in terms], out[i])
        return out
    if left.ndim == 2:
        left = left[:, :, None]
    if right.ndim == 2:
        right = right[:, :, None]
    # out[i, k] = sum_j left[i, j] * right[j, k], each term a (3, 3, N) broadcast product
    out = left[:, 0, None] * right[None, 0]
    out += left[:, 1, None] * right[None, 1]
    out += left[:, 2, None] * right[None, 2]
    return out


def rotated_vector(rotation: FloatArray, vector: FloatArray) -> FloatArray:
    """``R @ v`` for static or batched ``R`` ``(3, 3[, N])`` and ``v`` ``(3[, N])``."""
    if rotation.ndim == 2 and vector.ndim == 1:
        return rotation @ vector
    if vector.ndim == 1 and rotation.shape[2] >= _TERMS_FROM:
        out = np.empty(rotation.shape[::2])  # the columns of R, weighted by v
        (terms,) = _significant_terms(vector[None])
        _weighted_sum([rotation[:, j] for j, _ in terms], [c for _, c in terms], out)
        return out
    if rotation.ndim == 2 and vector.shape[1] >= _TERMS_FROM:
        out = np.empty(vector.shape)
        for i, terms in enumerate(_significant_terms(rotation)):
            _weighted_sum([vector[j] for j, _ in terms], [c for _, c in terms], out[i])
        return out
    if rotation.ndim == 2:
        rotation = rotation[:, :, None]
    elif vector.ndim == 1:
        vector = vector[:, None]
    out = rotation[:, 0] * vector[0]
    out += rotation[:, 1] * vector[1]
    out += rotation[:, 2] * vector[2]
    return out


def turned(rotation: FloatArray, axis: int, cosine: FloatArray | float,
           sine: FloatArray | float) -> FloatArray:
    """``rotation @ R(theta)``, ``R`` the turn by theta about coordinate axis ``axis``
    (0, 1, 2 for x, y, z), from ``cos(theta)`` and ``sin(theta)`` (floats or ``(N,)``).

    The turn mixes two columns of ``rotation`` and keeps the third: four products per
    entry row instead of a full matrix product.
    """
    first, second = (axis + 1) % 3, (axis + 2) % 3  # R e_first = c e_first + s e_second
    if rotation.ndim == 2 and np.ndim(cosine) == 0:
        turn = np.eye(3)
        turn[[first, second, first, second], [first, second, second, first]] = (
            cosine, cosine, -sine, sine)
        return rotation @ turn
    column_1, column_2 = rotation[:, first], rotation[:, second]
    kept = rotation[:, axis]
    if rotation.ndim == 2:
        column_1, column_2, kept = column_1[:, None], column_2[:, None], kept[:, None]
    out = np.empty((3, 3, max(column_1.shape[1], np.size(cosine))))
    np.multiply(column_1, cosine, out=out[:, first])
    out[:, first] += column_2 * sine
    np.multiply(column_2, cosine, out=out[:, second])
    out[:, second] -= column_1 * sine
    out[:, axis] = kept
    return out


def _add(left: FloatArray, right: FloatArray) -> FloatArray:
    """``left + right`` for static ``(3,)`` or batched ``(3, N)`` vectors."""
    if left.ndim == right.ndim:
        return left + right
    return left[:, None] + right if left.ndim == 1 else left + right[:, None]


_NEGLIGIBLE = float(np.finfo(float).eps)
_TERMS_FROM = 256
"""Samples from which a product with a static factor takes only its significant terms;
below, five broadcast operations cost less than the Python that picks the terms (the two
met at 256 samples: a rotation and a vector product, 15 us either way)."""


def _significant_terms(matrix: FloatArray) -> tuple[tuple[tuple[int, float], ...], ...]:
    """Per row of a static ``(rows, 3)`` matrix of coefficients, the ``(index,
    coefficient)`` pairs that count (see :func:`_terms_of_rows`), remembered by the
    coefficients: the same joint placements meet every query, and picking their terms in
    Python took 7 us per product."""
    return _terms_of_rows(tuple(matrix.ravel().tolist()), matrix.shape[1])


@lru_cache(maxsize=4096)
def _terms_of_rows(coefficients: tuple[float, ...], width: int
                   ) -> tuple[tuple[tuple[int, float], ...], ...]:
    """Per row of ``width`` coefficients (``coefficients`` row by row), the ``(index,
    coefficient)`` pairs that count.

    A coefficient at most machine epsilon times the largest of its row is dropped: its term
    lies within one rounding of the sum. Exact zeros go too, and so does the rounding residue
    that right angles leave in placements (cos(pi/2) read from a URDF is 2e-16, not 0), so a
    product with an axis-aligned placement is a few copies instead of 27 products.
    """
    significant = []
    for start in range(0, len(coefficients), width):
        row = coefficients[start:start + width]
        largest = max(abs(c) for c in row)
        significant.append(tuple((j, c) for j, c in enumerate(row)
                                 if abs(c) > _NEGLIGIBLE * largest))
    return tuple(significant)


def _weighted_sum(arrays: list[FloatArray], weights: list[float], out: FloatArray) -> None:
    """``out[...] = sum(w * a)``; a weight of +-1 costs a copy or a negation, no product."""
    if not arrays:
        out[...] = 0.0
        return
    for position, (array, weight) in enumerate(zip(arrays, weights, strict=True)):
        if position == 0:
            if weight == 1.0:
                np.copyto(out, array)
            elif weight == -1.0:
                np.negative(array, out=out)
            else:
                np.multiply(array, weight, out=out)
        elif weight == 1.0:
            out += array
        elif weight == -1.0:
            out -= array
        else:
            out += array * weight
