"""Length units of weldx ASDF files, as metres per unit.

weldx writes pint's long names (``millimeter``, ``meter``); older files and hand-written ones
may use the short symbols (both in :mod:`pinframes.values.length_units`). Coordinates without
a unit are millimetres (docs/asdf-format.md).
"""

from __future__ import annotations

from ...values.length_units import METRES_PER_UNIT, metres_per_length_unit

__all__ = ["DEFAULT_LENGTH_UNIT", "METRES_PER_UNIT", "metres_per_unit"]

DEFAULT_LENGTH_UNIT = "millimeter"


def metres_per_unit(unit: str | None) -> float | None:
    """Metres in one ``unit`` (``None`` means millimetres); ``None`` for an unknown unit."""
    if unit is None:
        return METRES_PER_UNIT[DEFAULT_LENGTH_UNIT]
    return metres_per_length_unit(unit)
