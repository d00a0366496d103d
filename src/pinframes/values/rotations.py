"""Batched rotation conversions.

Every function takes stacks of rotations: arrays whose last axes are ``(4,)`` quaternions
``(x, y, z, w)``, ``(3, 3)`` matrices or ``(3,)`` roll-pitch-yaw angles in radians, with any
leading shape. Roll, pitch and yaw follow URDF: ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "ROTATION_TOLERANCE",
    "matrix_from_axis_angle",
    "matrix_from_axis_vectors",
    "matrix_from_quaternion",
    "matrix_from_rpy",
    "matrix_rows_from_quaternion",
    "quaternion_from_matrix",
    "rotation_matrix_defects",
    "rpy_from_matrix",
    "sign_continuous_quaternions",
]

ROTATION_TOLERANCE = 1e-6
"""Largest accepted deviation of ``R.T @ R`` from the identity, and of ``det(R)`` from 1."""

FloatArray = NDArray[np.float64]


def matrix_from_quaternion(quaternion: ArrayLike) -> FloatArray:
    """Rotation matrices ``(..., 3, 3)`` from unit quaternions ``(..., 4)`` ``(x, y, z, w)``."""
    q = np.asarray(quaternion, dtype=float)
    rows = matrix_rows_from_quaternion(q[..., 0], q[..., 1], q[..., 2], q[..., 3])
    return np.ascontiguousarray(np.moveaxis(rows, (0, 1), (-2, -1)))


def matrix_rows_from_quaternion(
    x: FloatArray, y: FloatArray, z: FloatArray, w: FloatArray
) -> FloatArray:
    """Rotation matrices ``(3, 3, ...)``, matrix axes first, from quaternion components.

    The closed form ``R00 = 1 - 2 (yy + zz)``, ``R01 = 2 (xy - wz)``, ... evaluated entry by
    entry on whole rows of samples: about 20 element-wise passes, the same speed with one
    BLAS thread or many (a matrix product over the 16 component products ran 10x slower
    beside a busy core).
    """
    x2, y2, z2 = x + x, y + y, z + z
    xx, yy, zz = x * x2, y * y2, z * z2
    xy, xz, yz = x * y2, x * z2, y * z2
    wx, wy, wz = w * x2, w * y2, w * z2
    out = np.empty((3, 3, *np.shape(x)))
    np.subtract(1.0, yy + zz, out=out[0, 0, ...])
    np.subtract(xy, wz, out=out[0, 1, ...])
    np.add(xz, wy, out=out[0, 2, ...])
    np.add(xy, wz, out=out[1, 0, ...])
    np.subtract(1.0, xx + zz, out=out[1, 1, ...])
    np.subtract(yz, wx, out=out[1, 2, ...])
    np.subtract(xz, wy, out=out[2, 0, ...])
    np.add(yz, wx, out=out[2, 1, ...])
    np.subtract(1.0, xx + yy, out=out[2, 2, ...])
    return out


def quaternion_from_matrix(matrix: ArrayLike) -> FloatArray:
    """Unit quaternions ``(..., 4)`` ``(x, y, z, w)`` with ``w >= 0`` from rotation matrices.

    Uses the numerically stable branch per matrix (largest diagonal term). The four
    candidates share six sums and differences of opposite entries, built once into one
    ``(4, 4, ...)`` array (half the time of stacking them, the same numbers).
    """
    m = np.asarray(matrix, dtype=float)
    m00, m11, m22 = m[..., 0, 0], m[..., 1, 1], m[..., 2, 2]
    trace = m00 + m11 + m22
    sum_01, sum_02, sum_12 = (m[..., 0, 1] + m[..., 1, 0], m[..., 0, 2] + m[..., 2, 0],
                              m[..., 1, 2] + m[..., 2, 1])
    difference_21, difference_02, difference_10 = (
        m[..., 2, 1] - m[..., 1, 2], m[..., 0, 2] - m[..., 2, 0], m[..., 1, 0] - m[..., 0, 1])
    # Four candidate solutions, each accurate where its leading component is large.
    candidates = np.array([
        [1 + m00 - m11 - m22, sum_01, sum_02, difference_21],
        [sum_01, 1 - m00 + m11 - m22, sum_12, difference_02],
        [sum_02, sum_12, 1 - m00 - m11 + m22, difference_10],
        [difference_21, difference_02, difference_10, 1 + trace],
    ])
    choice = np.argmax(np.array([m00, m11, m22, trace]), axis=0)
    q = np.ascontiguousarray(np.moveaxis(
        np.take_along_axis(candidates, choice[None, None], axis=0)[0], 0, -1))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    return np.where(q[..., 3:4] < 0.0, -q, q)


def sign_continuous_quaternions(quaternions: FloatArray) -> FloatArray:
    """``quaternions`` (4,) or (T, 4) with ``w >= 0`` first, then each one's sign flipped
    where its dot product with the (already flipped) one before it is negative."""
    if quaternions.ndim == 1 or quaternions.shape[0] < 2:
        return quaternions
    dots = np.einsum("ij,ij->i", quaternions[1:], quaternions[:-1])
    signs = np.cumprod(np.concatenate([[1.0], np.where(dots < 0.0, -1.0, 1.0)]))
    return quaternions * signs[:, None]


def matrix_from_rpy(rpy: ArrayLike) -> FloatArray:
    """Rotation matrices ``(..., 3, 3)`` from ``(..., 3)`` roll, pitch, yaw in radians."""
    angles = np.asarray(rpy, dtype=float)
    cr, sr = np.cos(angles[..., 0]), np.sin(angles[..., 0])
    cp, sp = np.cos(angles[..., 1]), np.sin(angles[..., 1])
    cy, sy = np.cos(angles[..., 2]), np.sin(angles[..., 2])
    out = np.empty((*angles.shape[:-1], 3, 3))
    out[..., 0, 0] = cy * cp
    out[..., 0, 1] = cy * sp * sr - sy * cr
    out[..., 0, 2] = cy * sp * cr + sy * sr
    out[..., 1, 0] = sy * cp
    out[..., 1, 1] = sy * sp * sr + cy * cr
    out[..., 1, 2] = sy * sp * cr - cy * sr
    out[..., 2, 0] = -sp
    out[..., 2, 1] = cp * sr
    out[..., 2, 2] = cp * cr
    return out


def rpy_from_matrix(matrix: ArrayLike) -> FloatArray:
    """Roll, pitch, yaw ``(..., 3)`` in radians from rotation matrices.

    Pitch lies in ``[-pi/2, pi/2]``; at the gimbal lock (pitch = +-pi/2) roll is set to 0.
    Near the lock, yaw read from the first column (whose entries are about cos(pitch)) is
    uncertain by about 1e-16 / cos(pitch); roll is therefore read after undoing that yaw,
    from entries of size one (``Rz(yaw)^T R = Ry(pitch) Rx(roll)``, whose middle row is
    ``(0, cos roll, -sin roll)``), so the three angles give back the matrix to rounding
    at any pitch.
    """
    m = np.asarray(matrix, dtype=float)
    column = np.hypot(m[..., 0, 0], m[..., 1, 0])
    pitch = np.arctan2(-m[..., 2, 0], column)
    locked = column < 1e-12
    yaw = np.where(locked, np.arctan2(-m[..., 0, 1], m[..., 1, 1]),
                   np.arctan2(m[..., 1, 0], m[..., 0, 0]))
    cy, sy = np.cos(yaw), np.sin(yaw)
    roll = np.where(locked, 0.0,
                    np.arctan2(sy * m[..., 0, 2] - cy * m[..., 1, 2],
                               cy * m[..., 1, 1] - sy * m[..., 0, 1]))
    return np.stack([roll, pitch, yaw], axis=-1)


def matrix_from_axis_angle(axis: ArrayLike, angle: ArrayLike) -> FloatArray:
    """Rotation matrices ``(..., 3, 3)`` about a unit ``axis`` (3,) by ``angle`` (...) radians."""
    ux, uy, uz = np.asarray(axis, dtype=float)
    theta = np.asarray(angle, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    v = 1.0 - c
    out = np.empty((*theta.shape, 3, 3))
    out[..., 0, 0] = c + ux * ux * v
    out[..., 0, 1] = ux * uy * v - uz * s
    out[..., 0, 2] = ux * uz * v + uy * s
    out[..., 1, 0] = uy * ux * v + uz * s
    out[..., 1, 1] = c + uy * uy * v
    out[..., 1, 2] = uy * uz * v - ux * s
    out[..., 2, 0] = uz * ux * v - uy * s
    out[..., 2, 1] = uz * uy * v + ux * s
    out[..., 2, 2] = c + uz * uz * v
    return out


def rotation_matrix_defects(matrix: ArrayLike) -> tuple[float, float]:
    """Worst ``|R.T @ R - I|`` entry and worst ``|det R - 1|`` over a stack of matrices."""
    m = np.asarray(matrix, dtype=float)
    gram = np.swapaxes(m, -1, -2) @ m
    orthogonality = float(np.max(np.abs(gram - np.eye(3)), initial=0.0))
    determinant = float(np.max(np.abs(np.linalg.det(m) - 1.0), initial=0.0))
    return orthogonality, determinant


def matrix_from_axis_vectors(
    x: ArrayLike | None = None, y: ArrayLike | None = None, z: ArrayLike | None = None
) -> FloatArray:
    """Rotation matrices ``(..., 3, 3)`` whose columns point along two or three given axes.

    Of two given axes the first in ``x, y, z`` order keeps its direction, the second is made
    orthogonal to it (Gram-Schmidt), the third is their right-handed cross product. A third
    given axis must point along that product. Vectors may be ``(3,)`` or stacks ``(..., 3)``;
    their lengths do not matter. Raises ``ValueError`` naming the axis for a zero vector or
    parallel axes.
    """
    given = {name: np.asarray(v, dtype=float) for name, v in (("x", x), ("y", y), ("z", z))
             if v is not None}
    if len(given) < 2:
        raise ValueError("give at least two of the axes x, y, z")
    names = list(given)[:2]
    first = _unit(given[names[0]], names[0])
    second = given[names[1]]
    second = second - np.sum(second * first, axis=-1, keepdims=True) * first
    if np.any(np.linalg.norm(second, axis=-1) <= 1e-9 * np.linalg.norm(given[names[1]], axis=-1)):
        raise ValueError(f"the axes {names[0]} and {names[1]} are parallel")
    second = _unit(second, names[1])
    columns = {names[0]: first, names[1]: second}
    third = next(name for name in "xyz" if name not in columns)
    # x = y × z, y = z × x, z = x × y
    after, before = {"x": ("y", "z"), "y": ("z", "x"), "z": ("x", "y")}[third]
    columns[third] = np.cross(columns[after], columns[before])
    if third in given:
        agreement = np.sum(_unit(given[third], third) * columns[third], axis=-1)
        if np.any(agreement < 1.0 - 1e-6):
            raise ValueError(f"the axis {third} does not point along the right-handed "
                             f"cross product of {names[0]} and {names[1]}")
    return np.stack([columns["x"], columns["y"], columns["z"]], axis=-1)


def _unit(vector: FloatArray, name: str) -> FloatArray:
    norm = np.linalg.norm(vector, axis=-1, keepdims=True)
    if vector.shape[-1:] != (3,) or not np.all(np.isfinite(vector)) or np.any(norm == 0.0):
        raise ValueError(f"the axis {name} must be finite non-zero 3-vectors, got shape "
                         f"{vector.shape}")
    return vector / norm
