"""The fastest squared path speed at each sample of a path, by reachability (TOPP-RA's scheme).

The path parameter ``s`` is timed through ``x = (ds/dt)^2`` at the samples, with a constant
``u = d2s/dt2`` on each segment, so ``x`` grows linearly along it: ``x(s_k + r) = x_k + 2 u r``.
A joint's velocity is ``q'(s) ds/dt`` and its acceleration ``q''(s) x + q'(s) u``; on each
segment they are bounded at its start, middle and end (the accelerations) and at its middle
and at every sample (the velocities), which makes every bound a linear inequality
``c x_k + d u_k <= e`` with ``e > 0`` in the segment's own ``(x_k, u_k)``.

The backward pass finds, from the end at rest, the largest ``x_k`` from which the rest of the
path can still be braked within the bounds (the controllable sets ``[0, X_k]``); the forward
pass starts at rest and takes on each segment the largest ``u_k`` the bounds allow without
leaving those sets. Every step is a minimum of a few affine functions of the previous ``x``:
the divisions are arranged so that a joint whose ``q'`` vanishes gives a bound on ``x`` alone.
"""

from __future__ import annotations

import numpy as np

from ...errors import JointError
from ._clamped_chain import chain
from ._timing_grid import TimingGrid

__all__ = ["squared_path_speeds"]

_FRACTIONS = (0.0, 0.5, 1.0)
"""Where on each segment the joint accelerations are bounded."""

_BETWEEN = (0.25, 0.75)
"""Where on each segment the joints are measured after timing: a joint's acceleration is a
parabola on a segment, whose largest excess over its values at ``_FRACTIONS`` is near these."""

_EXCESS = 5e-3
"""How far (a part of the limit) a joint may go over its limit between the bounded points
before its limits on that segment are tightened and the path timed again."""

_RETIMINGS = 4
"""How often at most the path is timed again with tightened limits."""

_NEWTON_STEPS = 8
"""How many Newton steps find the largest feasible ``x`` of a segment before every pair of
its bounds is tried instead."""

_NEGLIGIBLE_RATE = 1e-6
"""A bound whose ``u`` coefficient is below this part of its ``x`` coefficient (times the
segment's double length) bounds ``x`` alone in the forward pass (no cancellation)."""


def squared_path_speeds(grid: TimingGrid, velocity: np.ndarray, acceleration: np.ndarray,
                        max_parameter_speed: float | None) -> np.ndarray:
    """The time-optimal ``(ds/dt)^2`` at each grid point, 0 at both ends.

    The joints are bounded at the grid points and the middle of each segment, then measured
    at its quarters: a segment on which a joint goes over its limit by more than
    :data:`_EXCESS` gets that joint's limits there tightened by the excess, and the path is
    timed again (at most :data:`_RETIMINGS` times).

    Raises
    ------
    JointError
        A stretch of the path on which no joint moves and no ``max_parameter_speed`` bounds
        the path speed (it would be crossed in no time).
    """
    sample_bound = _sample_bounds(grid.slopes(), velocity, max_parameter_speed)
    shape = grid.lengths.shape + velocity.shape
    segment_velocity = np.broadcast_to(velocity, shape)
    segment_acceleration = np.broadcast_to(acceleration, shape)
    for _ in range(_RETIMINGS):
        squared = _timed(grid, segment_velocity, segment_acceleration, sample_bound)
        speed_excess, acceleration_excess = _excess(grid, squared, velocity, acceleration)
        if max(speed_excess.max(), acceleration_excess.max()) <= 1 + _EXCESS:
            return squared
        segment_velocity = segment_velocity / np.maximum(speed_excess, 1.0)
        segment_acceleration = segment_acceleration / np.maximum(acceleration_excess, 1.0)
    return _timed(grid, segment_velocity, segment_acceleration, sample_bound)


def _timed(grid: TimingGrid, velocity: np.ndarray, acceleration: np.ndarray,
           sample_bound: np.ndarray) -> np.ndarray:
    """One timing: the backward and forward passes with limits ``(K, n)`` per segment."""
    double = 2 * grid.lengths
    lower, upper = _segment_bounds(grid, velocity, acceleration)
    static = _static_bounds(lower, upper, double, sample_bound[:-1])
    limits = _backward(static, *_braking(lower, double))
    if not np.all(np.isfinite(limits)):
        first = int(np.flatnonzero(~np.isfinite(limits))[0])
        raise JointError(
            f"no joint moves on the path from parameter {grid.parameters[first]:g} on, so "
            "nothing bounds its speed; give max_parameter_speed", field="positions")
    return _forward(limits, *_pushing(upper, double))


