"""Lengths given as pint quantities (as weldx users write them), converted to metres.

pint stays optional: it is never imported here. A value is a quantity when its type comes
from the ``pint`` package; anything else passes through unchanged, as metres.
"""

from __future__ import annotations

from typing import Any

from ..errors import InvalidPoseError

__all__ = ["is_quantity", "metres"]


def is_quantity(value: object) -> bool:
    """True when ``value`` is a pint quantity (judged by its type's module, no import)."""
    return type(value).__module__.split(".")[0] == "pint" and hasattr(value, "to")


def metres(value: Any, field: str) -> Any:
    """``value`` in metres: a pint quantity's magnitude after conversion, else ``value``.

    A quantity that is not a length is an :class:`InvalidPoseError` at ``field``.
    """
    if not is_quantity(value):
        return value
    try:
        return value.to("meter").magnitude
    except Exception as exc:  # pint's DimensionalityError, without importing pint
        if type(exc).__name__ != "DimensionalityError":
            raise
        raise InvalidPoseError(f"expected a length, got a quantity in {value.units!s} "
                               f"({value.dimensionality!s})", field=field) from None
