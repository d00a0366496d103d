"""Exact time derivatives of what queries interpolate, per sample.

Between two keyframes a translation moves linearly and a rotation turns by SLERP, so both
have a constant velocity on each segment: ``(t1 - t0) / dt`` and ``log(R1 @ R0.T) / dt``
(the rotation vector of the step, taken the short way as SLERP does, over the segment's
duration). Joint values move linearly between samples, at ``(q1 - q0) / dt``. Outside the
keyframes a pose or value is held, so its velocity is zero. At a keyframe the velocity is
that of the segment starting there; at the last keyframe, that of the segment ending there.

Times are int64 nanoseconds on the keyframes' own basis; velocities are per second.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..values.interpolation import Keyframes, segment_indices
from ..values.joint_trajectory import JointTrajectory

__all__ = ["keyframe_rates", "segment_rates", "track_rates"]

FloatArray = NDArray[np.float64]
_NS_PER_S = 1e9


def segment_rates(
    keyframe_times: NDArray[np.int64], times: NDArray[np.int64]
) -> tuple[NDArray[np.intp], FloatArray]:
    """Per time: its segment (the one starting at a keyframe; the last one at the last
    keyframe) and ``1 / duration`` of that segment in 1/s, 0 where the value is held."""
    if keyframe_times.shape[0] == 1:
        return np.zeros(times.shape, dtype=np.intp), np.zeros(times.shape)
    index = segment_indices(keyframe_times, times)
    # the spans of the segments used, not of all of them: a query in chunks must not pay
    # for every keyframe in every chunk
    inverse = _NS_PER_S / (keyframe_times[index + 1] - keyframe_times[index]).astype(float)
    held = (times < keyframe_times[0]) | (times > keyframe_times[-1])
    inverse[held] = 0.0
    return index, inverse


def keyframe_rates(keyframes: Keyframes, times: NDArray[np.int64]
                   ) -> tuple[FloatArray, FloatArray]:
    """Linear ``(N, 3)`` m/s and angular ``(N, 3)`` rad/s velocity of a keyframed pose.

    Both are written in the pose's reference frame: the derivative of its translation, and
    the angular velocity ``w`` with ``dR/dt = [w]x @ R``.
    """
    index, inverse = segment_rates(keyframes.times, times)
    if keyframes.times.shape[0] == 1:
        return np.zeros((times.shape[0], 3)), np.zeros((times.shape[0], 3))
    translations = keyframes.translations
    return ((translations[index + 1] - translations[index]) * inverse[:, None],
            keyframes.rotation_steps()[index] * inverse[:, None])


def track_rates(
    track: JointTrajectory, times: NDArray[np.int64],
    segments: tuple[NDArray[np.intp], FloatArray] | None = None,
) -> FloatArray:
    """Joint velocities ``(N,)`` (rad/s or m/s) of a sampled joint trajectory.

    ``segments`` is ``segment_rates(track.times, times)`` when the caller has it already
    (joints driven by one trajectory share their times).
    """
    if track.values.shape[0] == 1:
        return np.zeros(times.shape)
    index, inverse = segment_rates(track.times, times) if segments is None else segments
    values = track.values
    return (values[index + 1] - values[index]) * inverse
