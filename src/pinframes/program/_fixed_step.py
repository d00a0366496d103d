"""Planned moves laid end to end on the program's fixed step: one joint trajectory."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..values.motion import MoveRecord
from ._planned_moves import PlannedMove, steps_of

__all__ = ["Assembled", "assemble"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Assembled:
    """The samples of a whole program (T = steps + 1) and each move's record and rows."""

    seconds: FloatArray
    positions: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    reached: NDArray[np.bool_]
    records: tuple[MoveRecord, ...]
    rows: tuple[tuple[int, int], ...]
    """Per move, its first and last sample (inclusive)."""


def assemble(moves: list[PlannedMove], start: FloatArray, step: float) -> Assembled:
    """``moves`` from ``start``, each stretched to a whole number of ``step`` seconds."""
    counts = [steps_of(move.duration, step) for move in moves]
    total = sum(counts)
    width = start.shape[0]
    positions = np.empty((total + 1, width))
    positions[0] = start
    velocities = np.zeros((total + 1, width))
    accelerations = np.zeros((total + 1, width))
    reached = np.ones(total + 1, bool)
    records, rows = [], []
    first = 0
    for move, count in zip(moves, counts, strict=True):
        last = first + count
        speed = None
        if count:
            local = np.arange(count + 1, dtype=np.float64) * step
            sampled = move.sampled(local, count * step)
            positions[first:last + 1] = sampled[0]
            velocities[first:last + 1] = sampled[1]
            accelerations[first:last + 1] = sampled[2]
            reached[first:last + 1] &= sampled[3]
            speed = sampled[4]
        records.append(move.record(first * step, last * step, speed))
        rows.append((first, last))
        first = last
    return Assembled(np.arange(total + 1, dtype=np.float64) * step, positions, velocities,
                     accelerations, reached, tuple(records), tuple(rows))
