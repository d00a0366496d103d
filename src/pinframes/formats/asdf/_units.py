"""Length units of weldx ASDF files, as metres per unit.

weldx writes pint's long names (``millimeter``, ``meter``); older files and hand-written ones
may use the short symbols. Coordinates without a unit are millimetres (docs/asdf-format.md).
"""

from __future__ import annotations

__all__ = ["DEFAULT_LENGTH_UNIT", "METRES_PER_UNIT", "metres_per_unit"]

DEFAULT_LENGTH_UNIT = "millimeter"

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


def metres_per_unit(unit: str | None) -> float | None:
    """Metres in one ``unit`` (``None`` means millimetres); ``None`` for an unknown unit."""
    if unit is None:
        return METRES_PER_UNIT[DEFAULT_LENGTH_UNIT]
    return METRES_PER_UNIT.get(unit.strip().lower())
