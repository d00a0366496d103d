"""The standard messages pinframes writes, built as rosbags message objects from arrays.

Units as ROS has them: metres, radians, quaternions ``(x, y, z, w)``; stamps in ns since the
epoch split into ``sec`` and ``nanosec``; frame ids as given (the caller drops a leading
``/``, as tf2 does).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["joint_state", "joint_trajectory", "text", "transforms"]

_NS = 1_000_000_000


def transforms(types: dict[str, Any], parents: Sequence[str], children: Sequence[str],
               stamps_ns: NDArray[np.int64], translations: NDArray[np.float64],
               quaternions: NDArray[np.float64]) -> Iterator[Any]:
    """One ``tf2_msgs/TFMessage`` per stamp, holding the transform of every child in its
    parent then: ``translations`` (F, T, 3) metres and ``quaternions`` (F, T, 4) for the F
    ``children`` at the T ``stamps_ns``."""
    time, header = types["builtin_interfaces/msg/Time"], types["std_msgs/msg/Header"]
    stamped, transform = (types["geometry_msgs/msg/TransformStamped"],
                          types["geometry_msgs/msg/Transform"])
    vector, quaternion = types["geometry_msgs/msg/Vector3"], types["geometry_msgs/msg/Quaternion"]
    message = types["tf2_msgs/msg/TFMessage"]
    with_seq = "seq" in header.__dataclass_fields__
    pairs = list(zip(parents, children, strict=True))
    per_time_translation = np.ascontiguousarray(translations.transpose(1, 0, 2)).tolist()
    per_time_quaternion = np.ascontiguousarray(quaternions.transpose(1, 0, 2)).tolist()
    for stamp_ns, moved, turned in zip(stamps_ns.tolist(), per_time_translation,
                                       per_time_quaternion, strict=True):
        stamp = time(sec=stamp_ns // _NS, nanosec=stamp_ns % _NS)
        yield message(transforms=[
            stamped(header=header(seq=0, stamp=stamp, frame_id=parent) if with_seq
                    else header(stamp=stamp, frame_id=parent), child_frame_id=child,
                    transform=transform(translation=vector(*xyz), rotation=quaternion(*xyzw)))
            for (parent, child), xyz, xyzw in zip(pairs, moved, turned, strict=True)])


def joint_state(types: dict[str, Any], stamp_ns: int, names: Sequence[str],
                positions: Sequence[float]) -> Any:
    """A ``sensor_msgs/JointState`` of ``positions`` (radians or metres) at ``stamp_ns``,
    without velocities and efforts."""
    return types["sensor_msgs/msg/JointState"](
        header=_header(types, stamp_ns, ""), name=list(names),
        position=np.asarray(positions, np.float64), velocity=np.empty(0, np.float64),
        effort=np.empty(0, np.float64))


def joint_trajectory(types: dict[str, Any], names: Sequence[str],
                     offsets_ns: NDArray[np.int64], positions: NDArray[np.float64],
                     rates: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
                     ) -> Any:
    """A ``trajectory_msgs/JointTrajectory``: one point per sample, ``time_from_start`` the
    sample's ``offsets_ns`` after the first, with the ``rates`` (velocities and
    accelerations, (T, n)) when given; ``header.stamp`` zero, which a
    ``joint_trajectory_controller`` reads as "start on receipt"."""
    duration = types["builtin_interfaces/msg/Duration"]
    point = types["trajectory_msgs/msg/JointTrajectoryPoint"]
    empty = np.empty(0, np.float64)
    count = positions.shape[0]
    velocities = [empty] * count if rates is None else np.asarray(rates[0], np.float64)
    accelerations = [empty] * count if rates is None else np.asarray(rates[1], np.float64)
    points = [point(positions=np.asarray(row, np.float64), velocities=np.asarray(rate),
                    accelerations=np.asarray(change), effort=empty,
                    time_from_start=duration(sec=offset // _NS, nanosec=offset % _NS))
              for offset, row, rate, change in zip(offsets_ns.tolist(), positions, velocities,
                                                   accelerations, strict=True)]
    return types["trajectory_msgs/msg/JointTrajectory"](
        header=_header(types, 0, ""), joint_names=list(names), points=points)


def text(types: dict[str, Any], value: str) -> Any:
    """A ``std_msgs/String`` (a robot description)."""
    return types["std_msgs/msg/String"](data=value)


def _header(types: dict[str, Any], stamp_ns: int, frame: str) -> Any:
    header = types["std_msgs/msg/Header"]
    stamp = types["builtin_interfaces/msg/Time"](sec=stamp_ns // _NS, nanosec=stamp_ns % _NS)
    if "seq" in header.__dataclass_fields__:
        return header(seq=0, stamp=stamp, frame_id=frame)
    return header(stamp=stamp, frame_id=frame)
