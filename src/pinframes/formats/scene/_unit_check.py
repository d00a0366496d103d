"""Numbers of a scene that are implausible in its units (metres, radians): a cell written in
millimetres or degrees is read, and said so once per file and kind of unit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ...errors import UnitWarning, warn_at_caller

__all__ = ["LARGEST_PLAUSIBLE_METRES", "UnitCheck"]

LARGEST_PLAUSIBLE_METRES = 100.0
"""A position further than this from its parent, in metres, is taken for millimetres: a
work cell spans a few metres, a factory hall some tens."""


class UnitCheck:
    """Collects, while a scene is read, the first position beyond
    :data:`LARGEST_PLAUSIBLE_METRES` and the first ``rpy`` angle beyond a full turn, and
    warns about each once (:meth:`warn`), naming the frame, the field and the likely unit."""

    def __init__(self, path: Path) -> None:
        self._path = path
        self._found: dict[str, str] = {}  # kind of unit: the message about its first field

    def lengths(self, values: NDArray[np.float64], frame: str | None, field: str) -> None:
        """Positions (..., 3) in metres relative to the frame's parent."""
        x, y, z = np.reshape(values, (-1, 3)).T
        distances = np.hypot(np.hypot(x, y), z)  # no overflow for coordinates near 1e308
        if distances.shape[0] and float(distances.max()) > LARGEST_PLAUSIBLE_METRES:
            self._note("length", frame, field, f"{float(distances.max()):.6g} m from its "
                       "parent, implausible in metres: are the lengths in millimetres? "
                       "(scene lengths are metres)")

    def angles(self, values: NDArray[np.float64], frame: str | None, field: str) -> None:
        """``rpy`` angles in radians."""
        largest = float(np.abs(values).max())
        if largest > 2.0 * math.pi:
            self._note("angle", frame, field, f"an angle of {largest:.6g} rad is more than a "
                       "full turn: are the angles in degrees? (scene angles are radians)")

    def warn(self) -> None:
        """One :class:`~pinframes.errors.UnitWarning` per kind of implausible number, about
        the first field found."""
        for message in self._found.values():
            warn_at_caller(message, UnitWarning)

    def _note(self, kind: str, frame: str | None, field: str, text: str) -> None:
        if kind not in self._found:
            where = [str(self._path)] + ([] if frame is None else [f"frame {frame!r}"])
            self._found[kind] = ": ".join([*where, f"field {field!r}", text])
