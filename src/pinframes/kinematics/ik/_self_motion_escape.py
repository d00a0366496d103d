"""A sample lost with a joint on its limit, reached along another self-motion.

With more joints than the task has rows (a 7-axis arm), the configurations that put the tool
on one target form a self-motion (a circle for a 7-axis arm and a whole pose), and the joint
limits cut it into stretches. Tracked sample by sample, the solution stays on its stretch;
when a limit closes that stretch while another stays open (the path's own configuration
lies there) the sample is lost with a joint on the limit, although it is reachable. Such a
sample is solved again from the last reached solution moved along the self-motion's
directions there (the null space of the task's rows), :data:`REACHES` radians for the
joint that moves most, both ways; of the starts that reach the target, the solution that
moves the joints least (largest change of one joint) is taken. The step to it is a jump,
reported as one (``JointSolution.jumps``) unless the path's solve backwards from it
(:mod:`._jump_bridge`) connects it with the samples before.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ._bounded_step import JointLimits

__all__ = ["REACHES", "escape_along_self_motion"]

FloatArray = NDArray[np.float64]

Solved = tuple[FloatArray, float, float, bool, float]
"""As :data:`._newton_tracking.Solved`: a solution, its errors, whether reached, a margin."""

REACHES = (0.3, 0.7, 1.2, 2.0, 3.0)
"""How far the starts move along the self-motion: radians (or metres) of the joint that
moves most, tried in this order; the first that reaches the target ends the search."""


def escape_along_self_motion(solve: Callable[[FloatArray], Solved], limits: JointLimits,
                             rows: FloatArray, last: FloatArray) -> Solved | None:
    """The sample solved by ``solve`` from ``last`` (n,) moved along the null space of the
    task's ``rows`` (m, n) at ``last`` (see the module docstring), within the ``limits``;
    None when no start reaches its target or there is no null space."""
    count, joints = rows.shape
    if joints <= count:
        return None
    directions = np.linalg.svd(rows)[2][count:]  # an orthonormal basis of the null space
    for reach in REACHES:
        found: list[tuple[float, Solved]] = []
        for direction in directions:
            direction = direction * (reach / np.abs(direction).max())
            for start in (last + direction, last - direction):
                solved = solve(limits.clipped(start))
                if solved[3]:
                    found.append((float(np.abs(solved[0] - last).max()), solved))
        if found:
            return min(found, key=lambda pair: pair[0])[1]
    return None
