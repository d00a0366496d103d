"""Numbers in URDF attributes (``xyz="0 0.1 0"``), checked as urdfdom checks them."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np

from ...errors import FileFormatError

__all__ = ["numbers"]

_COUNTS = {1: "a finite number", 3: "three finite numbers", 4: "four finite numbers"}


def numbers(element: ET.Element | None, attribute: str, count: int, source: str,
            link: str | None, field: str, default: tuple[float, ...] | None
             ) -> tuple[float, ...]:
    """``count`` finite numbers from ``element``'s ``attribute``; ``default`` when absent
    (None: the attribute is required)."""
    text = None if element is None else element.get(attribute)
    if text is None:
        if default is None:
            raise FileFormatError(f"missing {attribute!r}", file=source, frame=link,
                                  field=field)
        return default
    try:
        values = tuple(float(part) for part in text.split())
    except ValueError:
        values = ()
    if len(values) != count or not all(np.isfinite(values)):
        raise FileFormatError(f"expected {_COUNTS[count]}, got {text!r}", file=source,
                              frame=link, field=field)
    return values
