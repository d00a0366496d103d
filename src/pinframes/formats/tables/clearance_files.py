"""A :class:`~pinframes.Clearance` per sample as CSV or JSON, as ``pinframes clearance`` writes it.

Columns ``time_s, distance_m, frame_a, frame_b, point_a_x_m, point_a_y_m, point_a_z_m,
point_b_x_m, point_b_y_m, point_b_z_m``: seconds after the result's reference time, the
smallest distance in metres (negative: overlap), the two frames of the closest pair, and the
closest point on each, in metres in the tree root's axes. A static result is one row whose
time is NaN (``nan`` in CSV, ``null`` in JSON).

CSV
    One header line, then one line per sample (frame names quoted where CSV needs it); with
    a reference time the first column is ``time_s_after_<timestamp>``. ``pandas.read_csv``
    reads it, and ``numpy.genfromtxt(path, delimiter=",", names=True, dtype=None)``.
JSON
    ``{"frames_a", "frames_b", "excluded", "fixed_together", "geometry", "reference_time",
    "units", "samples": [{column: value}]}``.
"""

from __future__ import annotations

import csv
import io
import json
import os
from pathlib import Path

import numpy as np

from ...errors import FileFormatError
from ...kinematics import Clearance
from ...values.timeconv import format_timestamp_iso
from ..atomic import atomic_write

__all__ = ["CLEARANCE_COLUMNS", "CLEARANCE_FILE_FORMATS", "clearance_text", "write_clearance"]

CLEARANCE_COLUMNS = ("time_s", "distance_m", "frame_a", "frame_b", "point_a_x_m",
                     "point_a_y_m", "point_a_z_m", "point_b_x_m", "point_b_y_m", "point_b_z_m")
CLEARANCE_FILE_FORMATS = ("csv", "json")


def write_clearance(clearance: Clearance, path: str | os.PathLike[str],
                    format: str | None = None) -> None:
    """Write ``clearance`` to ``path`` (atomically) as CSV or JSON (default: from the suffix)."""
    fmt = format or Path(path).suffix.lstrip(".").lower()
    if fmt not in CLEARANCE_FILE_FORMATS:
        raise FileFormatError(f"cannot tell the format from the name; give format= or a "
                              f"name ending in .{' or .'.join(CLEARANCE_FILE_FORMATS)}",
                              file=path, field="format")
    with atomic_write(path, "w") as handle:
        handle.write(clearance_text(clearance, fmt))


def clearance_text(clearance: Clearance, format: str = "csv") -> str:
    """``clearance`` as the text of a CSV or JSON file."""
    if format not in CLEARANCE_FILE_FORMATS:
        raise FileFormatError(f"expected one of {', '.join(CLEARANCE_FILE_FORMATS)}, got "
                              f"{format!r}", field="format")
    seconds = clearance.seconds
    times = [np.nan] if seconds is None else seconds.tolist()
    rows = [[time, distance, *pair, *a, *b] for time, distance, pair, a, b in zip(
        times, clearance.distance.tolist(), clearance.closest.tolist(),
        clearance.point_a.tolist(), clearance.point_b.tolist(), strict=True)]
    reference = (None if clearance.reference_time is None
                 else format_timestamp_iso(clearance.reference_time))
    if format == "json":
        records = [dict(zip(CLEARANCE_COLUMNS, row, strict=True)) for row in rows]
        for record in records:
            if np.isnan(record["time_s"]):
                record["time_s"] = None
        document = {"frames_a": list(clearance.frames_a), "frames_b": list(clearance.frames_b),
                    "excluded": [list(pair) for pair in clearance.excluded],
                    "fixed_together": [list(pair) for pair in clearance.fixed_together],
                    "geometry": clearance.geometry, "reference_time": reference,
                    "units": {"time_s": "s", "distance_m point_*_m": "m",
                              "point axes": "the tree's root"},
                    "samples": records}
        return json.dumps(document, indent=1) + "\n"
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    time_column = "time_s" if reference is None else f"time_s_after_{reference}"
    writer.writerow([time_column, *CLEARANCE_COLUMNS[1:]])
    for row in rows:
        writer.writerow([repr(value) if isinstance(value, float) else value for value in row])
    return text.getvalue()
