"""Sampling keyframes at arbitrary times: translation linear, rotation SLERP, held outside.

Times are int64 nanoseconds on one common basis (the caller converts offsets and reference
times before calling). SLERP takes the shortest arc between consecutive keyframes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ._trigonometry import cos_sin
from .rotations import matrix_rows_from_quaternion, quaternion_from_matrix
from .se3 import Transform, to_stacks

__all__ = ["Keyframes", "rotation_steps", "segment_indices", "segment_position",
           "segment_positions"]

_SMALL_ANGLE = 1e-12


def segment_indices(
    keyframe_times: NDArray[np.int64], times: NDArray[np.int64]
) -> NDArray[np.intp]:
    """Per time, the segment it falls in (the one starting at or before it), clamped to the
    first and last segment; at least two keyframes."""
    index = np.searchsorted(keyframe_times, times, side="right") - 1
    # np.minimum/np.maximum: np.clip costs several microseconds more on short arrays.
    np.minimum(np.maximum(index, 0, out=index), keyframe_times.shape[0] - 2, out=index)
    return index


def segment_positions(
    keyframe_times: NDArray[np.int64], times: NDArray[np.int64]
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """Segment index and fraction in [0, 1] of each time; times outside are clamped.

    Returns ``(index, fraction)`` such that a value at ``times[i]`` is
    ``(1 - fraction[i]) * v[index[i]] + fraction[i] * v[index[i] + 1]``.
    For a single keyframe, the index is 0 and the fraction 0.
    """
    if keyframe_times.shape[0] == 1:
        return np.zeros(times.shape, dtype=np.intp), np.zeros(times.shape)
    index = segment_indices(keyframe_times, times)
    start = keyframe_times[index]
    span = (keyframe_times[index + 1] - start).astype(float)
    fraction = (times - start).astype(float) / span
    np.minimum(np.maximum(fraction, 0.0, out=fraction), 1.0, out=fraction)
    return index, fraction


def segment_position(keyframe_times: NDArray[np.int64], time: int) -> tuple[int, float]:
    """:func:`segment_positions` for one ``time`` (ns), in Python numbers: the same segment,
    and the same fraction to the last bit, without arrays of length one."""
    count = keyframe_times.shape[0]
    if count == 1:
        return 0, 0.0
    index = min(max(int(keyframe_times.searchsorted(time, side="right")) - 1, 0), count - 2)
    start, end = keyframe_times[index:index + 2].tolist()
    return index, min(max(float(time - start) / float(end - start), 0.0), 1.0)


@dataclass
class Keyframes:
    """Keyframes of a moving pose, prepared for fast sampling.

    Attributes
    ----------
    times : ndarray of int64, shape (K,)
        Strictly increasing keyframe times, nanoseconds.
    rotations : ndarray, shape (K, 3, 3)
        Rotation matrices.
    translations : ndarray, shape (K, 3)
        Metres.
    """

    times: NDArray[np.int64]
    rotations: NDArray[np.float64]
    translations: NDArray[np.float64]
    _rows: tuple[NDArray[np.float64], ...] | None = field(default=None, repr=False)
    _steps: NDArray[np.float64] | None = field(default=None, repr=False)

    def sample(
        self, times: NDArray[np.int64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Rotation matrices ``(N, 3, 3)`` and translations ``(N, 3)`` at ``times`` (ns)."""
        return to_stacks(self.transform_at(times), times.shape[0])

    def transform_at(self, times: NDArray[np.int64]) -> Transform:
        """The pose at ``times`` (ns), samples last: rotations ``(3, 3, N)``, translations
        ``(3, N)``; static ``(3, 3)`` and ``(3,)`` for a single keyframe."""
        if self.times.shape[0] == 1:
            return self.rotations[0], self.translations[0]
        translations, start, end, angle, inverse_sine, cotangent = self._prepared_rows()
        index, fraction = segment_positions(self.times, times)
        before = 1.0 - fraction
        translation = translations[:, index]
        translation *= before
        translation += fraction * translations[:, index + 1]
        # SLERP weights sin((1 - f) a) / sin(a) = cos(f a) - sin(f a) / tan(a) and
        # sin(f a) / sin(a) per sample
        cosine, weight_end = cos_sin(fraction * angle[index])
        weight_start = weight_end * cotangent[index]
        np.subtract(cosine, weight_start, out=weight_start)
        weight_end *= inverse_sine[index]
        quaternion = start[:, index]
        quaternion *= weight_start
        quaternion += weight_end * end[:, index]
        return matrix_rows_from_quaternion(*quaternion), translation

    def pose_at(self, time: int) -> tuple[list[float], list[float]]:
        """The pose at one ``time`` (ns) in Python floats: translation ``[x, y, z]`` (metres)
        and unit quaternion ``[x, y, z, w]``; :meth:`transform_at`'s interpolation for one
        sample, without numpy calls on arrays of length one."""
        if self.times.shape[0] == 1:
            return (self.translations[0].tolist(),
                    quaternion_from_matrix(self.rotations[0]).tolist())
        translations, start, end, angle, inverse_sine, cotangent = self._prepared_rows()
        index, fraction = segment_position(self.times, time)
        before = 1.0 - fraction
        (x0, x1), (y0, y1), (z0, z1) = translations[:, index:index + 2].tolist()
        # the weights of transform_at: cos(f a) - sin(f a) / tan(a) and sin(f a) / sin(a)
        swept = fraction * float(angle[index])
        sine = math.sin(swept)
        weight_start = math.cos(swept) - sine * float(cotangent[index])
        weight_end = sine * float(inverse_sine[index])
        return ([x0 * before + fraction * x1, y0 * before + fraction * y1,
                 z0 * before + fraction * z1],
                [a * weight_start + weight_end * b
                 for a, b in zip(start[:, index].tolist(), end[:, index].tolist(), strict=True)])

    def rotation_steps(self) -> NDArray[np.float64]:
        """Per segment, the rotation vector of its step, ``(K - 1, 3)`` radians (see
        :func:`rotation_steps`), computed on first use."""
        if self._steps is None:
            self._steps = rotation_steps(self.rotations)
        return self._steps

    def _prepared_rows(self) -> tuple[NDArray[np.float64], ...]:
        """Translations as rows ``(3, K)`` and the SLERP rows of :func:`_prepare_slerp`,
        computed on first use."""
        if self._rows is None:
            self._rows = (np.ascontiguousarray(self.translations.T),
                          *_prepare_slerp(quaternion_from_matrix(self.rotations)))
        return self._rows


