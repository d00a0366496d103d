"""Joint positions along a path parameter, between samples: a C1 cubic Hermite curve.

Between two samples each joint follows the cubic whose ends are the samples and whose slopes
there are those of the parabola through the sample and its two neighbours (through the first
or last three samples at the ends; the chord when there are only two samples), so the curve is
continuous with its first derivative, reproduces a parabola exactly and needs no system of
equations. Between samples it is off a smooth path by the cube of their spacing.
"""

from __future__ import annotations

import numpy as np

__all__ = ["PathSpline"]


class PathSpline:
    """Joints ``q(s)`` through ``positions (N, n)`` at increasing ``parameters (N,)``.

    Attributes
    ----------
    parameters : numpy.ndarray
        Shape ``(N,)``: the samples' path parameter.
    positions : numpy.ndarray
        Shape ``(N, n)``: the joints there (rad or m).
    slopes : numpy.ndarray
        Shape ``(N, n)``: ``dq/ds`` there.
    """

    def __init__(self, positions: np.ndarray, parameters: np.ndarray) -> None:
        self.parameters = parameters
        self.positions = positions
        lengths = np.diff(parameters)[:, None]
        chords = np.diff(positions, axis=0) / lengths
        slopes = np.empty_like(positions)
        slopes[0], slopes[-1] = chords[0], chords[-1]
        if len(chords) > 1:  # the three-point slopes: of the parabola through three samples
            inner, outer = lengths[:-1], lengths[1:]
            slopes[1:-1] = (outer * chords[:-1] + inner * chords[1:]) / (inner + outer)
            slopes[0] = ((2 * inner[0] + outer[0]) * chords[0] - inner[0] * chords[1]) / (
                inner[0] + outer[0])
            slopes[-1] = ((2 * outer[-1] + inner[-1]) * chords[-1] - outer[-1] * chords[-2]) / (
                inner[-1] + outer[-1])
        self.slopes = slopes
        # q(s_k + r) = q_k + slope_k r + square_k r^2 + cube_k r^3 on segment k
        self._slopes = slopes[:-1]
        self._squares = (3 * chords - 2 * slopes[:-1] - slopes[1:]) / lengths
        self._cubes = (slopes[:-1] + slopes[1:] - 2 * chords) / lengths**2

    @property
    def lengths(self) -> np.ndarray:
        """Shape ``(N - 1,)``: each segment's length in the path parameter."""
        return np.diff(self.parameters)

    def derivatives(self, segments: np.ndarray,
                    offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``q``, ``dq/ds`` and ``d2q/ds2``, each ``(T, n)``, at ``offsets (T,)`` into
        ``segments (T,)`` (the path parameter minus the segment's first)."""
        r = offsets[:, None]
        slope, square, cube = self._slopes[segments], self._squares[segments], self._cubes[segments]
        position = self.positions[segments] + r * (slope + r * (square + r * cube))
        first = slope + r * (2 * square + 3 * r * cube)
        second = 2 * square + 6 * r * cube
        return position, first, second
