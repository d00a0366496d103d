"""Where a path is timed: its samples, with points added between them when they are few.

The reachability passes bound the joints at a finite set of path parameters; their result
is the closer to the time-optimum the finer that set. A path of fewer than
:data:`MIN_SEGMENTS` segments (a straight line given by its two ends) has each of them split
evenly into about its share of that number (by length).
"""

from __future__ import annotations

import numpy as np

from ._path_spline import PathSpline

__all__ = ["MIN_SEGMENTS", "TimingGrid"]

MIN_SEGMENTS = 200
"""The fewest segments a path is timed on."""


class TimingGrid:
    """The path parameters at which a path is timed, each within one segment of its spline.

    Attributes
    ----------
    spline : PathSpline
        The path.
    parameters : numpy.ndarray
        Shape ``(M,)``: the grid, increasing, holding every sample's parameter.
    lengths : numpy.ndarray
        Shape ``(M - 1,)``: each grid segment's length.
    samples : numpy.ndarray
        Shape ``(N,)``: where the path's samples are in the grid.
    """

    def __init__(self, spline: PathSpline) -> None:
        self.spline = spline
        lengths = spline.lengths
        share = lengths / (spline.parameters[-1] - spline.parameters[0])
        splits = (np.ones(lengths.size, dtype=int) if lengths.size >= MIN_SEGMENTS
                  else np.maximum(1, np.rint(share * MIN_SEGMENTS)).astype(int))
        # grid segment j lies in spline segment segments[j], offsets[j] into it
        self._segments = np.repeat(np.arange(lengths.size), splits)
        firsts = np.concatenate([[0], np.cumsum(splits)])
        part = np.arange(self._segments.size) - firsts[self._segments]
        step = lengths / splits
        self._offsets = part * step[self._segments]
        self.lengths = step[self._segments]
        self.parameters = np.append(spline.parameters[self._segments] + self._offsets,
                                    spline.parameters[-1])
        self.samples = firsts
        self._rates: dict[float, tuple[np.ndarray, np.ndarray]] = {}

    def rates(self, fraction: float) -> tuple[np.ndarray, np.ndarray]:
        """``dq/ds`` and ``d2q/ds2``, each ``(M - 1, n)``, at ``fraction`` of every grid
        segment (the segment's own side of a sample: at ``fraction=1`` the left limit)."""
        if fraction not in self._rates:
            _, first, second = self.spline.derivatives(
                self._segments, self._offsets + fraction * self.lengths)
            self._rates[fraction] = first, second
        return self._rates[fraction]

    def on_spline(self, segments: np.ndarray,
                  offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``q``, ``dq/ds`` and ``d2q/ds2``, each ``(T, n)``, at ``offsets (T,)`` into grid
        ``segments (T,)``."""
        return self.spline.derivatives(self._segments[segments], self._offsets[segments] + offsets)

    def slopes(self) -> np.ndarray:
        """Shape ``(M, n)``: ``dq/ds`` at every grid point."""
        first, _ = self.rates(0.0)
        return np.concatenate([first, self.spline.slopes[-1:]])