def _prepare_slerp(quaternions: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Per segment: start and end quaternion on one hemisphere as rows ``(4, K - 1)``, arc
    angle, 1 / sin(angle), 1 / tan(angle).

    Arcs below ``_SMALL_ANGLE`` are widened to it: there ``sin(f a) / sin(a)`` equals ``f``
    to machine precision, so SLERP becomes the (exact enough) linear blend of two nearly
    equal quaternions, without a branch per sample.
    """
    start = quaternions[:-1]
    end = quaternions[1:].copy()
    dot = np.einsum("ij,ij->i", start, end)
    end[dot < 0.0] *= -1.0
    angle = np.arccos(np.clip(np.abs(dot), 0.0, 1.0))
    angle = np.maximum(angle, _SMALL_ANGLE)
    return (np.ascontiguousarray(start.T), np.ascontiguousarray(end.T), angle,
            1.0 / np.sin(angle), 1.0 / np.tan(angle))


def rotation_steps(rotations: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rotation vectors ``log(R[k+1] @ R[k].T)`` ``(K-1, 3)``, radians, the way SLERP turns.

    From the quaternions ``q[k]`` and ``q[k+1]`` put on one hemisphere (SLERP's rule), the
    step ``q[k+1] * conj(q[k])`` has a non-negative scalar part: its angle is at most pi.
    """
    quaternions = quaternion_from_matrix(rotations)
    start, end = quaternions[:-1], quaternions[1:].copy()
    end[np.einsum("ij,ij->i", start, end) < 0.0] *= -1.0
    v0, w0, v1, w1 = start[:, :3], start[:, 3:], end[:, :3], end[:, 3:]
    vector = w0 * v1 - w1 * v0 + np.cross(v0, v1)
    scalar = np.einsum("ij,ij->i", start, end)
    norm = np.linalg.norm(vector, axis=1)
    # 2 atan2(|v|, w) / |v| is the angle per unit of |v|; it tends to 2 / w as |v| -> 0
    small = norm < 1e-12
    scale = np.where(small, 2.0 / np.maximum(scalar, 1e-300),
                     2.0 * np.arctan2(norm, scalar) / np.where(small, 1.0, norm))
    return vector * scale[:, None]
