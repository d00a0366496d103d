"""Length units by name, as metres per unit: the one table of the file readers (weldx ASDF
units) and the command line (a CSV column's ``_mm``).

Long names as pint writes them (``millimeter``) and their symbols (``mm``); a name is looked
up without case or surrounding spaces.
"""

from __future__ import annotations

__all__ = ["LENGTH_SYMBOLS", "METRES_PER_UNIT", "metres_per_length_unit"]

METRES_PER_UNIT: dict[str, float] = {
    "meter": 1.0, "metre": 1.0, "m": 1.0,
    "kilometer": 1e3, "km": 1e3,
    "decimeter": 1e-1, "dm": 1e-1,
    "centimeter": 1e-2, "cm": 1e-2,
    "millimeter": 1e-3, "mm": 1e-3,
    "micrometer": 1e-6, "um": 1e-6, "µm": 1e-6, "micron": 1e-6,
    "nanometer": 1e-9, "nm": 1e-9,
    "inch": 0.0254, "in": 0.0254,
    "foot": 0.3048, "ft": 0.3048,
}
"""Metres in one unit of each length unit pinframes reads."""

LENGTH_SYMBOLS = ("m", "km", "dm", "cm", "mm", "um", "nm", "in", "ft")
"""The units' short names, as messages list them."""


def metres_per_length_unit(unit: str) -> float | None:
    """Metres in one ``unit`` (any case, spaces around ignored); None for an unknown one."""
    return METRES_PER_UNIT.get(unit.strip().lower())
