"""A scene frame's pose: fixed (xyz, rpy or quaternion) or moving (keyframes, a curve or a
weave); each error names the scene file, the frame and the field.

Lengths in metres, angles in radians, times in seconds; a pose is the frame's in its parent.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import FileFormatError, PinframesError
from ...values.curve_frames import length_along_polyline
from ...values.pose import Pose
from ...values.rotations import matrix_from_axis_angle
from ..limits import current_limits, exceeded
from ._fields import SceneFields
from ._unit_check import UnitCheck

POSE_KEYS = {"xyz", "rpy", "quaternion"}
"""The keys of a fixed pose."""
_KEYFRAME_KEYS = {"time"} | POSE_KEYS
_CURVE_KEYS = {"points", "normals", "arc", "speed", "duration", "times"}
_CURVE_TIMINGS = ("speed", "duration", "times")
_ARC_KEYS = {"centre", "axis", "start", "angle", "count"}
_WEAVE_KEYS = {"amplitude", "frequency", "pattern", "dwell", "times", "duration", "step"}


class SceneMotion:
    """Reads the poses of one scene file's entries, checking lengths and angles against the
    scene's units (``units``)."""

    def __init__(self, fields: SceneFields, units: UnitCheck) -> None:
        self.fields = fields
        self.path = fields.path
        self.units = units

    def pose_parts(self, item: dict, frame: str | None, field: str
                   ) -> tuple[np.ndarray | None, np.ndarray]:
        """Rotation (a (3, 3) matrix, or None) and translation (3,) metres."""
        translation = self.fields.numbers(item.get("xyz", (0.0, 0.0, 0.0)), 3, frame,
                                          f"{field}.xyz")
        self.units.lengths(translation, frame, f"{field}.xyz")
        if "rpy" in item and "quaternion" in item:
            raise FileFormatError("give either rpy or quaternion, not both", file=self.path,
                                  frame=frame, field=f"{field}.rpy")
        rotation = None
        if "rpy" in item:
            rpy = self.fields.numbers(item["rpy"], 3, frame, f"{field}.rpy")
            self.units.angles(rpy, frame, f"{field}.rpy")
            rotation = Pose.from_xyz_rpy(0.0, 0.0, 0.0, *rpy).rotation
        elif "quaternion" in item:
            quaternion = self.fields.numbers(item["quaternion"], 4, frame, f"{field}.quaternion")
            try:
                rotation = Pose(rotation=quaternion).rotation
            except PinframesError as exc:
                raise FileFormatError(exc.message, file=self.path, frame=frame,
                                      field=f"{field}.quaternion") from None
        return rotation, translation

    def keyframes(self, item: dict, static: tuple[np.ndarray | None, np.ndarray],
                  frame: str, field: str) -> Pose:
        """A frame moving through its ``keyframes``; a keyframe without xyz or a rotation
        keeps the frame's ``static`` one (rotation, translation)."""
        keyframes = item["keyframes"]
        if not isinstance(keyframes, list) or not keyframes:
            raise FileFormatError("expected a non-empty list of keyframes", file=self.path,
                                  frame=frame, field=f"{field}.keyframes")
        times, translations, rotations = [], [], []
        for position, keyframe in enumerate(keyframes):
            where = f"{field}.keyframes[{position}]"
            self.fields.check_keys(keyframe, _KEYFRAME_KEYS, frame, where)
            if "time" not in keyframe:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.time")
            times.append(keyframe["time"])
            rotation, translation = self.pose_parts(
                {"xyz": static[1], **keyframe}, frame, where)
            translations.append(translation)
            if rotation is None:
                rotation = np.eye(3) if static[0] is None else static[0]
            rotations.append(rotation)
        reference = self._reference_time(item, frame, field)
        try:
            return Pose(np.array(translations), np.array(rotations), times=times,
                        reference_time=reference)
        except PinframesError as exc:
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=f"{field}.keyframes.time") from None

    def curve(self, item: dict, frame: str, field: str) -> Pose:
        """A frame moving along a polyline (``Pose.along_curve``), given as points or an arc."""
        where = f"{field}.curve"
        curve = item["curve"]
        self.fields.check_keys(curve, _CURVE_KEYS, frame, where)
        if ("points" in curve) == ("arc" in curve):
            raise FileFormatError("give either points (with normals) or arc", file=self.path,
                                  frame=frame, field=where)
        if "points" in curve:
            points = self.fields.vectors(curve["points"], frame, f"{where}.points")
            self.units.lengths(points, frame, f"{where}.points")
            if "normals" not in curve:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.normals")
            normals = curve["normals"]
            normals = (self.fields.numbers(normals, 3, frame, f"{where}.normals")
                       if _is_flat(normals) else
                       self.fields.vectors(normals, frame, f"{where}.normals"))
        else:
            if "normals" in curve:
                raise FileFormatError("an arc's normals point away from its centre; give "
                                      "points for others", file=self.path, frame=frame,
                                      field=f"{where}.normals")
            points, normals = self._arc(curve["arc"], frame, f"{where}.arc")
        timings = [key for key in _CURVE_TIMINGS if key in curve]
        if len(timings) != 1:
            raise FileFormatError("give one of speed (m/s), duration (s) or times",
                                  file=self.path, frame=frame, field=where)
        speed, times = None, curve.get("times")
        if "speed" in curve:
            speed = self.fields.positive(curve["speed"], frame, f"{where}.speed")
        elif "duration" in curve:
            duration = self.fields.positive(curve["duration"], frame, f"{where}.duration")
            speed = float(length_along_polyline(points)[-1]) / duration
        reference = self._reference_time(item, frame, field)
        try:
            return Pose.along_curve(points, normals, speed=speed, times=times,
                                    reference_time=reference)
        except PinframesError as exc:
            raise self._inside(exc, frame, where) from None

    def weave(self, item: dict, frame: str, field: str) -> Pose:
        """A frame weaving across its parent's y axis (``Pose.weave``), sampled at ``times``
        or every ``step`` seconds from 0 through ``duration``."""
        where = f"{field}.weave"
        weave = item["weave"]
        self.fields.check_keys(weave, _WEAVE_KEYS, frame, where)
        for key in ("amplitude", "frequency"):
            if key not in weave:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.{key}")
        if ("times" in weave) == ("duration" in weave or "step" in weave):
            raise FileFormatError("give either times or duration (s) with step (s)",
                                  file=self.path, frame=frame, field=where)
        times = weave.get("times")
        if times is None:
            times = self._time_grid(weave, frame, where)
        reference = self._reference_time(item, frame, field)
        amplitude = self.fields.positive(weave["amplitude"], frame, f"{where}.amplitude")
        frequency = self.fields.positive(weave["frequency"], frame, f"{where}.frequency")
        try:
            return Pose.weave(amplitude, frequency, times=times,
                              pattern=weave.get("pattern", "triangle"),
                              dwell=weave.get("dwell"), reference_time=reference)
        except PinframesError as exc:
            if exc.field == "times" and "step" in weave:  # the times came from the step
                exc = type(exc)(exc.message, field="step")
            raise self._inside(exc, frame, where) from None

    def _reference_time(self, item: dict, frame: str, field: str) -> np.datetime64 | None:
        """The moving frame's ``reference_time``, if it has one."""
        if "reference_time" not in item:
            return None
        return self.fields.timestamp(item["reference_time"], frame, f"{field}.reference_time")

    def _inside(self, exc: PinframesError, frame: str, where: str) -> FileFormatError:
        """``exc`` from building the motion at ``where``, located in the scene (its field, if
        any, below ``where``)."""
        inner = "" if exc.field is None else f".{exc.field}"
        return FileFormatError(exc.message, file=self.path, frame=frame, field=where + inner)

    def _time_grid(self, weave: dict, frame: str, where: str) -> np.ndarray:
        """Times (timedelta64[ns]) every ``step`` seconds from 0 through ``duration``."""
        for key in ("duration", "step"):
            if key not in weave:
                raise FileFormatError("missing", file=self.path, frame=frame,
                                      field=f"{where}.{key}")
        duration_ns = round(self.fields.positive(weave["duration"], frame,
                                                 f"{where}.duration") * 1e9)
        step_ns = round(self.fields.positive(weave["step"], frame, f"{where}.step") * 1e9)
        if step_ns == 0:
            raise FileFormatError("the step is below a nanosecond", file=self.path,
                                  frame=frame, field=f"{where}.step")
        count = duration_ns // step_ns + 1
        if count > current_limits().max_samples:
            raise exceeded("max_samples", f"the weave has {count:,} samples",
                           field=f"{where}.step", frame=frame).located(file=self.path)
        return (step_ns * np.arange(count, dtype=np.int64)).astype("timedelta64[ns]")

    def _arc(self, arc: Any, frame: str, field: str) -> tuple[np.ndarray, np.ndarray]:
        """Points (count, 3) of a circular arc and their normals, away from its centre."""
        self.fields.check_keys(arc, _ARC_KEYS, frame, field)
        missing = sorted(_ARC_KEYS - set(arc))
        if missing:
            raise FileFormatError("missing", file=self.path, frame=frame,
                                  field=f"{field}.{missing[0]}")
        centre = self.fields.numbers(arc["centre"], 3, frame, f"{field}.centre")
        axis = self.fields.numbers(arc["axis"], 3, frame, f"{field}.axis")
        start = self.fields.numbers(arc["start"], 3, frame, f"{field}.start")
        self.units.lengths(np.stack([centre, start]), frame, field)
        angle = self.fields.number(arc["angle"], frame, f"{field}.angle")
        count = arc["count"]
        if isinstance(count, bool) or not isinstance(count, int) or count < 2:
            raise FileFormatError(f"expected a whole number of points >= 2, got {count!r}",
                                  file=self.path, frame=frame, field=f"{field}.count")
        if count > current_limits().max_samples:
            raise exceeded("max_samples", f"an arc of {count:,} points", frame=frame,
                           field=f"{field}.count").located(file=self.path)
        if not np.linalg.norm(axis) > 0.0:
            raise FileFormatError("the axis must not be zero", file=self.path, frame=frame,
                                  field=f"{field}.axis")
        axis = axis / np.linalg.norm(axis)
        radial = (start - centre) - np.dot(start - centre, axis) * axis
        if not np.linalg.norm(radial) > 0.0 or angle == 0.0:
            raise FileFormatError("the arc has no length: start on the axis or angle 0",
                                  file=self.path, frame=frame, field=field)
        step = angle / (count - 1)
        if abs(step) >= np.pi:
            raise FileFormatError(
                f"the arc turns by {np.degrees(step):g} degrees from point to point, half a "
                "turn or more, so its points do not follow it (whole turns stand still): "
                "give more points (count)", file=self.path, frame=frame, field=field)
        turns = matrix_from_axis_angle(axis, np.linspace(0.0, angle, count))
        points = centre + turns @ (start - centre)
        return points, turns @ (radial / np.linalg.norm(radial))


def _is_flat(value: Any) -> bool:
    """A list of numbers (one vector), not a list of lists."""
    return isinstance(value, list) and not any(isinstance(item, list) for item in value)
