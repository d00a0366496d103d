"""pint quantities (as weldx users write them), converted to pinframes' units.

Lengths become metres, angles radians, times seconds, and quaternions and rotation matrices
must be plain numbers. pint stays optional: it is never imported here. A value is a
quantity when its type comes from the ``pint`` package; anything else passes through
unchanged, as a number already in pinframes' unit. A quantity of another kind (a length
given as an angle) is refused with the caller's error class.
"""

from __future__ import annotations

from typing import Any

from ..errors import InvalidPoseError, InvalidTimeError, PinframesError

__all__ = ["is_quantity", "magnitude_in", "metres", "radians", "seconds"]

_KINDS = {"meter": "a length", "radian": "an angle", "second": "a time",
          "meter / second": "a speed", "hertz": "a frequency",
          "dimensionless": "plain numbers"}


def is_quantity(value: object) -> bool:
    """True when ``value`` is a pint quantity (judged by its type's module, no import)."""
    return type(value).__module__.split(".")[0] == "pint" and hasattr(value, "to")


def magnitude_in(value: Any, unit: str, field: str,
                 error: type[PinframesError] = InvalidPoseError) -> Any:
    """``value``'s magnitude in ``unit`` (``"meter"``, ``"radian"``, ``"second"``,
    ``"meter / second"``, ``"hertz"`` or ``"dimensionless"``) when it is a pint quantity,
    else ``value`` unchanged.

    A quantity that cannot be converted (a length for an angle) is an ``error`` at ``field``
    naming its unit. Angles accept plain dimensionless quantities, as pint does.
    """
    if not is_quantity(value):
        return value
    try:
        return value.to(unit).magnitude
    except Exception as exc:  # pint's DimensionalityError, without importing pint
        if type(exc).__name__ != "DimensionalityError":
            raise
        raise error(f"expected {_KINDS[unit]}, got a quantity in {value.units!s} "
                    f"({value.dimensionality!s})", field=field) from None


def metres(value: Any, field: str, error: type[PinframesError] = InvalidPoseError) -> Any:
    """``value`` in metres (see :func:`magnitude_in`)."""
    return magnitude_in(value, "meter", field, error)


def radians(value: Any, field: str, error: type[PinframesError] = InvalidPoseError) -> Any:
    """``value`` in radians (see :func:`magnitude_in`): ``Q_(90, "deg")`` gives pi / 2."""
    return magnitude_in(value, "radian", field, error)


def seconds(value: Any, field: str) -> Any:
    """``value`` in seconds (see :func:`magnitude_in`), an :class:`InvalidTimeError` for a
    quantity that is not a time."""
    return magnitude_in(value, "second", field, InvalidTimeError)
