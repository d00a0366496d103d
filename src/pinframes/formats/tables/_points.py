"""Point tables: the CSV tables of points that ``pinframes transform`` reads and writes,
known to the registry by their header only (so that such a file handed to a tree reader is
named for what it is)."""

from __future__ import annotations

from .._registry import FileFormat
from ..reading import InputFile

__all__ = ["POINT_TABLE_FORMAT"]


def _is_point_table(source: InputFile) -> bool:
    """A CSV table of points: a header of ``x``, ``y``, ``z`` columns (each may name its
    unit: ``x_mm``), perhaps after a time and a point column."""
    lines = [line for line in source.start().split(b"\n") if line.strip()]
    if not lines:
        return False
    cells = [cell.strip().decode("utf-8", "replace") for cell in lines[0].split(b",")]
    data = [cell for cell in cells if cell not in ("time_s", "time", "point")]
    return len(data) == 3 and all(cell == axis or cell.startswith(axis + "_")
                                  for cell, axis in zip(data, "xyz", strict=True))


POINT_TABLE_FORMAT = FileFormat(
    "csv", "CSV", (".csv",), kind="points", head_test=_is_point_table,
    looks_like="a CSV table of points (x, y, z columns), which 'pinframes transform' takes")
"""Points in CSV: no reader or writer of the registry, a content test only."""
