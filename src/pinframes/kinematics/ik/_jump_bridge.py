"""Jumps bridged and lost stretches recovered. Where the solved path steps far more than
usual between two reached samples (``joint_jumps``), the samples before the jump are solved
again backwards from the sample after it, and over the stretch where the two solutions
differ the joints are taken from the one to the other, each sample put back on its target
by Newton: led sample by sample from the one before (a share of the way left to the
backward solution), or blended in proportion to the time, whichever steps least.

This is what keeps a path that rests in a singular configuration on its way: a UR5 with
wrist 2 at 0 while wrists 1 and 3 turn can split the turn between them in any way, and
where it leaves the singularity only one split fits; the forward solve learns which only
there (a jump), the backward solve knows it from the start. The bridge moves the split
across the resting stretch instead, where the task leaves it free (the samples stay on
their targets). A bridge is kept only when every sample it changes is reached and its
largest step is below the jump's and within the jump bar; a flip between two branches that
no such stretch joins stays, reported as a jump.

Before that, a stretch of samples not reached that ends in a reached sample (the solver
found its way back) is solved backwards from that sample: a 7-axis arm whose self-motion
walked a joint onto its limit comes back along the way the later samples take, and the
samples it reaches take its solutions; the jump where the stretch began is then bridged as
any other.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import numpy as np
from numpy.typing import NDArray

from ._newton_tracking import Solution, Tracked, TrackingProblem, solve_again
from ._path_chunks import PathToSolve, problem_of, track_in_chunks
from .joint_jumps import jump_bar, jumps_of

__all__ = ["BACK_SAMPLES", "bridged_jumps"]

FloatArray = NDArray[np.float64]

BACK_SAMPLES = 1024
"""Samples solved backwards from a jump at most."""

AGREE = 1e-6
"""Radians or metres by which the backward and forward solutions of a sample may differ and
still be one (the stretch to blend starts after the last such sample)."""


def bridged_jumps(request: PathToSolve, tracked: Tracked, factor: float, frame: str
                  ) -> Tracked:
    """``tracked`` (the solutions of ``request``'s samples) with its jumps bridged where a
    bridge holds (see the module docstring); changed in place."""
    _recover_lost_stretches(request, tracked, frame)
    bar = jump_bar(tracked.positions, factor)
    for after in jumps_of(tracked.positions, factor).tolist():
        if tracked.reached[after - 1] and tracked.reached[after]:
            _bridge(request, tracked, after, bar, frame)
    return tracked


def _recover_lost_stretches(request: PathToSolve, tracked: Tracked, frame: str) -> None:
    """Each stretch of samples not reached that ends in a reached one, solved again
    backwards from that one: the samples it reaches take its solutions (in place; the jump
    where the stretch began is then bridged as any other)."""
    reached = tracked.reached
    ends = np.flatnonzero(reached[1:] & ~reached[:-1]) + 1  # reached after a miss
    for end in ends.tolist():
        begin = end - 1
        while begin > 0 and not reached[begin - 1]:
            begin -= 1
        if begin == 0:
            continue  # lost from the first sample: the start's business
        rows = np.arange(end - 1, begin - 1, -1)
        back = _backwards(request, rows, tracked.positions[end], frame)
        found = rows[back.reached]
        tracked.positions[found] = back.positions[back.reached]
        tracked.position_error[found] = back.position_error[back.reached]
        tracked.orientation_error[found] = back.orientation_error[back.reached]
        tracked.reached[found] = True
        tracked.measured[found] = back.measured[back.reached]


def _backwards(request: PathToSolve, rows: NDArray[np.intp], start: FloatArray, frame: str
               ) -> Tracked:
    """The samples ``rows`` of ``request`` (in reverse order) solved by the numeric solver
    from ``start``, the solution of the sample after them."""
    back, _ = track_in_chunks(request.at(rows), start, False, False, frame)
    return back


def _bridge(request: PathToSolve, tracked: Tracked, after: int, bar: float, frame: str
            ) -> None:
    """The jump into sample ``after`` bridged in ``tracked`` when it holds."""
    positions = tracked.positions
    first = max(0, after - BACK_SAMPLES)
    rows = np.arange(after - 1, first - 1, -1)  # the samples before the jump, backwards
    back = _backwards(request, rows, positions[after], frame)
    backward, reached = back.positions[::-1], back.reached[::-1]  # samples first..after-1
    apart = np.abs(backward - positions[first:after]).max(axis=1)
    agreeing = np.flatnonzero(apart <= AGREE)
    begin = first + (int(agreeing[-1]) + 1 if agreeing.shape[0] else 0)
    if begin >= after or not reached[begin - first:].all():
        return
    problem = problem_of(request.at(slice(begin, after)))
    before = positions[max(begin - 1, 0)]
    jump = float(np.abs(positions[after] - positions[after - 1]).max())
    best: tuple[float, list[Solution]] | None = None
    count = after - begin
    backward, forward = backward[begin - first:], positions[begin:after]
    times = request.plan.sample_times[max(begin - 1, 0):after + 1].astype(float)
    weights = (times[-count - 1:-1] - times[0]) / (times[-1] - times[0])

    def led(index: int, theta: FloatArray) -> FloatArray:  # from the solution before it
        return theta + (backward[index] - theta) / (count - index)  # a share of the way left

    def blended(index: int, _: FloatArray) -> FloatArray:  # in proportion to the time
        return forward[index] + weights[index] * (backward[index] - forward[index])

    for guides in (_on_targets(problem, before, count, led),
                   _on_targets(problem, before, count, blended)):
        solved = list(guides)
        if len(solved) < count:  # a sample missed
            continue
        steps = np.diff(np.vstack([before, *(solution[0] for solution in solved),
                                   positions[after]]), axis=0)
        step = float(np.abs(steps).max())
        if step < min(jump, bar * (1.0 + 1e-12)) and (best is None or step < best[0]):
            best = step, solved
    if best is None:
        return
    for index, (theta, position, orientation, _) in enumerate(best[1], start=begin):
        positions[index] = theta
        tracked.position_error[index], tracked.orientation_error[index] = position, orientation
        tracked.measured[index] = True


def _on_targets(problem: TrackingProblem, before: FloatArray, count: int,
                guess: Callable[[int, FloatArray], FloatArray]) -> Iterator[Solution]:
    """The ``count`` samples of ``problem`` put back on their targets by Newton, each from
    ``guess(index, previous)`` (``previous`` the solution before it, the first's
    ``before``); stops at a miss."""
    theta = before
    for index in range(count):
        solution = solve_again(problem, index, guess(index, theta), serve=False)
        if not solution[3]:
            return
        yield solution
        theta = solution[0]
