"""Poses, times and arrays as tagged asdf nodes of one weldx schema generation.

The nodes are raw tagged trees (``asdf.tagged``), so asdf writes them as they are and no
converter (weldx's included) ever runs on them. Lengths go out in millimetres: without a unit
in the legacy generation (where that is the convention), with ``millimeter`` in the current
one, as weldx writes it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from asdf.tagged import tag_object

from ...values.pose import Pose
from ...values.timeconv import format_timedelta_iso, format_timestamp_iso
from ._units import DEFAULT_LENGTH_UNIT, METRES_PER_UNIT

__all__ = ["CURRENT", "LEGACY", "SCHEMAS", "Generation", "encode_pose", "encode_timestamp",
           "tagged"]

_MILLIMETRES_PER_METRE = 1.0 / METRES_PER_UNIT[DEFAULT_LENGTH_UNIT]


@dataclass(frozen=True)
class Generation:
    """How one weldx schema generation spells its tags and values.

    Attributes
    ----------
    schema : str
        The hierarchy's schema version, as passed to ``write_asdf``.
    tag_prefix : str
        What every weldx tag starts with.
    versions : dict of str to str
        The version written for each tag path (``core/variable`` -> ``1.0.0``).
    time_in_object : bool
        Durations and timestamps as ``{value: ...}`` objects (legacy) or plain strings.
    length_unit : str or None
        The unit written with coordinates, or None for unitless millimetres.
    asdf_standard : str
        The ASDF standard version of the file.
    """

    schema: str
    tag_prefix: str
    versions: dict[str, str]
    time_in_object: bool
    length_unit: str | None
    asdf_standard: str

    def tag(self, path: str) -> str:
        """The full tag of ``path`` (e.g. ``core/variable``) in this generation."""
        return f"{self.tag_prefix}{path}-{self.versions[path]}"


LEGACY = Generation(
    schema="1.0.0",
    tag_prefix="tag:weldx.bam.de:weldx/",
    versions={
        "core/transformations/coordinate_system_hierarchy": "1.0.0",
        "core/transformations/coordinate_system_hierarchy_subsystem": "1.0.0",
        "core/transformations/coordinate_transformation": "1.0.0",
        "core/transformations/local_coordinate_system": "1.0.0",
        "core/variable": "1.0.0",
        "time/timedelta": "1.0.0",
        "time/timedeltaindex": "1.0.0",
        "time/timestamp": "1.0.0",
    },
    time_in_object=True,
    length_unit=None,
    asdf_standard="1.5.0",
)

CURRENT = Generation(
    schema="0.1.0",
    tag_prefix="asdf://weldx.bam.de/weldx/tags/",
    versions={
        "core/transformations/coordinate_system_hierarchy": "0.1.0",
        "core/graph/di_graph": "0.1.0",
        "core/graph/di_node": "0.1.0",
        "core/graph/di_edge": "0.1.0",
        "core/transformations/local_coordinate_system": "0.1.1",
        "core/variable": "0.1.1",
        "core/data_array": "0.1.0",
        "core/geometry/spatial_data": "0.1.1",
        "time/timedelta": "0.1.0",
        "time/timedeltaindex": "0.1.0",
        "time/timestamp": "0.1.0",
        "units/quantity": "0.1.0",
        "units/units": "0.1.0",
    },
    time_in_object=False,
    length_unit=DEFAULT_LENGTH_UNIT,
    asdf_standard="1.6.0",
)

SCHEMAS: dict[str, Generation] = {LEGACY.schema: LEGACY, CURRENT.schema: CURRENT}


def tagged(generation: Generation, path: str, value: Any) -> Any:
    """``value`` (dict, list or str) carrying the tag of ``path`` in ``generation``."""
    return tag_object(generation.tag(path), value)


def encode_timestamp(generation: Generation, stamp: np.datetime64) -> Any:
    """A ``time/timestamp`` node."""
    return _time_node(generation, "time/timestamp", format_timestamp_iso(stamp))


def encode_pose(generation: Generation, pose: Pose) -> Any:
    """A ``local_coordinate_system`` node for ``pose`` (a frame in its parent).

    Parts that are the identity are left out (``{}`` is the identity). A part that does not
    change over time is written without a time dimension, except that a moving pose keeps
    its coordinates on the time axis when both parts are constant, so it stays moving.
    """
    node: dict[str, Any] = {}
    rotation, translation = pose.rotation, pose.translation
    timed = pose.is_time_dependent
    if timed:
        if pose.reference_time is not None:
            node["reference_time"] = encode_timestamp(generation, pose.reference_time)
        node["time"] = _time_index(generation, pose.keyframes.times)
        rotation_constant = _is_constant(rotation)
        if rotation_constant:
            rotation = rotation[0]
        if _is_constant(translation) and not rotation_constant:
            translation = translation[0]
    if not np.array_equal(rotation, np.eye(3)):
        dimensions = ["time", "c", "v"] if rotation.ndim == 3 else ["c", "v"]
        node["orientations"] = _variable(generation, "orientations", dimensions, rotation)
    if translation.ndim == 2 or np.any(translation != 0.0):
        dimensions = ["time", "c"] if translation.ndim == 2 else ["c"]
        node["coordinates"] = _variable(generation, "coordinates", dimensions,
                                        translation * _MILLIMETRES_PER_METRE,
                                        generation.length_unit)
    return tagged(generation, "core/transformations/local_coordinate_system", node)


def _is_constant(samples: np.ndarray) -> bool:
    """True when every sample (along the first axis) equals the first one exactly."""
    return bool(np.all(samples == samples[0]))


def _variable(generation: Generation, name: str, dimensions: list[str], data: np.ndarray,
              unit: str | None = None) -> Any:
    node: dict[str, Any] = {"name": name, "dimensions": dimensions, "dtype": "<f8"}
    if unit is not None:
        node["units"] = tagged(generation, "units/units", unit)
    node["data"] = np.ascontiguousarray(data, dtype="<f8")
    return tagged(generation, "core/variable", node)


def _time_index(generation: Generation, offsets_ns: np.ndarray) -> Any:
    """The explicit times (never a ``freq`` grid), with start, end, min and max."""
    first, last = int(offsets_ns[0]), int(offsets_ns[-1])
    node = {"values": np.ascontiguousarray(offsets_ns, dtype="<i8"),
            "start": _duration(generation, first), "end": _duration(generation, last),
            "min": _duration(generation, int(offsets_ns.min())),
            "max": _duration(generation, int(offsets_ns.max()))}
    return tagged(generation, "time/timedeltaindex", node)


def _duration(generation: Generation, nanoseconds: int) -> Any:
    return _time_node(generation, "time/timedelta", format_timedelta_iso(nanoseconds))


def _time_node(generation: Generation, path: str, text: str) -> Any:
    return tagged(generation, path, {"value": text} if generation.time_in_object else text)
