"""The steps of the reachability passes against brute force: the largest feasible squared
path speed of a segment against a scan, the composed chain against one step at a time."""

from __future__ import annotations

import numpy as np

from pinframes.kinematics.timing._clamped_chain import chain
from pinframes.kinematics.timing._reachability import _static_bounds


def scanned_bound(lower, upper, double, start, row, points=20001):
    """The largest x in [0, start] on a fine scan at which some u keeps every bound
    ``c x + d u <= e`` of the row and ``x + double u >= 0``: the u-interval is not empty."""
    xs = np.linspace(0.0, start, points)
    lows = [-xs / double]  # x_{k+1} >= 0
    highs = [np.full(points, np.inf)]
    for (c, d, e), into in ((lower, lows), (upper, highs)):
        for column in range(c.shape[1]):
            cc, dd, ee = c[row, column], d[row, column], e[row, column]
            if dd == 0:
                into.append(np.where(cc * xs <= ee, -np.inf if into is lows else np.inf,
                                     np.inf if into is lows else -np.inf))
            else:
                into.append((ee - cc * xs) / dd)
    feasible = np.max(lows, axis=0) <= np.min(highs, axis=0)
    return xs[np.flatnonzero(feasible)[-1]], xs[1] - xs[0]


def test_newton_on_the_gap_finds_the_scanned_bound():
    rng = np.random.default_rng(5)
    segments, joints = 30, 3
    c = rng.normal(0, 1, (segments, 2 * joints))
    d = np.abs(rng.normal(0, 1, (segments, 2 * joints)))
    d[::7, 0] = 0.0  # bounds on x alone
    e = rng.uniform(0.5, 2, (segments, 2 * joints))
    lower = (c[:, :joints], -d[:, :joints], e[:, :joints])
    upper = (c[:, joints:], d[:, joints:], e[:, joints:])
    double = rng.uniform(0.01, 0.1, segments)
    start = np.full(segments, 50.0)
    bounds = _static_bounds(lower, upper, double, start)
    assert np.sum(bounds < start) > segments // 2  # mostly the bounds, not the start, decide
    for row in range(segments):
        scanned, step = scanned_bound(lower, upper, double[row], start[row], row)
        assert scanned <= bounds[row] + 1e-9 < scanned + step + 1e-9


def stepped_chain(caps, offsets, slopes):
    """x_0 = 0, x_{i+1} = max(0, min(cap_i, min_j(a_ij + b_ij x_i))), one row at a time."""
    values = [0.0]
    for cap, row_offsets, row_slopes in zip(caps, offsets, slopes, strict=True):
        pieces = [a + b * values[-1] for a, b in zip(row_offsets, row_slopes, strict=True)
                  if np.isfinite(a)]
        values.append(max(0.0, min([cap, *pieces])))
    return np.array(values)


def test_the_composed_chain_is_the_stepped_one():
    rng = np.random.default_rng(6)
    rows, pieces = 700, 5
    # slowly varying pieces around x_{i+1} = x_i + 2 h u, some slopes negative, some missing
    drift = np.cumsum(rng.normal(0, 0.05, (rows, pieces)), axis=0)
    offsets = 0.02 + 0.01 * np.abs(drift)
    slopes = 1 + 0.3 * np.sin(drift)
    slopes[::11, 1] = -0.7
    offsets[::13, 2] = np.inf
    caps = 1.5 + np.sin(np.linspace(0, 20, rows))
    composed = chain(caps, offsets, slopes)
    np.testing.assert_allclose(composed, stepped_chain(caps, offsets, slopes), rtol=1e-9)
    caps[300] = np.inf  # nothing caps one row: stepped all the way
    np.testing.assert_allclose(chain(caps, offsets, slopes), stepped_chain(caps, offsets, slopes),
                               rtol=1e-9)
