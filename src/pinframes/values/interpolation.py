"""How moving things go between their samples: one class per interpolation scheme.

A scheme is one class holding both what it samples and the exact time derivatives of it:

- :class:`FrameInterpolation` for a moving frame's keyframes; :class:`LinearSlerp` is the
  scheme of every moving frame today: translation linear, rotation by SLERP along the
  shortest arc, held outside the keyframes.
- :class:`JointInterpolation` for a joint's samples; :class:`LinearValues` is the scheme of
  every joint trajectory today: values linear between samples, held outside.

The data record their scheme (:attr:`Keyframes.interpolation`,
``JointTrajectory.interpolation``), and every query, velocity and Jacobian asks the scheme,
so a second scheme (ScLERP along the screw between two poses, a smooth spline) is one new
subclass: its ``transform_at`` / ``pose_at`` / ``rates`` (or ``sample`` / ``value_at`` /
``rates`` for joints), given to ``Keyframes(..., interpolation=...)``. What such a scheme
does not get from this module alone: a way for users to choose it per frame (a ``Pose`` or
``FrameTree`` argument) and a field in the file formats to store the choice.

Times are int64 nanoseconds on one common basis (the caller converts offsets and reference
times before calling); rates are per second.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from ._trigonometry import cos_sin
from .rotations import matrix_rows_from_quaternion, quaternion_from_matrix
from .se3 import IDENTITY, Transform, to_stacks

__all__ = ["DEFAULT_FRAME_INTERPOLATION", "DEFAULT_JOINT_INTERPOLATION", "FrameInterpolation",
           "JointInterpolation", "Keyframes", "LinearSlerp", "LinearValues", "SegmentSearches",
           "Segments",
           "rotation_steps", "segment_indices", "segment_position"]

FloatArray = NDArray[np.float64]
_SMALL_ANGLE = 1e-12
_NS_PER_S = 1e9


def segment_indices(
    sample_times: NDArray[np.int64], times: NDArray[np.int64]
) -> NDArray[np.intp]:
    """Per time, the segment it falls in (the one starting at or before it), clamped to the
    first and last segment; at least two samples."""
    index = np.searchsorted(sample_times, times, side="right") - 1
    # np.minimum/np.maximum: np.clip costs several microseconds more on short arrays.
    np.minimum(np.maximum(index, 0, out=index), sample_times.shape[0] - 2, out=index)
    return index


class Segments:
    """Where ``times`` fall among strictly increasing ``sample_times``: searched once, then
    shared by the values and the rates of everything sampled at those times.

    Attributes
    ----------
    index : ndarray of intp, shape (N,)
        Per time, its segment: the one starting at or before it, clamped to the first and
        last (0 for a single sample).
    """

    __slots__ = ("_fraction", "_inverse_duration", "index", "sample_times", "times")

    def __init__(self, sample_times: NDArray[np.int64], times: NDArray[np.int64]) -> None:
        self.sample_times = sample_times
        self.times = times
        self.index = (np.zeros(times.shape, dtype=np.intp) if sample_times.shape[0] == 1
                      else segment_indices(sample_times, times))
        self._fraction: FloatArray | None = None
        self._inverse_duration: FloatArray | None = None

    @property
    def fraction(self) -> FloatArray:
        """Per time, the part of its segment passed, in [0, 1] (clamped outside the samples;
        0 for a single sample): a value at ``times[i]`` is ``(1 - f) v[i0] + f v[i0 + 1]``."""
        if self._fraction is None:
            sample_times, index = self.sample_times, self.index
            if sample_times.shape[0] == 1:
                self._fraction = np.zeros(self.times.shape)
            else:
                start = sample_times[index]
                span = (sample_times[index + 1] - start).astype(float)
                fraction = (self.times - start).astype(float) / span
                np.minimum(np.maximum(fraction, 0.0, out=fraction), 1.0, out=fraction)
                self._fraction = fraction
        return self._fraction

    @property
    def inverse_duration(self) -> FloatArray:
        """Per time, ``1 / duration`` of its segment in 1/s, and 0 where the value is held
        (outside the samples; a single sample)."""
        if self._inverse_duration is None:
            sample_times, index, times = self.sample_times, self.index, self.times
            if sample_times.shape[0] == 1:
                self._inverse_duration = np.zeros(times.shape)
            else:
                # the spans of the segments used, not of all of them: a query in chunks must
                # not pay for every sample in every chunk
                inverse = _NS_PER_S / (sample_times[index + 1] - sample_times[index]).astype(float)
                inverse[(times < sample_times[0]) | (times > sample_times[-1])] = 0.0
                self._inverse_duration = inverse
        return self._inverse_duration


class SegmentSearches:
    """Where one set of times (a query's timeline basis, ns) falls among the samples of
    the moving things it takes: one :class:`Segments` per moving frame and one per group
    of driven joints with equal sample times, shared by everything taken at those times
    (poses, joint values, and their rates).

    ``shifts`` holds, per moving thing, what to subtract from a timeline time to land on its
    own time basis.

    Attributes
    ----------
    times : ndarray of int64 or None
        The times; None for a path on which nothing is sampled.
    """

    __slots__ = ("_found", "_shifts", "times")

    def __init__(self, times: NDArray[np.int64] | None, shifts: Mapping[str, int]) -> None:
        self.times = times
        self._shifts = shifts
        self._found: dict[tuple[str, str], Segments] = {}

    def of_frame(self, frame: str, keyframe_times: NDArray[np.int64]) -> Segments:
        """The times among the keyframes of the moving frame ``frame`` (its own basis)."""
        return self._search(("frame", frame), frame, keyframe_times)

    def of_joints(self, time_group: str, joint: str, sample_times: NDArray[np.int64]
                  ) -> Segments:
        """The times among the samples of the driven ``joint`` of ``time_group`` (joints
        whose trajectories share their times; its own basis)."""
        return self._search(("joints", time_group), joint, sample_times)

    def _search(self, key: tuple[str, str], source: str, sample_times: NDArray[np.int64]
                ) -> Segments:
        found = self._found.get(key)
        if found is None:
            assert self.times is not None  # a moving thing is sampled: the query has times
            found = self._found[key] = Segments(sample_times, self.times - self._shifts[source])
        return found


def segment_position(sample_times: NDArray[np.int64], time: int) -> tuple[int, float]:
    """:class:`Segments` for one ``time`` (ns), in Python numbers: the same segment, and
    the same fraction to the last bit, without arrays of length one."""
    count = sample_times.shape[0]
    if count == 1:
        return 0, 0.0
    index = min(max(int(sample_times.searchsorted(time, side="right")) - 1, 0), count - 2)
    start, end = sample_times[index:index + 2].tolist()
    return index, min(max(float(time - start) / float(end - start), 0.0), 1.0)


class FrameInterpolation(ABC):
    """A scheme for a moving frame: its pose between keyframes, and the exact rates of it.

    One instance per :class:`Keyframes` (made on first use, so it may prepare and keep what
    its sampling needs). Outside the keyframes a pose is held, so its rates are zero. A
    scheme must be invariant under a static transform on the left (interpolating keyframes
    written in another frame gives the same motion written there): queries fold a static
    placement into the keyframes once (:meth:`Keyframes.placed`).
    """

    largest_uniform_turn: ClassVar[float]
    """Keyframes a turn about one axis apart are joined by a turn at constant rate about that
    axis when the turn is below this angle (radians): how densely a writer must key a
    turning joint to store it as keyframes."""

    def __init__(self, keyframes: Keyframes) -> None:
        self.keyframes = keyframes

    @abstractmethod
    def transform_at(self, times: NDArray[np.int64], segments: Segments | None = None
                     ) -> Transform:
        """The pose at ``times`` (ns), samples last: rotations ``(3, 3, N)``, translations
        ``(3, N)``; static ``(3, 3)`` and ``(3,)`` for a single keyframe. ``segments`` may
        pass ``Segments(keyframes.times, times)`` when the caller has it."""

    @abstractmethod
    def pose_at(self, time: int) -> tuple[list[float], list[float]]:
        """The pose at one ``time`` (ns) in Python floats: translation ``[x, y, z]`` (metres)
        and unit quaternion ``[x, y, z, w]``, as :meth:`transform_at` gives it."""

    @abstractmethod
    def rates(self, times: NDArray[np.int64], segments: Segments | None = None
              ) -> tuple[FloatArray, FloatArray]:
        """Linear ``(N, 3)`` m/s and angular ``(N, 3)`` rad/s velocity at ``times`` (ns),
        both in the keyframes' reference frame: the derivative of the translation, and
        ``w`` with ``dR/dt = [w]x @ R``."""


class LinearSlerp(FrameInterpolation):
    """Translation linear and rotation by SLERP (the shortest arc) between keyframes.

    Both move at a constant velocity on each segment: ``(t1 - t0) / dt`` and
    ``log(R1 @ R0.T) / dt``. At a keyframe the rate is that of the segment starting there; at
    the last keyframe, that of the segment ending there. A static factor on the left commutes
    with both, and a turn about one axis by less than half a turn is SLERP's own path.
    """

    largest_uniform_turn = math.pi

    def __init__(self, keyframes: Keyframes) -> None:
        super().__init__(keyframes)
        self._rows: tuple[FloatArray, ...] | None = None
        self._steps: FloatArray | None = None

    def transform_at(self, times: NDArray[np.int64], segments: Segments | None = None
                     ) -> Transform:
        keyframes = self.keyframes
        if keyframes.times.shape[0] == 1:
            return keyframes.rotations[0], keyframes.translations[0]
        translations, start, end, angle, inverse_sine, cotangent = self._prepared_rows()
        if segments is None:
            segments = Segments(keyframes.times, times)
        index, fraction = segments.index, segments.fraction
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
        keyframes = self.keyframes
        if keyframes.times.shape[0] == 1:
            return (keyframes.translations[0].tolist(),
                    quaternion_from_matrix(keyframes.rotations[0]).tolist())
        translations, start, end, angle, inverse_sine, cotangent = self._prepared_rows()
        index, fraction = segment_position(keyframes.times, time)
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

    def rates(self, times: NDArray[np.int64], segments: Segments | None = None
              ) -> tuple[FloatArray, FloatArray]:
        keyframes = self.keyframes
        if keyframes.times.shape[0] == 1:
            return np.zeros((times.shape[0], 3)), np.zeros((times.shape[0], 3))
        if segments is None:
            segments = Segments(keyframes.times, times)
        index, inverse = segments.index, segments.inverse_duration
        translations = keyframes.translations
        return ((translations[index + 1] - translations[index]) * inverse[:, None],
                self._rotation_steps()[index] * inverse[:, None])

    def _rotation_steps(self) -> FloatArray:
        """Per segment, the rotation vector of its step, ``(K - 1, 3)`` radians (see
        :func:`rotation_steps`), computed on first use."""
        if self._steps is None:
            self._steps = rotation_steps(self.keyframes.rotations)
        return self._steps

    def _prepared_rows(self) -> tuple[FloatArray, ...]:
        """Translations as rows ``(3, K)`` and the SLERP rows of :func:`_prepare_slerp`,
        computed on first use."""
        if self._rows is None:
            keyframes = self.keyframes
            self._rows = (np.ascontiguousarray(keyframes.translations.T),
                          *_prepare_slerp(quaternion_from_matrix(keyframes.rotations)))
        return self._rows


def _prepare_slerp(quaternions: FloatArray) -> tuple[FloatArray, ...]:
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


def rotation_steps(rotations: FloatArray) -> FloatArray:
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


DEFAULT_FRAME_INTERPOLATION: type[FrameInterpolation] = LinearSlerp
"""The scheme of keyframes that name none: every moving frame read or built today."""


@dataclass
class Keyframes:
    """Keyframes of a moving pose and the scheme that goes between them.

    Attributes
    ----------
    times : ndarray of int64, shape (K,)
        Strictly increasing keyframe times, nanoseconds.
    rotations : ndarray, shape (K, 3, 3)
        Rotation matrices.
    translations : ndarray, shape (K, 3)
        Metres.
    interpolation : type of FrameInterpolation
        The scheme (default :class:`LinearSlerp`).
    """

    times: NDArray[np.int64]
    rotations: FloatArray
    translations: FloatArray
    interpolation: type[FrameInterpolation] = DEFAULT_FRAME_INTERPOLATION
    _scheme: FrameInterpolation | None = field(default=None, repr=False, compare=False)

    def scheme(self) -> FrameInterpolation:
        """The scheme's instance for these keyframes, made on first use."""
        if self._scheme is None:
            self._scheme = self.interpolation(self)
        return self._scheme

    def sample(self, times: NDArray[np.int64]) -> tuple[FloatArray, FloatArray]:
        """Rotation matrices ``(N, 3, 3)`` and translations ``(N, 3)`` at ``times`` (ns)."""
        return to_stacks(self.scheme().transform_at(times), times.shape[0])

    def transform_at(self, times: NDArray[np.int64], segments: Segments | None = None
                     ) -> Transform:
        """See :meth:`FrameInterpolation.transform_at`."""
        return self.scheme().transform_at(times, segments)

    def pose_at(self, time: int) -> tuple[list[float], list[float]]:
        """See :meth:`FrameInterpolation.pose_at`."""
        return self.scheme().pose_at(time)

    def rates(self, times: NDArray[np.int64], segments: Segments | None = None
              ) -> tuple[FloatArray, FloatArray]:
        """See :meth:`FrameInterpolation.rates`."""
        return self.scheme().rates(times, segments)

    def placed(self, placement: Transform) -> Keyframes:
        """Keyframes of ``placement @ pose`` with the same scheme: since every scheme
        commutes with a static factor on the left, applying it to the keyframes once gives
        the same poses and rates as applying it to every sample."""
        if placement is IDENTITY:
            return self
        rotation, translation = placement
        return Keyframes(self.times, rotation @ self.rotations,
                         self.translations @ rotation.T + translation, self.interpolation)


class JointInterpolation(ABC):
    """A scheme for a joint's samples: its value between them, and the exact rate of it.

    One instance per joint trajectory (made on first use). Outside the samples a value is
    held, so its rate is zero. Values are radians or metres, rates per second.
    """

    def __init__(self, times: NDArray[np.int64], values: FloatArray) -> None:
        self.times = times
        self.values = values

    @abstractmethod
    def sample(self, times: NDArray[np.int64], segments: Segments | None = None) -> FloatArray:
        """Values ``(N,)`` at ``times`` (ns); ``segments`` may pass
        ``Segments(self.times, times)`` when the caller has it."""

    @abstractmethod
    def value_at(self, time: int, position: tuple[int, float] | None = None) -> float:
        """The value at one ``time`` (ns) in Python floats, as :meth:`sample` gives it;
        ``position`` may pass ``segment_position(self.times, time)``."""

    @abstractmethod
    def rates(self, times: NDArray[np.int64], segments: Segments | None = None) -> FloatArray:
        """Rates ``(N,)`` at ``times`` (ns), per second."""


class LinearValues(JointInterpolation):
    """Values linear between samples: a constant rate ``(q1 - q0) / dt`` on each segment (at
    a sample, that of the segment starting there; at the last, of the one ending there)."""

    def sample(self, times: NDArray[np.int64], segments: Segments | None = None) -> FloatArray:
        values = self.values
        if values.shape[0] == 1:
            return np.full(times.shape, values[0])
        if segments is None:
            segments = Segments(self.times, times)
        index, fraction = segments.index, segments.fraction
        return (1.0 - fraction) * values[index] + fraction * values[index + 1]

    def value_at(self, time: int, position: tuple[int, float] | None = None) -> float:
        values = self.values
        if values.shape[0] == 1:
            return float(values[0])
        index, fraction = position or segment_position(self.times, time)
        first, second = values[index:index + 2].tolist()
        return (1.0 - fraction) * first + fraction * second

    def rates(self, times: NDArray[np.int64], segments: Segments | None = None) -> FloatArray:
        values = self.values
        if values.shape[0] == 1:
            return np.zeros(times.shape)
        if segments is None:
            segments = Segments(self.times, times)
        index = segments.index
        return (values[index + 1] - values[index]) * segments.inverse_duration


DEFAULT_JOINT_INTERPOLATION: type[JointInterpolation] = LinearValues
"""The scheme of joint trajectories that name none: every trajectory read or built today."""
