"""Sampling keyframes at arbitrary times: translation linear, rotation SLERP, held outside.

Times are int64 nanoseconds on one common basis (the caller converts offsets and reference
times before calling). SLERP takes the shortest arc between consecutive keyframes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .rotations import matrix_from_quaternion, quaternion_from_matrix

__all__ = ["Keyframes", "segment_positions"]

_SMALL_ANGLE = 1e-12


def segment_positions(
    keyframe_times: NDArray[np.int64], times: NDArray[np.int64]
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """Segment index and fraction in [0, 1] of each time; times outside are clamped.

    Returns ``(index, fraction)`` such that a value at ``times[i]`` is
    ``(1 - fraction[i]) * v[index[i]] + fraction[i] * v[index[i] + 1]``.
    For a single keyframe, the index is 0 and the fraction 0.
    """
    count = keyframe_times.shape[0]
    if count == 1:
        return np.zeros(times.shape, dtype=np.intp), np.zeros(times.shape)
    index = np.searchsorted(keyframe_times, times, side="right") - 1
    # np.minimum/np.maximum: np.clip costs several microseconds more on short arrays.
    np.minimum(np.maximum(index, 0, out=index), count - 2, out=index)
    start = keyframe_times[index]
    span = (keyframe_times[index + 1] - start).astype(float)
    fraction = (times - start).astype(float) / span
    np.minimum(np.maximum(fraction, 0.0, out=fraction), 1.0, out=fraction)
    return index, fraction


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
    _slerp: tuple[NDArray[np.float64], ...] | None = field(default=None, repr=False)

    def sample(
        self, times: NDArray[np.int64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Rotation matrices ``(N, 3, 3)`` and translations ``(N, 3)`` at ``times`` (ns)."""
        if self.times.shape[0] == 1:
            count = times.shape[0]
            return (np.broadcast_to(self.rotations[0], (count, 3, 3)).copy(),
                    np.broadcast_to(self.translations[0], (count, 3)).copy())
        index, fraction = segment_positions(self.times, times)
        before = 1.0 - fraction
        translations = (before[:, None] * self.translations[index]
                        + fraction[:, None] * self.translations[index + 1])
        return matrix_from_quaternion(self._slerp_quaternions(index, fraction)), translations

    def _slerp_quaternions(
        self, index: NDArray[np.intp], fraction: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        if self._slerp is None:
            self._slerp = _prepare_slerp(quaternion_from_matrix(self.rotations))
        start, end, angle, inverse_sine = self._slerp
        angle = angle[index]
        inverse_sine = inverse_sine[index]
        swept = fraction * angle
        weight_end = np.sin(swept) * inverse_sine
        weight_start = np.sin(angle - swept) * inverse_sine
        return weight_start[:, None] * start[index] + weight_end[:, None] * end[index]


def _prepare_slerp(quaternions: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Per segment: start and end quaternion on one hemisphere, arc angle, 1 / sin(angle).

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
    return start, end, angle, 1.0 / np.sin(angle)
