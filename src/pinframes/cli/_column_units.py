"""The unit a CSV column names after its label: ``x_mm`` is ``x`` in millimetres.

A column name is ``LABEL`` or ``LABEL_UNIT``, split at the first underscore (``vx_m_s`` is
``vx`` in ``m_s``). Points need lengths (``m``, ``cm``, ``mm``, ``in``... the units of
:mod:`pinframes.values.length_units`), or no unit at all, which is metres as everywhere in
pinframes. Directions only rotate, so their unit (``m_s``,
``rad_s``, none) does not change the numbers, but all three columns must share it. Names
with a unit pinframes does not know, and columns in different units, are refused.
"""

from __future__ import annotations

from ..errors import FileFormatError
from ..values.length_units import LENGTH_SYMBOLS, metres_per_length_unit

__all__ = ["metres_per_unit"]


def metres_per_unit(names: list[str], points: bool, file: str) -> float:
    """The factor from the columns' common unit to metres (1 for directions).

    Raises :class:`FileFormatError` naming ``file`` and the column when the columns' units
    differ, or when a column of points carries a unit that is not a known length.
    """
    units = [_unit(name) for name in names]
    for name, unit in zip(names[1:], units[1:], strict=True):
        if unit != units[0]:
            raise FileFormatError(
                f"the columns are in different units ({names[0]!r}: {_spoken(units[0])}, "
                f"{name!r}: {_spoken(unit)}): give all three in one unit", file=file,
                field=name)
    if not points:
        return 1.0
    unit = units[0]
    if unit is None:
        label = names[0]
        if not label.isidentifier():
            raise FileFormatError(
                f"no unit pinframes knows in {label!r}: name the columns LABEL_UNIT with a "
                f"length unit ({_known()}), e.g. x_mm", file=file, field=label)
        return 1.0
    factor = metres_per_length_unit(unit)
    if factor is None:
        hint = ("; directions (velocities, normals) only rotate: pass --vectors"
                if "_" in unit else "")
        raise FileFormatError(
            f"'{unit}' is not a length unit pinframes knows ({_known()}){hint}", file=file,
            field=names[0])
    return factor


def _unit(name: str) -> str | None:
    label, separator, unit = name.partition("_")
    return unit if separator and label else None


def _spoken(unit: str | None) -> str:
    return "no unit (metres)" if unit is None else repr(unit)


def _known() -> str:
    return ", ".join(LENGTH_SYMBOLS)
