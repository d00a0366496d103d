"""A weldx ``local_coordinate_system`` (any version) as a :class:`~pinframes.Pose`.

The transformation maps coordinates in the child to its reference system: ``orientations``
are rotation matrices (shape (3, 3) or (T, 3, 3)), ``coordinates`` the child's origin
(shape (3,) or (T, 3)) in ``units`` (``unit`` in 1.0.0; none means millimetres), converted to
metres here. A static part broadcasts against a time-dependent other part; ``{}`` is the
identity (docs/asdf-format.md).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import FileFormatError, PinframesError, UnsupportedFeatureError
from ...values.pose import Pose
from ._decode import float_array, raw_tag, required, time_index_ns, timestamp, weldx_tag
from ._units import metres_per_unit

__all__ = ["pose_from_lcs"]

# Field names of Pose errors, as the file calls them.
_FILE_FIELDS = {"rotation": "orientations", "translation": "coordinates", "times": "time"}
_LCS_TAG = "core/transformations/local_coordinate_system"


def pose_from_lcs(node: Any, frame: str, field: str) -> Pose:
    """The pose ``node`` describes; errors name ``frame`` and the field below ``field``."""
    try:
        return _pose(node, field)
    except PinframesError as exc:
        raise exc.located(frame=frame) from None


def _pose(node: Any, field: str) -> Pose:
    if not isinstance(node, dict):
        raise FileFormatError(f"expected a local_coordinate_system mapping, got "
                              f"{type(node).__name__}", field=field)
    tag = raw_tag(node)
    if tag is not None and (weldx_tag(node) or ("",))[0] != _LCS_TAG:
        raise FileFormatError(f"expected a local_coordinate_system, got the tag {tag!r}",
                              field=field)
    rotation = _variable_data(node.get("orientations"), f"{field}.orientations")
    translation = _coordinates_metres(node.get("coordinates"), f"{field}.coordinates")
    timed = ((rotation is not None and rotation.ndim == 3)
             or (translation is not None and translation.ndim == 2))
    times = reference = None
    if timed:
        times = time_index_ns(required(node, "time", field), f"{field}.time")
        if node.get("reference_time") is not None:
            reference = timestamp(node["reference_time"], f"{field}.reference_time")
    try:
        return Pose(np.zeros(3) if translation is None else translation, rotation,
                    times=None if times is None else times.astype("timedelta64[ns]"),
                    reference_time=reference)
    except PinframesError as exc:
        part = _FILE_FIELDS.get(exc.field or "", exc.field)
        raise type(exc)(exc.message, field=f"{field}.{part}" if part else field) from None


def _coordinates_metres(node: Any, field: str) -> NDArray[np.float64] | None:
    tag = weldx_tag(node)
    if tag is not None and tag[0] == "core/time_series":
        expression = node.get("expression") if isinstance(node, dict) else None
        text = (expression.get("expression") if isinstance(expression, dict) else None)
        raise UnsupportedFeatureError(
            "coordinates given as a core/time_series"
            + (f" (the math expression {str(text)!r})" if text is not None else "")
            + " are not supported: pinframes reads sampled coordinates only; evaluate the "
            "expression at the times you need with weldx and store the samples", field=field)
    data = _variable_data(node, field)
    if data is None:
        return None
    unit = node.get("units", node.get("unit"))
    scale = metres_per_unit(None if unit is None else str(unit))
    if scale is None:
        raise FileFormatError(f"unknown length unit {str(unit)!r}", field=f"{field}.units")
    return data * scale


def _variable_data(node: Any, field: str) -> NDArray[np.float64] | None:
    """The ``data`` of a ``core/variable`` (None when the part is absent)."""
    if node is None:
        return None
    return float_array(required(node, "data", field), f"{field}.data")
