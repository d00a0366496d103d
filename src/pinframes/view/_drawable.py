"""What the 3-D page can draw: finite numbers within :data:`MAX_DRAWN_DISTANCE_M`.

The page stores positions as float32 for three.js and frames its camera on everything it
shows: one NaN radius, a box of 1e308 m or a frame 1e200 m away would leave the page blank
(or make its data invalid JSON) while the page was reported written. Such geometry and
frames are left out with a :class:`GeometryWarning` naming them, and the rest is drawn.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import warn_at_caller
from ._geometry import GeometryWarning, LinkGeometry

__all__ = ["MAX_DRAWN_DISTANCE_M", "drawable", "drawable_frames", "drawable_geometry"]

MAX_DRAWN_DISTANCE_M = 1e6
"""The farthest a drawn point may be from the drawing frame (1,000 km: float32 still places
it to 6 cm)."""


def drawable(values: np.ndarray) -> bool:
    """Whether every number of ``values`` (positions or 4x4 matrices, metres) is finite
    and at most :data:`MAX_DRAWN_DISTANCE_M` in size."""
    with np.errstate(invalid="ignore", over="ignore"):
        return bool(np.all(np.isfinite(values)) and np.all(np.abs(values)
                                                            <= MAX_DRAWN_DISTANCE_M))


def drawable_frames(matrices: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The frames whose placements (``(n, 4, 4)``, metres in the drawing frame) can be
    drawn; a warning for each other one."""
    kept = {}
    for frame, placements in matrices.items():
        if drawable(placements):
            kept[frame] = placements
        else:
            _warn(f"frame {frame!r} is not drawn: its position is not finite or farther than "
                  f"{MAX_DRAWN_DISTANCE_M:g} m from the drawing frame at some time")
    return kept


def drawable_geometry(geometry: Sequence[LinkGeometry], frames: dict[str, np.ndarray]
                      ) -> list[LinkGeometry]:
    """The pieces of ``geometry`` that can be drawn in the drawn ``frames``: finite
    vertices and placement, within :data:`MAX_DRAWN_DISTANCE_M`; a warning for the others
    (pieces of frames not drawn are left out silently: their frame's warning says it)."""
    kept = []
    for piece in geometry:
        if piece.frame not in frames:
            continue
        if drawable(piece.vertices) and drawable(piece.pose_in_frame):
            kept.append(piece)
        else:
            _warn(f"link {piece.link!r} ({piece.frame!r}): geometry {piece.source!r} is not "
                  "drawn: its size or placement is not finite or exceeds "
                  f"{MAX_DRAWN_DISTANCE_M:g} m")
    return kept


def _warn(message: str) -> None:
    warn_at_caller(message, GeometryWarning)
