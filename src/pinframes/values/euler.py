"""Euler angle sequences, named as scipy and weldx name them.

A sequence is one to three axis letters: lower case (``"xyz"``) rotates about the fixed axes
of the reference frame (extrinsic), upper case (``"XYZ"``) about the axes of the turning frame
(intrinsic). Angles are radians, one per letter, in the order of the letters. Extrinsic
``"xyz"`` by ``(a, b, c)`` is ``R = Rz(c) @ Ry(b) @ Rx(a)``; intrinsic ``"XYZ"`` is
``R = Rx(a) @ Ry(b) @ Rz(c)``. Every function takes stacks: angles of shape ``(..., n)``.
"""

from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidPoseError
from .rotations import matrix_from_axis_angle, quaternion_from_matrix

__all__ = ["euler_from_matrix", "matrix_from_euler", "parse_sequence"]

FloatArray = NDArray[np.float64]
_AXES = {"x": 0, "y": 1, "z": 2}
_GIMBAL_TOLERANCE = 1e-7


def parse_sequence(sequence: object) -> tuple[tuple[int, ...], bool]:
    """Axis indices of ``sequence`` in the order they are applied, and whether it is
    intrinsic; an :class:`InvalidPoseError` at field ``sequence`` for anything else."""
    if not isinstance(sequence, str) or not 1 <= len(sequence) <= 3:
        raise InvalidPoseError(f"expected one to three axis letters such as 'xyz' or 'ZYZ', "
                               f"got {sequence!r}", field="sequence")
    if not (sequence.islower() or sequence.isupper()) or any(
            letter not in _AXES for letter in sequence.lower()):
        raise InvalidPoseError(
            f"{sequence!r}: use the letters x, y, z, all lower case (extrinsic) or all upper "
            "case (intrinsic)", field="sequence")
    axes = tuple(_AXES[letter] for letter in sequence.lower())
    if any(first == second for first, second in itertools.pairwise(axes)):
        raise InvalidPoseError(f"{sequence!r}: two successive rotations about the same axis",
                               field="sequence")
    return axes, sequence.isupper()


def matrix_from_euler(sequence: str, angles: ArrayLike) -> FloatArray:
    """Rotation matrices ``(..., 3, 3)`` from angles ``(..., n)`` in radians."""
    axes, intrinsic = parse_sequence(sequence)
    theta = np.asarray(angles, dtype=float)
    if theta.ndim == 0 and len(axes) == 1:
        theta = theta[None]
    if theta.ndim == 0 or theta.shape[-1] != len(axes):
        raise InvalidPoseError(f"{sequence!r} needs {len(axes)} angles per rotation, got "
                               f"shape {theta.shape}", field="angles")
    out = np.broadcast_to(np.eye(3), (*theta.shape[:-1], 3, 3)).copy()
    for position, axis in enumerate(axes):
        step = matrix_from_axis_angle(np.eye(3)[axis], theta[..., position])
        # intrinsic: each rotation acts in the turned frame (right); extrinsic: in the fixed
        # frame (left)
        out = out @ step if intrinsic else step @ out
    return out


def euler_from_matrix(sequence: str, matrix: ArrayLike) -> FloatArray:
    """Angles ``(..., 3)`` in radians of a three-axis ``sequence`` from rotation matrices.

    The first and last angles lie in ``[-pi, pi]``; the middle one in ``[0, pi]`` when the
    first and last axes are the same (proper Euler angles), else in ``[-pi/2, pi/2]``. At a
    gimbal lock the rotation has one free angle: the last angle of the sequence is set to 0,
    as scipy does.

    The method is the direct quaternion conversion of Bernardes and Viollet (2022, PLoS ONE
    17(11): e0276302), which treats all 24 sequences alike.
    """
    axes, intrinsic = parse_sequence(sequence)
    if len(axes) != 3:
        raise InvalidPoseError(f"{sequence!r}: angles are read back for three-axis sequences",
                               field="sequence")
    if intrinsic:  # intrinsic ABC equals extrinsic cba with the angles reversed
        axes = axes[::-1]
    i, j, k = axes
    proper = i == k
    if proper:
        k = 3 - i - j
    sign = (i - j) * (j - k) * (k - i) // 2
    q = quaternion_from_matrix(matrix)
    w = q[..., 3]
    if proper:
        a, b, c, d = w, q[..., i], q[..., j], q[..., k] * sign
    else:
        a, b = w - q[..., j], q[..., i] + q[..., k] * sign
        c, d = q[..., j] + w, q[..., k] * sign - q[..., i]
    middle = 2.0 * np.arctan2(np.hypot(c, d), np.hypot(a, b))
    half_sum, half_difference = np.arctan2(b, a), np.arctan2(d, c)
    first = half_sum - half_difference
    last = half_sum + half_difference
    at_zero = np.abs(middle) < _GIMBAL_TOLERANCE
    at_pi = np.abs(middle - np.pi) < _GIMBAL_TOLERANCE
    # at a lock only first + last (middle 0) or first - last (middle pi) is defined; the
    # angle that comes last in the caller's sequence is set to 0
    locked = at_zero | at_pi
    free = np.where(at_zero, 2.0 * half_sum, -2.0 * half_difference)
    if intrinsic:
        last = np.where(locked, np.where(at_zero, free, -free), last)
        first = np.where(locked, 0.0, first)
    else:
        first = np.where(locked, free, first)
        last = np.where(locked, 0.0, last)
    if not proper:
        last = last * sign
        middle = middle - np.pi / 2
    angles = np.stack([first, middle, last], axis=-1)
    angles = (angles + np.pi) % (2.0 * np.pi) - np.pi
    angles[..., 1] = middle  # already in its range; wrapping would move pi to -pi
    return angles[..., ::-1].copy() if intrinsic else angles
