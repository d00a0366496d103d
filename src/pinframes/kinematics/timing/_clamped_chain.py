"""A chain of steps ``x_{i+1} = max(0, min(cap_i, min_j(a_ij + b_ij x_i)))`` from ``x_0 = 0``.

Both passes of the reachability timing are such a chain (the backward one read from the
end). Step by step it is a Python loop over the rows. Faster: pick in each row the piece ``j``
that is least at a guess of ``x_i``, so that every step is one clamped affine map
``y -> min(hi, max(lo, p + q y))``; such maps composed are again one, so the whole chain is
prefix compositions, found by doubling in ``log2(K)`` numpy passes. The pieces are picked
once more at the values found and the chain composed again; then every row is checked
against all its pieces, and from a row where the check fails the chain is stepped row by row
until it meets the composed values again (a value that reaches its cap, typically).
"""

from __future__ import annotations

import numpy as np

__all__ = ["chain"]

_AGREEMENT = 1e-10
"""How close (a part of the value) a composed value must come to the step from the one
before it to be taken."""


def chain(caps: np.ndarray, offsets: np.ndarray, slopes: np.ndarray) -> np.ndarray:
    """Shape ``(K + 1,)``: ``x_0 = 0`` and each next ``x`` from ``caps (K,)`` and the rows'
    affine pieces ``offsets + slopes x`` (``(K, m)``; an infinite offset is no piece)."""
    offsets = np.where(np.isinf(offsets), caps[:, None], offsets)
    if not np.all(np.isfinite(caps)):
        values = np.full(caps.size + 1, np.nan)  # nothing to meet: every row stepped
        values[0] = 0.0
        _step_until_met(values, 0, caps, offsets, slopes)
        return values
    rows = np.arange(caps.size)
    guess = np.concatenate([[0.0], caps[:-1]])
    with np.errstate(over="ignore", invalid="ignore"):
        for _ in range(2):
            picked = np.argmin(offsets + slopes * guess[:, None], axis=1)
            values = _composed(offsets[rows, picked], slopes[rows, picked], caps)
            guess = values[:-1]
        stepped = _steps(caps, offsets, slopes, values[:-1])
    # row i is right when x_{i+1} is the step from x_i; the chain is right up to a wrong row
    wrong = ~(np.abs(values[1:] - stepped) <= _AGREEMENT * np.abs(stepped))
    values[1:] = np.where(wrong, values[1:], stepped)
    row = 0
    while (failing := np.flatnonzero(wrong[row:])).size:
        row = _step_until_met(values, row + int(failing[0]), caps, offsets, slopes)
    return values


def _steps(caps: np.ndarray, offsets: np.ndarray, slopes: np.ndarray,
           previous: np.ndarray) -> np.ndarray:
    """Each row's step from its ``previous`` value, with every piece."""
    return np.maximum(0.0, np.minimum(caps, np.min(offsets + slopes * previous[:, None], axis=1)))


def _composed(offsets: np.ndarray, slopes: np.ndarray, caps: np.ndarray) -> np.ndarray:
    """Shape ``(K + 1,)``: the chain of one piece per row, by doubling its prefix maps."""
    p, q = offsets.copy(), slopes.copy()
    low, high = np.zeros_like(caps), caps.copy()
    shift = 1
    while shift < caps.size:
        # the map up to row k after the one up to row k - shift
        p_out, q_out, low_out, high_out = p[shift:], q[shift:], low[shift:], high[shift:]
        p_in, q_in, low_in, high_in = p[:-shift], q[:-shift], low[:-shift], high[:-shift]
        ends = (p_out + q_out * low_in, p_out + q_out * high_in)
        new_low = np.clip(np.minimum(*ends), low_out, high_out)
        new_high = np.clip(np.maximum(*ends), low_out, high_out)
        constant = new_high <= new_low
        new_p = np.where(constant, new_low, p_out + q_out * p_in)
        new_q = np.where(constant, 0.0, q_out * q_in)
        p[shift:], q[shift:], low[shift:], high[shift:] = new_p, new_q, new_low, new_high
        shift *= 2
    return np.concatenate([[0.0], np.clip(p, low, high)])


def _step_until_met(values: np.ndarray, row: int, caps: np.ndarray, offsets: np.ndarray,
                    slopes: np.ndarray) -> int:
    """Step the chain in ``values`` from ``row`` on, row by row, until a step agrees with the
    value already there; return the index of that value (``K`` at the end)."""
    current = float(values[row])
    for index in range(row, caps.size):
        pieces = zip(offsets[index].tolist(), slopes[index].tolist(), strict=True)
        current = max(0.0, min(float(caps[index]),
                               *[offset + slope * current for offset, slope in pieces]))
        met = abs(values[index + 1] - current) <= _AGREEMENT * abs(current)
        values[index + 1] = current
        if met:
            return index + 1
    return caps.size
