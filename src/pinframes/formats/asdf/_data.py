"""Data attached to frames in weldx files: ``core/geometry/spatial_data`` and bare point arrays.

weldx keeps each frame's data in its graph node, ``attributes.data: {name: data}`` (weldx 0.4
legacy files: a ``spatial_data`` list of ``{coordinate_system, name, data}``). Each data set is:

- ``core/geometry/spatial_data-0.1.0`` (and legacy ``1.0.0``): ``coordinates`` a plain
  ``(M, 3)`` array in millimetres, optional ``triangles`` and ``attributes``;
- ``core/geometry/spatial_data-0.1.1``: ``coordinates`` a ``units/quantity``
  ``{value, units}`` for static points, or a ``core/data_array`` for points with time;
- ``core/data_array``: points assigned without ``SpatialData``; its ``data`` variable has
  dimensions ``[n, c]`` or ``[time, n, c]`` and ``units``; a ``time`` coordinate holds
  ``<m8[ns]`` offsets or ``<M8[ns]`` timestamps as int64 nanoseconds.

Anything else is an :class:`UnsupportedFeatureError` naming the frame, the data and the tag.
pinframes writes ``spatial_data-0.1.1`` in millimetres, as weldx 0.8 writes it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import FileFormatError, PinframesError, UnsupportedFeatureError
from ...values.spatial_data import SpatialData
from ._decode import (
    DECODING_ERRORS,
    as_list,
    first_line,
    float_array,
    raw_tag,
    required,
    weldx_tag,
)
from ._encode import Generation, tagged
from ._units import DEFAULT_LENGTH_UNIT, METRES_PER_UNIT, metres_per_unit

__all__ = ["encode_data", "read_data"]

_SPATIAL = "core/geometry/spatial_data"
_ARRAY = "core/data_array"
_QUANTITY = "units/quantity"
_MILLIMETRES_PER_METRE = 1.0 / METRES_PER_UNIT[DEFAULT_LENGTH_UNIT]


def read_data(node: Any, frame: str, name: str, field: str) -> SpatialData:
    """The data set ``node`` attached to ``frame``; errors name the frame and ``field``."""
    try:
        return _read(node, f"{field}.{name}")
    except PinframesError as exc:
        raise exc.located(frame=frame) from None


def _read(node: Any, field: str) -> SpatialData:
    tag = weldx_tag(node)
    kind = None if tag is None else tag[0]
    if kind == _ARRAY:
        points, times, reference = _data_array(node, field)
        return _spatial(points, None, {}, times, reference, field)
    if kind != _SPATIAL:
        raise UnsupportedFeatureError(
            f"data with the tag {raw_tag(node) or 'none'!r} cannot be held by pinframes (it "
            "holds spatial_data and point data_arrays)", field=field)
    coordinates = required(node, "coordinates", field)
    coordinates_field = f"{field}.coordinates"
    inner = (weldx_tag(coordinates) or ("",))[0]
    times = reference = None
    if inner == _ARRAY:
        points, times, reference = _data_array(coordinates, coordinates_field)
    elif inner == _QUANTITY:
        points = float_array(required(coordinates, "value", coordinates_field),
                             f"{coordinates_field}.value")
        points = points * _scale(coordinates.get("units"), f"{coordinates_field}.units")
    elif raw_tag(coordinates) is None or inner == "":
        points = float_array(coordinates, coordinates_field) * _scale(None, coordinates_field)
    else:
        raise UnsupportedFeatureError(f"coordinates with the tag {raw_tag(coordinates)!r} "
                                      "cannot be held by pinframes", field=coordinates_field)
    attributes = node.get("attributes") or {}
    if not isinstance(attributes, dict):
        raise FileFormatError("expected a mapping", field=f"{field}.attributes")
    triangles = node.get("triangles")
    if triangles is not None:
        triangles = _array(triangles, f"{field}.triangles")
    return _spatial(points, triangles,
                    {str(key): _array(value, f"{field}.attributes.{key}")
                     for key, value in attributes.items()}, times, reference, field)


def _spatial(points: Any, triangles: Any, attributes: dict[str, Any], times: Any,
             reference: Any, field: str) -> SpatialData:
    try:
        return SpatialData(points, triangles, attributes, times, reference)
    except PinframesError as exc:
        raise type(exc)(exc.message, field=f"{field}.{exc.field}" if exc.field else field
                        ) from None


def _data_array(node: Any, field: str) -> tuple[Any, Any, Any]:
    """Points (metres), times and reference time of a ``core/data_array`` of points."""
    variable = required(node, "data", field)
    dimensions = [str(d) for d in as_list(required(variable, "dimensions", f"{field}.data"),
                                          f"{field}.data.dimensions")]
    if dimensions not in (["n", "c"], ["time", "n", "c"]):
        raise UnsupportedFeatureError(
            f"point data with the dimensions {dimensions} cannot be held by pinframes (it "
            "holds [n, c] and [time, n, c])", field=f"{field}.data.dimensions")
    points = float_array(required(variable, "data", f"{field}.data"), f"{field}.data.data")
    points = points * _scale(variable.get("units"), f"{field}.data.units")
    if dimensions[0] != "time":
        return points, None, None
    coordinates = as_list(node.get("coordinates") or [], f"{field}.coordinates")
    time = next((c for c in coordinates if isinstance(c, dict) and c.get("name") == "time"),
                None)
    if time is None:
        raise FileFormatError("points along time need a 'time' coordinate",
                              field=f"{field}.coordinates")
    values = _array(required(time, "data", f"{field}.coordinates.time"),
                    f"{field}.coordinates.time.data")
    if values.dtype.kind not in "iu":
        raise FileFormatError(f"expected whole nanoseconds (int64), got values of dtype "
                              f"{values.dtype}", field=f"{field}.coordinates.time.data")
    values = values.astype(np.int64)
    dtype = str(time.get("dtype", ""))
    if "M8" in dtype:  # timestamps: the first one becomes the reference time
        stamps = values.astype("datetime64[ns]")
        return points, stamps - stamps[0], stamps[0]
    if "m8" in dtype:
        return points, values.astype("timedelta64[ns]"), None
    raise FileFormatError(f"expected times of dtype <m8[ns] or <M8[ns], got {dtype!r}",
                          field=f"{field}.coordinates.time.dtype")


def _scale(unit: Any, field: str) -> float:
    scale = metres_per_unit(None if unit is None else str(unit))
    if scale is None:
        raise FileFormatError(f"unknown length unit {str(unit)!r}", field=field)
    return scale


def _array(value: Any, field: str) -> np.ndarray:
    try:
        return np.array(value)
    except DECODING_ERRORS as exc:
        raise FileFormatError(f"cannot read the array: {first_line(exc)}", field=field
                              ) from None


def encode_data(generation: Generation, data: SpatialData) -> Any:
    """A ``spatial_data-0.1.1`` node: static points as a quantity, timed ones as a
    ``data_array`` with a ``time`` coordinate (timestamps when the data has a reference
    time), millimetres."""
    millimetres = np.ascontiguousarray(data.points * _MILLIMETRES_PER_METRE, dtype="<f8")
    unit = tagged(generation, "units/units", DEFAULT_LENGTH_UNIT)
    offsets = data.times
    if offsets is None:
        coordinates = tagged(generation, _QUANTITY, {"value": millimetres, "units": unit})
    else:
        stamps = offsets if data.reference_time is None else data.reference_time + offsets
        time = stamps.astype(np.int64)
        coordinates = tagged(generation, _ARRAY, {
            "attributes": {},
            "coordinates": [
                _variable(generation, "c", ["c"], "<U1", np.array(["x", "y", "z"])),
                _variable(generation, "time", ["time"],
                          "<m8[ns]" if data.reference_time is None else "<M8[ns]", time)],
            "data": _variable(generation, "data", ["time", "n", "c"], "<f8", millimetres,
                              unit)})
    node: dict[str, Any] = {"coordinates": coordinates}
    if data.attributes:
        node["attributes"] = {name: np.ascontiguousarray(value)
                              for name, value in data.attributes.items()}
    if data.triangles is not None:
        node["triangles"] = np.ascontiguousarray(data.triangles, dtype="<u8")
    return tagged(generation, _SPATIAL, node)


def _variable(generation: Generation, name: str, dimensions: list[str], dtype: str,
              values: np.ndarray, unit: Any = None) -> Any:
    node: dict[str, Any] = {"name": name, "dimensions": dimensions, "dtype": dtype}
    if unit is not None:
        node["units"] = unit
    node["data"] = values
    return tagged(generation, "core/variable", node)