def _excess(grid: TimingGrid, squared: np.ndarray, velocity: np.ndarray,
            acceleration: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each joint's largest velocity and acceleration over its limit (a ratio, ``(K, n)``)
    at the quarters of each segment, timed by ``squared``."""
    rate = (np.diff(squared) / (2 * grid.lengths))[:, None]
    speed = np.zeros(rate.shape[:1] + velocity.shape)
    change = np.zeros_like(speed)
    for fraction in _BETWEEN:
        first, second = grid.rates(fraction)
        here = (squared[:-1] + 2 * fraction * grid.lengths * rate[:, 0])[:, None]
        speed = np.maximum(speed, np.abs(first) * np.sqrt(here))
        change = np.maximum(change, np.abs(second * here + first * rate))
    return speed / velocity, change / acceleration


def _segment_bounds(grid: TimingGrid, velocity: np.ndarray, acceleration: np.ndarray,
                    ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """Every bound of every segment as ``(c, d, e)``, each ``(K, m)``: those that bound ``u``
    from below (``d <= 0``) and from above (``d >= 0``), for limits ``(K, n)``."""
    lengths = grid.lengths[:, None]
    cs, ds = [], []
    for fraction in _FRACTIONS:
        first, second = grid.rates(fraction)
        # acceleration q'' (x + 2 u r) + q' u at r = fraction * length, within +- a
        rate = 2 * fraction * lengths * second + first
        sign = np.where(rate >= 0, 1.0, -1.0)
        cs.append(sign * second)
        ds.append(sign * rate)
    accelerations = np.concatenate([acceleration] * len(_FRACTIONS), axis=1)
    lower = (-np.concatenate(cs, axis=1), -np.concatenate(ds, axis=1), accelerations)
    # velocity at the middle: q'^2 (x + u length) <= v^2
    middle = grid.rates(0.5)[0] ** 2
    upper = (np.concatenate([*cs, middle], axis=1),
             np.concatenate([*ds, middle * lengths], axis=1),
             np.concatenate([accelerations, velocity**2], axis=1))
    return lower, upper


def _sample_bounds(slopes: np.ndarray, velocity: np.ndarray,
                   max_parameter_speed: float | None) -> np.ndarray:
    """Shape ``(N,)``: the largest ``x`` at each sample from the joint velocities and the
    path's own speed limit."""
    with np.errstate(divide="ignore"):
        bound = np.min(velocity**2 / slopes**2, axis=1)
    if max_parameter_speed is not None:
        bound = np.minimum(bound, max_parameter_speed**2)
    return bound


def _static_bounds(lower: tuple[np.ndarray, ...], upper: tuple[np.ndarray, ...],
                   double: np.ndarray, start: np.ndarray) -> np.ndarray:
    """Shape ``(K,)``: the largest ``x_k``, at most ``start``, for which some ``u_k`` keeps
    every bound of the segment and ``x_{k+1} >= 0``, whatever follows.

    Below that ``x`` the bounds on ``u`` from below (a convex function of ``x``, their
    maximum) stay under those from above (a concave one), so the gap between them is concave
    and positive at 0. Newton's method from the right on that gap, one pair of bounds at a
    time, comes down onto where it closes in a few steps; a segment it has not settled in
    :data:`_NEWTON_STEPS` gets every pair of its bounds crossed instead.
    """
    # bounds divided by their e > 0: c x + d u <= 1
    c_low, d_low = (part / lower[2] for part in lower[:2])
    c_up, d_up = (part / upper[2] for part in upper[:2])
    # an upper bound on u above -x / (2 length), the u that stops at the segment's end, and
    # bounds on x alone
    stops = np.max(c_up - d_up / double[:, None], axis=1, initial=0.0)
    alone = np.max(np.where(d_low == 0, c_low, 0.0), axis=1, initial=0.0)
    bound = np.minimum(start, _inverse(np.maximum(stops, alone)))
    rows = np.flatnonzero(np.isfinite(bound))
    unsettled = np.flatnonzero(~np.isfinite(bound))
    for _ in range(_NEWTON_STEPS):
        if rows.size == 0:
            break
        here = bound[rows, None]
        c_l, d_l, c_u, d_u = c_low[rows], d_low[rows], c_up[rows], d_up[rows]
        with np.errstate(divide="ignore", invalid="ignore"):
            lows = np.where(d_l < 0, (1 - c_l * here) / d_l, -np.inf)
            highs = np.where(d_u > 0, (1 - c_u * here) / d_u, np.inf)
        index = np.arange(rows.size)
        low, high = lows.argmax(axis=1), highs.argmin(axis=1)
        open_gap = lows[index, low] <= highs[index, high]
        c_l, d_l = c_l[index, low], d_l[index, low]
        c_u, d_u = c_u[index, high], d_u[index, high]
        # where the two lines cross: (c_l d_u - c_u d_l) x = d_u - d_l
        with np.errstate(divide="ignore", invalid="ignore"):
            crossing = (d_u - d_l) / (c_l * d_u - c_u * d_l)
        moves = ~open_gap & (crossing < here[:, 0] * (1 - 1e-12))
        bound[rows[~open_gap]] = np.minimum(bound[rows[~open_gap]], crossing[~open_gap])
        rows = rows[moves]
    unsettled = np.concatenate([unsettled, rows])
    if unsettled.size:
        bound[unsettled] = np.minimum(bound[unsettled], _crossed_pairs(
            c_low[unsettled], d_low[unsettled], c_up[unsettled], d_up[unsettled]))
    return bound


def _crossed_pairs(c_low: np.ndarray, d_low: np.ndarray, c_up: np.ndarray,
                   d_up: np.ndarray) -> np.ndarray:
    """The largest ``x`` at which no lower bound on ``u`` passes an upper one, from every
    pair of bounds (``c x + d u <= 1``, lower ``(K, m)``, upper ``(K, p)``)."""
    # a pair: (c_l d_u - c_u d_l) x <= d_u - d_l, whose right side is > 0; the largest ratio
    # of the two sides over every pair is 1 / (the bound on x)
    ratio = np.multiply(c_low[:, :, None], d_up[:, None, :])
    ratio -= c_up[:, None, :] * d_low[:, :, None]
    right = np.subtract(d_up[:, None, :], d_low[:, :, None])
    np.maximum(right, np.finfo(float).tiny, out=right)
    ratio /= right
    return _inverse(ratio.max(axis=(1, 2), initial=0.0))


def _inverse(ratio: np.ndarray) -> np.ndarray:
    """``1 / ratio`` where it is positive, else no bound (inf)."""
    positive = ratio > 0
    return np.where(positive, 1 / np.where(positive, ratio, 1.0), np.inf)


def _braking(lower: tuple[np.ndarray, ...], double: np.ndarray,
             ) -> tuple[np.ndarray, np.ndarray]:
    """The backward step's affine pieces ``x_k <= P + Q x_{k+1}`` (``(K, m)`` each): a lower
    bound on ``u`` that still reaches ``x_{k+1}``."""
    c, d, e = lower
    coefficient = double[:, None] * c - d
    positive = coefficient > 0
    safe = np.where(positive, coefficient, 1.0)
    return (np.where(positive, double[:, None] * e / safe, np.inf),
            np.where(positive, -d / safe, 0.0))


def _pushing(upper: tuple[np.ndarray, ...], double: np.ndarray,
             ) -> tuple[np.ndarray, np.ndarray]:
    """The forward step's affine pieces ``x_{k+1} <= F + G x_k`` (``(K, m)`` each): an upper
    bound on ``u`` times the segment's double length."""
    c, d, e = upper
    steep = d > _NEGLIGIBLE_RATE * double[:, None] * np.abs(c)
    safe = np.where(steep, d, 1.0)
    return (np.where(steep, double[:, None] * e / safe, np.inf),
            np.where(steep, 1 - double[:, None] * c / safe, 0.0))


def _backward(static: np.ndarray, offsets: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    """Shape ``(N,)``: the largest ``x`` at each sample from which the path's end is reached at
    rest (0 at the end)."""
    return chain(static[::-1], offsets[::-1], slopes[::-1])[::-1]


def _forward(limits: np.ndarray, offsets: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    """Shape ``(N,)``: from rest, the largest ``x`` at each next sample within ``limits``."""
    return chain(limits[1:], offsets, slopes)
