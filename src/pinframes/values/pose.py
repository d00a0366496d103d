"""`Pose`: a rigid transform, static or sampled in time.

A pose of frame A in frame B maps coordinates given in A to coordinates in B:
``p_B = R @ p_A + t``. The columns of ``R`` are A's axes written in B; ``t`` is A's origin
in B, in metres.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InvalidPoseError, InvalidTimeError, ReferenceTimeError
from ._readonly import readonly
from ._transform_data import transform_data
from .curve_frames import curve_rotations, length_along_polyline
from .euler import euler_from_matrix, matrix_from_euler
from .interpolation import Keyframes
from .numbers import float_array, require_finite_result
from .quantities import is_quantity, magnitude_in, metres, radians
from .rotations import (
    ROTATION_TOLERANCE,
    matrix_from_axis_vectors,
    matrix_from_quaternion,
    matrix_from_rpy,
    quaternion_from_matrix,
    rotation_matrix_defects,
    rpy_from_matrix,
    sign_continuous_quaternions,
)
from .se3 import compose, inverse, samples_first, samples_last
from .timeconv import (
    TimeAxis,
    anchor_time_axis,
    format_timestamp_iso,
    parse_time_axis,
    parse_timestamp,
    shift_ns,
    timestamp_ns,
)
from .timed import SampledInTime
from .timeline import QueryTimeline, TimedSource, plan_query_timeline
from .weave import Weave

__all__ = ["Pose", "trusted_pose"]

FloatArray = NDArray[np.float64]
_QUATERNION_NORM_TOLERANCE = 1e-3


class Pose(SampledInTime):
    """A rigid transform, static or sampled at strictly increasing times.

    Parameters
    ----------
    translation : array_like, shape (3,) or (T, 3)
        Origin of the frame in its reference frame, metres (or a pint length quantity).
    rotation : None or array_like, shape (3, 3), (T, 3, 3), (4,) or (T, 4)
        Rotation matrix or unit quaternion ``(x, y, z, w)``; None is the identity.
    times : None or sequence of T times
        None for a static pose. Float seconds, ``timedelta64``, ``datetime64``, ISO strings
        or pandas times (see :mod:`pinframes.values.timeconv`).
    reference_time : None or timestamp
        What relative ``times`` count from. Absolute ``times`` set it to their first value
        unless it is given.

    A static translation or rotation broadcasts against a time-dependent other part.
    Poses are immutable: the arrays given are copied, and the arrays a pose hands out
    (``translation``, ``rotation``) are read-only views of its own, so writing into them
    raises numpy's ``ValueError``; copy them (``np.array(pose.translation)``) to edit.
    """

    __slots__ = ("_keyframes", "_rotation", "_translation", "_weave")

    def __init__(
        self,
        translation: ArrayLike = (0.0, 0.0, 0.0),
        rotation: ArrayLike | None = None,
        times: Any = None,
        reference_time: Any = None,
    ) -> None:
        translation_array = _as_float_array(metres(translation, "translation"), "translation")
        rotation_array = _rotation_matrices(magnitude_in(rotation, "dimensionless", "rotation"))
        axis = _time_axis(times, reference_time)
        count = None if axis is None else axis.offsets.shape[0]
        translation_array = _broadcast_part(translation_array, (3,), count, "translation")
        rotation_array = _broadcast_part(rotation_array, (3, 3), count, "rotation")
        # the arrays above are this pose's own copies (np.array and astype copy)
        self._translation = readonly(translation_array)
        self._rotation = readonly(rotation_array)
        self._times = None if axis is None else readonly(axis.offsets)
        self._reference = None if axis is None else axis.reference
        self._keyframes: Keyframes | None = None
        self._weave: Weave | None = None

    # -- construction --------------------------------------------------------------------
    @classmethod
    def _trusted(
        cls,
        rotation: FloatArray,
        translation: FloatArray,
        times: NDArray[np.int64] | None = None,
        reference: np.datetime64 | None = None,
    ) -> Pose:
        """Wrap arrays that are known to be valid, without checks or copies.

        The arrays are marked read-only: they must be new, or already read-only (caches
        and other poses share them); never an array a caller may still write into.
        """
        pose = cls.__new__(cls)
        pose._translation = readonly(translation)
        pose._rotation = readonly(rotation)
        pose._times = None if times is None else readonly(times)
        pose._reference = reference
        pose._keyframes = None
        pose._weave = None
        return pose

    @classmethod
    def identity(cls) -> Pose:
        """The static identity pose."""
        return cls._trusted(np.eye(3), np.zeros(3))

    @classmethod
    def from_matrix(
        cls, matrix: ArrayLike, times: Any = None, reference_time: Any = None
    ) -> Pose:
        """A pose from homogeneous matrices of shape ``(4, 4)`` or ``(T, 4, 4)``."""
        m = _as_float_array(matrix, "matrix")
        if m.shape[-2:] != (4, 4) or m.ndim not in (2, 3):
            raise InvalidPoseError(f"expected shape (4, 4) or (T, 4, 4), got {m.shape}",
                                   field="matrix")
        bottom = m[..., 3, :]
        if not np.allclose(bottom, [0.0, 0.0, 0.0, 1.0], atol=1e-9):
            raise InvalidPoseError("the last row must be (0, 0, 0, 1)", field="matrix")
        return cls(m[..., :3, 3], m[..., :3, :3], times, reference_time)

    @classmethod
    def from_xyz_rpy(
        cls, x: float = 0.0, y: float = 0.0, z: float = 0.0,
        roll: float = 0.0, pitch: float = 0.0, yaw: float = 0.0,
    ) -> Pose:
        """A static pose from a position in metres and roll, pitch, yaw in radians.

        ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``, as in URDF.
        """
        values = _as_float_array([metres(x, "x"), metres(y, "y"), metres(z, "z"),
                                  radians(roll, "roll"), radians(pitch, "pitch"),
                                  radians(yaw, "yaw")], "xyz_rpy")
        return cls._trusted(matrix_from_rpy(values[3:]), values[:3].copy())

    @classmethod
    def from_euler(
        cls, sequence: str, angles: ArrayLike, degrees: bool = False,
        translation: ArrayLike | None = None, times: Any = None, reference_time: Any = None,
    ) -> Pose:
        """A pose from Euler angles, as scipy's and weldx's ``from_euler``.

        ``sequence`` is one to three axis letters, lower case for rotations about the fixed
        axes (extrinsic, ``"xyz"``: ``R = Rz(c) Ry(b) Rx(a)``), upper case about the turning
        axes (intrinsic, ``"XYZ"``: ``R = Rx(a) Ry(b) Rz(c)``). ``angles`` has one value per
        letter, shape ``(n,)`` or ``(T, n)`` with T ``times``; radians unless ``degrees``,
        or a pint quantity of angles in any unit (``degrees`` then does not apply).
        ``translation`` in metres (or a pint length), default the origin.
        """
        if is_quantity(angles):
            theta = _as_float_array(radians(angles, "angles"), "angles")
        else:
            theta = _as_float_array(angles, "angles")
            if degrees:
                theta = np.deg2rad(theta)
        rotation = matrix_from_euler(sequence, theta)
        return cls((0.0, 0.0, 0.0) if translation is None else translation, rotation,
                   times, reference_time)

    def to_euler(self, sequence: str, degrees: bool = False) -> FloatArray:
        """Angles of a three-axis ``sequence`` (see :meth:`from_euler`): ``(3,)`` or ``(T, 3)``.

        Radians unless ``degrees``. First and last angles in ``[-pi, pi]``, the middle in
        ``[0, pi]`` (same first and last axis) or ``[-pi/2, pi/2]``; at a gimbal lock the
        last angle is 0.
        """
        angles = euler_from_matrix(sequence, self._rotation)
        return np.rad2deg(angles) if degrees else angles

    @classmethod
    def from_axis_vectors(
        cls, x: ArrayLike | None = None, y: ArrayLike | None = None,
        z: ArrayLike | None = None, translation: ArrayLike | None = None, times: Any = None,
        reference_time: Any = None,
    ) -> Pose:
        """A pose whose axes point along two (or three) of ``x, y, z``, given in the reference
        frame as ``(3,)`` or ``(T, 3)`` vectors, as weldx's ``from_axis_vectors``.

        The first given axis (in ``x, y, z`` order) keeps its direction, the second is made
        orthogonal to it, the third completes a right-handed frame (a third given axis must
        agree with it). Parallel or zero axes are an :class:`InvalidPoseError`.
        """
        vectors = {name: None if value is None else _as_float_array(value, name)
                   for name, value in (("x", x), ("y", y), ("z", z))}
        try:
            rotation = matrix_from_axis_vectors(**vectors)
        except ValueError as exc:
            named = [name for name in "xyz" if vectors[name] is not None]
            raise InvalidPoseError(str(exc), field=",".join(named)) from None
        return cls((0.0, 0.0, 0.0) if translation is None else translation, rotation,
                   times, reference_time)

    @classmethod
    def along_curve(
        cls, points: ArrayLike, normals: ArrayLike, *, speed: float | None = None,
        times: Any = None, reference_time: Any = None,
    ) -> Pose:
        """A pose moving along the polyline ``points`` (N, 3), metres (or a pint length):
        a seam frame. ``speed`` in m/s (or a pint speed).

        Axes at each point: x the travel direction (the direction there of the parabola
        through the point and its neighbours, parametrised by the length along the chords:
        the three-point non-uniform difference; at the ends that of the parabola through the
        first or last three points), z the point's ``normals`` row ((N, 3), or one (3,)
        normal for all) made perpendicular to x, y = z x x. Give exactly one of ``speed`` (m/s: the
        first point at time 0, each next one after its distance along the polyline) and
        ``times`` (one per point, strictly increasing; any time form, with
        ``reference_time`` as for :class:`Pose`). Between points the pose moves as every
        pose does: the origin linearly, the axes by SLERP.

        Raises :class:`~pinframes.errors.InvalidPoseError` naming the point (``points[3]``,
        ``normals[3]``, ``times[3]``): fewer than 2 points, a point repeating the one before
        it, a curve turning back on itself (within 0.01 degrees of straight back), a normal
        parallel to the travel direction, times that do not increase.
        """
        path = _as_float_array(metres(points, "points"), "points")
        rotation = curve_rotations(
            path, _as_float_array(magnitude_in(normals, "dimensionless", "normals"), "normals"))
        if (speed is None) == (times is None):
            raise InvalidPoseError("give either speed (m/s) or times (one per point)",
                                   field="speed")
        if speed is not None:
            speed = magnitude_in(speed, "meter / second", "speed")
            if (isinstance(speed, bool) or not isinstance(speed, (int, float, np.number))
                    or not (np.isfinite(speed) and speed > 0)):
                raise InvalidPoseError(f"expected a positive speed in m/s, got {speed!r}",
                                       field="speed")
            times = length_along_polyline(path) / float(speed)
        axis = parse_time_axis(times)
        if axis.offsets.shape[0] != path.shape[0]:
            raise InvalidPoseError(f"expected one time per point: {axis.offsets.shape[0]} "
                                   f"times for {path.shape[0]} points", field="times")
        late = np.diff(axis.offsets) <= 0
        if np.any(late):
            index = int(np.argmax(late)) + 1
            raise InvalidPoseError(
                f"point {index} is not after point {index - 1} in time (times must "
                "increase; at a speed, points closer than a nanosecond of travel collide)",
                field=f"times[{index}]")
        return cls(path, rotation, times, reference_time)

    @classmethod
    def weave(
        cls, amplitude: float, frequency: float, *, times: Any, pattern: str = "triangle",
        dwell: float | None = None, reference_time: Any = None,
    ) -> Pose:
        """A weave: a pose moving across its parent's y axis (and, for ``"circle"``, along
        its x) by up to ``amplitude`` metres (or a pint length) at ``frequency`` Hz (or a
        pint frequency), starting on the centre line at the first of ``times``; put the
        torch target under it. Its axes are the parent's.

        ``pattern`` is ``"triangle"``, ``"sine"``, ``"trapezoid"`` (with ``dwell``, the
        fraction of each period held at the two edges, in (0, 1)) or ``"circle"``; the
        offsets are defined in :class:`~pinframes.Weave`. The pose holds the
        pattern's exact offsets at ``times`` (at least two, strictly increasing, any time
        form, ``reference_time`` as for :class:`Pose`) and moves linearly between them, as
        every pose does: sample the sine and the circle finely, and the triangle's and
        trapezoid's corners to keep them. :attr:`weaving` keeps the pattern (a scene
        writes it as a ``weave`` entry).

        Raises :class:`~pinframes.errors.InvalidPoseError` naming the field (``amplitude``,
        ``frequency``, ``pattern``, ``dwell``, ``times``); ``times`` that all fall on whole
        half periods (a step of the period or half of it) sample a straight line, and are
        refused too.
        """
        pattern_spec = Weave(metres(amplitude, "amplitude"),
                             magnitude_in(frequency, "hertz", "frequency"), pattern, dwell)
        axis = _time_axis(times, reference_time)
        if axis is None or axis.offsets.shape[0] < 2:
            raise InvalidPoseError("a weave needs at least two times", field="times")
        seconds = (axis.offsets - axis.offsets[0]) / 1e9
        pattern_spec.check_sample_times(seconds)
        count = axis.offsets.shape[0]
        pose = cls._trusted(np.broadcast_to(np.eye(3), (count, 3, 3)).copy(),
                            pattern_spec.offsets(seconds), axis.offsets, axis.reference)
        pose._weave = pattern_spec
        return pose

    # -- attributes ----------------------------------------------------------------------
    @property
    def weaving(self) -> Weave | None:
        """The weave pattern of a pose made by :meth:`weave`; None for every other pose
        (what an operation on a weave returns included)."""
        return self._weave

    @property
    def translation(self) -> FloatArray:
        """Origin in the reference frame, metres: shape (3,) or (T, 3)."""
        return self._translation

    @property
    def rotation(self) -> FloatArray:
        """Rotation matrices: shape (3, 3) or (T, 3, 3)."""
        return self._rotation

    @property
    def quaternion(self) -> FloatArray:
        """Unit quaternions ``(x, y, z, w)``: shape (4,) or (T, 4).

        ``q`` and ``-q`` are the same rotation; the sign is chosen so that a series is
        continuous: the first (or only) quaternion has ``w >= 0`` and each later one the
        sign that makes its dot product with the one before it ``>= 0``.
        """
        return sign_continuous_quaternions(quaternion_from_matrix(self._rotation))

    @property
    def matrix(self) -> FloatArray:
        """Homogeneous matrices: shape (4, 4) or (T, 4, 4)."""
        lead = self._translation.shape[:-1]
        out = np.zeros((*lead, 4, 4))
        out[..., :3, :3] = self._rotation
        out[..., :3, 3] = self._translation
        out[..., 3, 3] = 1.0
        return out

    def __len__(self) -> int:
        """Number of samples (1 for a static pose)."""
        return 1 if self._times is None else int(self._times.shape[0])

    def __getitem__(self, key: Any) -> Pose:
        """The samples that ``key`` selects, with their times and the reference time.

        ``key`` is an index, a slice, a boolean mask of length ``len(pose)`` or an array of
        increasing indices, as for a numpy array; ``pose[i]`` is a one-sample pose at the
        i-th time. A static pose is its own only sample (``pose[0]``, ``pose[-1]``).
        """
        if self._times is None:
            if isinstance(key, (int, np.integer)) and key in (0, -1):
                return self
            raise InvalidTimeError("a static pose has one sample: select it with 0 or -1",
                                   field="index")
        if isinstance(key, (int, np.integer)):
            key = [key]
        times = self._times[key]
        if times.ndim != 1 or times.shape[0] == 0:
            raise InvalidTimeError("the selection holds no samples", field="index")
        if np.any(np.diff(times) <= 0):
            raise InvalidTimeError("selected samples must keep their times increasing",
                                   field="index")
        return Pose._trusted(self._rotation[key].copy(), self._translation[key].copy(),
                             times.copy(), self._reference)

    def to_xyz_rpy(self) -> FloatArray:
        """``x, y, z`` in metres and ``roll, pitch, yaw`` in radians: shape (6,) or (T, 6)."""
        return np.concatenate([self._translation, rpy_from_matrix(self._rotation)], axis=-1)

    # -- algebra -------------------------------------------------------------------------
    def inverse(self) -> Pose:
        """The inverse transform: the pose of B in A for a pose of A in B."""
        rotation, translation = samples_first(
            inverse(samples_last((self._rotation, self._translation))))
        require_finite_result(translation, "the inverse pose's translation", InvalidPoseError,
                              field="translation")
        return Pose._trusted(rotation, translation, self._times, self._reference)

    def __matmul__(self, other: Pose) -> Pose:
        """``pose_b_in_c @ pose_a_in_b`` is ``pose_a_in_c``, on one common timeline."""
        if not isinstance(other, Pose):
            return NotImplemented
        left, right = self, other
        if left.is_time_dependent and right.is_time_dependent and not _same_timeline(left, right):
            timeline = _union_timeline(left, right)
            union = timeline.result_offsets
            assert union is not None  # two moving poses: a union of their times
            left = left._sampled(union, timeline.reference)
            right = right._sampled(union, timeline.reference)
        rotation, translation = samples_first(compose(
            samples_last((left._rotation, left._translation)),
            samples_last((right._rotation, right._translation))))
        require_finite_result(translation, "the composed translation", InvalidPoseError,
                              field="translation")
        timed = left if left.is_time_dependent else right
        return Pose._trusted(rotation, translation, timed._times, timed._reference)

    def transform_points(self, points: ArrayLike, *, per_time: bool = False) -> FloatArray:
        """Points given in frame A, returned in frame B (``R @ p + t``), metres.

        ``points`` is ``(3,)``, ``(M, 3)`` or ``(T, M, 3)``. A static pose keeps the shape.
        A pose with ``T`` samples gives ``(T, 3)`` for ``(3,)``, and ``(T, M, 3)`` for
        ``(M, 3)`` (every point at every sample, whatever ``M``), for ``(T, M, 3)`` (a
        profile per sample) and for ``(1, M, 3)``. ``per_time=True`` pairs ``(T, 3)`` points
        with the samples instead (row ``i`` at sample ``i``, giving ``(T, 3)``). Bad shapes
        and NaN are an :class:`~pinframes.errors.InvalidDataError` naming ``points``.
        """
        return transform_data(self._rotation, self._translation, points, "points", per_time)

    def transform_vectors(self, vectors: ArrayLike, *, per_time: bool = False) -> FloatArray:
        """Directions given in frame A, returned in frame B (``R @ v``: rotation only).

        Shapes and ``per_time`` as :meth:`transform_points`; the field named in errors is
        ``vectors``.
        """
        return transform_data(self._rotation, None, vectors, "vectors", per_time)

    def at(self, times: Any, time_ref: Any = None) -> Pose:
        """This pose interpolated at ``times``: one pose per requested time.

        Relative ``times`` count from ``time_ref`` if given, else from this pose's
        reference time. The result's reference time is ``time_ref``, else this pose's
        reference time, else the first of absolute ``times``. Outside its keyframes a pose
        is held at the first or last keyframe.
        """
        # the rules of a tree query (docs/time-semantics.md) with this pose as the one moving
        # thing; a time_ref is never ambiguous here, as for a tree whose frames have references
        timeline = plan_query_timeline(self._sources(), parse_time_axis(times), time_ref,
                                       None, True)
        offsets = timeline.result_offsets
        assert offsets is not None  # times were given
        return self._sampled(offsets, timeline.reference)

    def _sampled(self, times: NDArray[np.int64], reference: np.datetime64 | None) -> Pose:
        """Samples at ``times`` ns after ``reference`` (both on this pose's own basis)."""
        if not self.is_time_dependent:
            count = times.shape[0]
            return Pose._trusted(np.broadcast_to(self._rotation, (count, 3, 3)).copy(),
                                 np.broadcast_to(self._translation, (count, 3)).copy(),
                                 times, reference)
        shift = 0
        if reference is not None and self._reference is not None:
            shift = timestamp_ns(reference) - timestamp_ns(self._reference)
        rotation, translation = self.keyframes.sample(shift_ns(times, shift))
        require_finite_result(translation, "the interpolated translation", InvalidPoseError,
                              field="translation")
        return Pose._trusted(rotation, translation, times, reference)

    def _sources(self) -> list[TimedSource]:
        """This pose as the moving thing of a timeline plan (none when static)."""
        if self._times is None:
            return []
        return [TimedSource("pose", self._times, self._reference)]

    @property
    def keyframes(self) -> Keyframes:
        """The keyframes of a time-dependent pose, prepared for interpolation."""
        if self._times is None:
            raise InvalidTimeError("a static pose has no keyframes", field="times")
        if self._keyframes is None:
            self._keyframes = Keyframes(self._times, self._rotation, self._translation)
        return self._keyframes

    def __repr__(self) -> str:
        """The numbers of a static pose; the time span and the first and last samples'
        numbers of a time-dependent one (quaternions with ``w >= 0``)."""
        if not self.is_time_dependent:
            quaternion = quaternion_from_matrix(self._rotation)
            return f"Pose({_numbers_text(self._translation, quaternion)})"
        offsets = self.keyframes.times
        first, last = offsets[[0, -1]] / 1e9
        text = (f"Pose(1 sample at {first:.9g} s" if len(self) == 1 else
                f"Pose({len(self)} samples from {first:.9g} s to {last:.9g} s")
        if self._reference is not None:
            stamps = [format_timestamp_iso(stamp) for stamp in
                      self._reference + offsets[[0, -1]].astype("timedelta64[ns]")]
            text += (f" after {format_timestamp_iso(self._reference)}, "
                     f"{' to '.join(stamps[:len(self)])}")
        ends = [0] if len(self) == 1 else [0, -1]
        numbers = _numbers_text(self._translation[ends],
                                quaternion_from_matrix(self._rotation[ends]))
        return f"{text}: {numbers})"


def trusted_pose(
    rotation: FloatArray, translation: FloatArray, times: NDArray[np.int64] | None = None,
    reference: np.datetime64 | None = None,
) -> Pose:
    """A :class:`Pose` of arrays known to be valid (the evaluator's results): no checks or
    copies. ``times`` are int64 ns after ``reference``."""
    return Pose._trusted(rotation, translation, times, reference)


def _numbers_text(translation: FloatArray, quaternion: FloatArray) -> str:
    """``translation=(x, y, z), quaternion=(x, y, z, w)``, or for two samples each as
    ``(first) to (last)``."""
    def vector(values: FloatArray) -> str:
        rows = np.atleast_2d(values)
        return " to ".join("(" + ", ".join(f"{value:.6g}" for value in row) + ")"
                           for row in rows)
    return f"translation={vector(translation)}, quaternion={vector(quaternion)}"


def _same_timeline(a: Pose, b: Pose) -> bool:
    times_a, times_b = a.keyframes.times, b.keyframes.times
    return (a._reference == b._reference and times_a.shape == times_b.shape
            and bool(np.array_equal(times_a, times_b)))


def _union_timeline(a: Pose, b: Pose) -> QueryTimeline:
    """The union of two poses' times, by the rules of a tree query without times."""
    if (a._reference is None) != (b._reference is None):
        raise ReferenceTimeError(
            "cannot combine a pose with a reference time and one without", field="times"
        )
    return plan_query_timeline([*a._sources(), *b._sources()], None, None, None, True)


def _as_float_array(values: ArrayLike, field: str) -> FloatArray:
    return float_array(values, field, InvalidPoseError, copy=True)


def _rotation_matrices(rotation: ArrayLike | None) -> FloatArray:
    if rotation is None:
        return np.eye(3)
    array = _as_float_array(rotation, "rotation")
    if array.shape[-1:] == (4,) and array.ndim in (1, 2):
        norms = np.linalg.norm(array, axis=-1)
        if np.any(np.abs(norms - 1.0) > _QUATERNION_NORM_TOLERANCE):
            raise InvalidPoseError(
                f"quaternion (x, y, z, w) must have unit norm, got norm {np.min(norms):.6g}"
                + ("" if norms.size == 1 else f" to {np.max(norms):.6g}"),
                field="rotation",
            )
        return matrix_from_quaternion(array / norms[..., None])
    if array.shape[-2:] == (3, 3) and array.ndim in (2, 3):
        orthogonality, determinant = rotation_matrix_defects(array)
        if orthogonality > ROTATION_TOLERANCE:
            raise InvalidPoseError(
                f"rotation matrix is not orthonormal (R.T @ R deviates from I by "
                f"{orthogonality:.3g})", field="rotation")
        if determinant > ROTATION_TOLERANCE:
            raise InvalidPoseError(
                "rotation matrix has determinant -1: a reflection, not a rotation"
                if np.any(np.linalg.det(array) < 0) else
                f"rotation matrix determinant deviates from 1 by {determinant:.3g}",
                field="rotation")
        return array
    raise InvalidPoseError(
        f"expected a (3, 3) or (T, 3, 3) matrix or a (4,) or (T, 4) quaternion, got shape "
        f"{array.shape}", field="rotation")


def _time_axis(times: Any, reference_time: Any) -> TimeAxis | None:
    if times is None:
        if reference_time is not None:
            raise InvalidTimeError("a reference_time needs times", field="reference_time")
        return None
    axis = parse_time_axis(times)
    if axis.offsets.shape[0] > 1 and np.any(np.diff(axis.offsets) <= 0):
        position = int(np.argmax(np.diff(axis.offsets) <= 0)) + 1
        raise InvalidTimeError(
            f"times must be strictly increasing; time {position} is not after time "
            f"{position - 1}", field="times")
    if reference_time is None:
        return axis
    return anchor_time_axis(axis, parse_timestamp(reference_time))


def _broadcast_part(
    array: FloatArray, item_shape: tuple[int, ...], count: int | None, field: str
) -> FloatArray:
    single = array.shape == item_shape
    stacked = array.ndim == len(item_shape) + 1 and array.shape[1:] == item_shape
    if not (single or stacked):
        raise InvalidPoseError(
            f"expected shape {item_shape} or (T, {', '.join(map(str, item_shape))}), "
            f"got {array.shape}", field=field)
    if count is None:
        if stacked:
            if array.shape[0] != 1:
                raise InvalidPoseError(
                    f"{array.shape[0]} samples given but no times", field=field)
            return array[0].copy()
        return array
    if single:
        return np.broadcast_to(array, (count, *item_shape)).copy()
    if array.shape[0] != count:
        raise InvalidPoseError(
            f"{array.shape[0]} samples given for {count} times", field=field)
    return array
