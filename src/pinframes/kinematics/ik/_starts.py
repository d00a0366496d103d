"""Where a solve starts: the caller's seed, else several starts for the first sample, one taken.

A seed names joint values (a mapping by name, possibly partial, or one value per joint)
within the limits; the joints it leaves out start from their defaults. The default start is
the joints' own values at the first time (their trajectories), else their rest values. A
path that the arm can follow from one branch may be lost from another (an elbow down where
the path needs it up, a wrist whose turn runs into a limit), and a rest value may be a
singular configuration (a UR's stretched arm). So without a seed the first sample is solved
from the default start and from :data:`SPREAD_STARTS` fixed configurations spread over the
joint ranges (the same for every call: :data:`SPREAD_SEED`), these in the order of their
distance from the default start, until one is taken. Many starts are needed where the
ranges are wide: from far away a solve often stops on a limit (an ABB GoFa's joints turn
-180..180 degrees), so few starts end on a solution. A joint that may turn a whole turn
(:attr:`SolvedJoints.whole_turns`) is not stopped by its limits while a start is solved: it
turns the short way, and its solution is brought back into its range by whole turns (the
same pose). The distinct solutions
(:data:`SAME_SOLUTION` apart), at most :data:`TRACKED_SOLUTIONS` of them, are tracked along
the first stretch of samples in that order (the first chunk in which the path moves, led
by its first sample: see :mod:`._path_chunks`); the first that reaches every sample of it is
taken. Else, of those that follow the path furthest before their first miss, the one that
reaches the most of the stretch is taken (the earlier on ties). A given seed is the only
start.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ArgumentTypeError, InvalidDataError, JointError
from ...values.joint import Joint
from ...values.joint_trajectory import JointTrajectory
from .._plan import QueryPlan
from ._bounded_step import JointLimits
from ._flat import FlatFrame
from ._newton_tracking import Tracked, TrackingHistory, TrackingProblem, solve_again, track_targets
from ._solved_joints import SolvedJoints

__all__ = ["SAME_SOLUTION", "SPREAD_SEED", "SPREAD_STARTS", "TRACKED_SOLUTIONS", "first_start",
           "spread_starts", "track_from_the_best_start"]

FloatArray = NDArray[np.float64]

SPREAD_STARTS = 64
"""Starts spread over the joint ranges, besides the default one."""

TRACKED_SOLUTIONS = 16
"""At most this many distinct first-sample solutions are tracked along the first stretch."""

SPREAD_SEED = 20_240_301
"""Seed of the generator that spreads the starts (fixed: every call tries the same)."""

SAME_SOLUTION = 1e-3
"""Radians or metres (largest joint difference) within which two first-sample solutions are
one."""


def first_start(solved: SolvedJoints, seed: Any, plan: QueryPlan, joints: Mapping[str, Joint],
                trajectories: Mapping[str, JointTrajectory], frame: str) -> FloatArray:
    """Joint values of the first sample's start: ``seed`` where it gives them, else each
    joint's trajectory at the plan's first time, else its rest value; defaults are put
    within the limits, a given seed must be. Errors name ``frame`` and the field ``seed``."""
    names, limits = solved.names, solved.limits
    given = _given_seed(seed, names, frame)
    first = int(plan.sample_times[0])
    start = np.empty(len(names))
    for column, name in enumerate(names):
        trajectory = trajectories.get(name)
        start[column] = (joints[name].rest_value if trajectory is None else
                         trajectory.value_at(first - plan.shifts.get(name, 0)))
    start = limits.clipped(start)
    for column, number in given.items():
        name = names[column]
        low, high = limits.lower[column], limits.upper[column]
        if not low <= number <= high:
            raise JointError(f"seed {number:.6g} of joint {name!r} is outside its limits "
                             f"[{low:.6g}, {high:.6g}]", frame=frame, field="seed")
        start[column] = number
    return start


def _given_seed(seed: Any, names: tuple[str, ...], frame: str) -> dict[int, float]:
    """The values ``seed`` gives, by column (none for None), each a finite number."""
    if seed is None:
        return {}
    given: dict[int, Any]
    if isinstance(seed, Mapping):
        unknown = [name for name in seed if name not in names]
        if unknown:
            raise JointError(f"seed names {unknown[0]!r}, which is not solved for (joints: "
                             f"{', '.join(names)})", frame=frame, field="seed")
        given = {names.index(name): value for name, value in seed.items()}
    else:
        try:
            values = np.asarray(seed, dtype=float)
        except (TypeError, ValueError):
            raise ArgumentTypeError(f"expected joint values by name or one per joint, got "
                                    f"{seed!r}", frame=frame, field="seed") from None
        if values.shape != (len(names),):
            raise InvalidDataError(f"expected {len(names)} values (joints {', '.join(names)}), "
                                   f"got shape {values.shape}", frame=frame, field="seed")
        given = dict(enumerate(values.tolist()))
    numbers: dict[int, float] = {}
    for column, value in given.items():
        try:
            number = float(value)
        except (TypeError, ValueError):
            number = math.nan
        if not math.isfinite(number):
            raise InvalidDataError(f"expected a finite number for joint {names[column]!r}, "
                                   f"got {value!r}", frame=frame, field="seed")
        numbers[column] = number
    return numbers


def spread_starts(limits: JointLimits, default: FloatArray) -> list[FloatArray]:
    """:data:`SPREAD_STARTS` configurations uniform over the ranges (within -pi..pi where a
    range is wider or unbounded), nearest to ``default`` first."""
    lower = np.maximum(limits.lower, -math.pi)
    upper = np.minimum(limits.upper, math.pi)
    lower, upper = np.minimum(lower, limits.upper), np.maximum(upper, limits.lower)
    generator = np.random.default_rng(SPREAD_SEED)
    starts = generator.uniform(lower, upper, size=(SPREAD_STARTS, default.shape[0]))
    order = np.argsort(np.linalg.norm(starts - default, axis=1), kind="stable")
    return list(starts[order])


def track_from_the_best_start(problem: TrackingProblem, default: FloatArray,
                              stop_when_unreached: bool) -> tuple[Tracked, TrackingHistory]:
    """The samples of ``problem`` tracked from the start taken by the rule of the module
    docstring, and the history to go on from.

    A solution is first tracked up to its first miss only: on a branch that loses the path
    every later sample is a miss, and a miss costs many iterations. Only when none reaches
    every sample are those that followed furthest tracked to the end and counted (with
    ``stop_when_unreached`` the furthest is returned as it stopped). With a flat frame
    (:class:`FlatFrame`) the default start is each of its flat starts in turn, and a
    solution is taken at once only when it also keeps the frame flat at every sample (see
    :func:`_kept_flat`); of those that reach every sample without, the one flat at the most
    samples (the earlier on ties)."""
    samples = problem.step_ratios.shape[0]
    flat = problem.objective if isinstance(problem.objective, FlatFrame) else None
    defaults = [default] if flat is None else flat.flat_starts(default,
                                                                problem.configurations[0])
    firsts: list[FloatArray] = []
    followed: list[int] = []  # per solution, the samples tracked up to its first miss
    furthest: tuple[Tracked, TrackingHistory] | None = None
    flattest: tuple[Tracked, TrackingHistory] | None = None  # reaches all, flat at the most
    most_flat = -1
    bar = 0.0 if flat is None else _flat_bar(flat, defaults[0], problem.configurations[0])
    # from far away a joint that may turn a whole turn turns the short way, not onto a limit
    turning = replace(problem, joints=problem.joints.turning_freely())
    for start in [*defaults, *spread_starts(problem.joints.limits, defaults[0])]:
        first, _, _, reached = solve_again(turning, 0, start)
        first = problem.joints.into_ranges(first)
        if not reached or any(np.max(np.abs(first - other)) <= SAME_SOLUTION
                              for other in firsts):
            continue
        if len(firsts) == TRACKED_SOLUTIONS:
            break
        history = TrackingHistory(first)
        tracked = track_targets(problem, history, stop_when_unreached=True)
        if tracked.reached.shape[0] == samples and tracked.reached.all():
            kept = samples if flat is None else _kept_flat(flat, bar, tracked,
                                                           problem.configurations)
            if kept == samples:
                return tracked, history
            if kept > most_flat:
                flattest, most_flat = (tracked, history), kept
        firsts.append(first)
        followed.append(tracked.reached.shape[0])
        if followed[-1] > max(followed[:-1], default=0):
            furthest = tracked, history
    if flattest is not None:
        return flattest
    if furthest is None:  # no start reaches the first sample: the default's closest approach
        history = TrackingHistory(defaults[0])
        return track_targets(problem, history, stop_when_unreached), history
    if stop_when_unreached:
        return furthest
    return _most_reached(problem, [first for first, count in zip(firsts, followed, strict=True)
                                   if count == max(followed)])


def _flat_bar(flat: FlatFrame, start: FloatArray, configuration: FloatArray) -> float:
    """Radians from up within which a tracked sample keeps the flat frame flat: its tolerance
    beyond the angle of the frame at the first flat start ``start`` (0 where the first
    sample can be flat; ``configuration``: the first sample's ``q``)."""
    return float(flat.angles(start[None], configuration[None])[0]) + flat.tolerance


def _kept_flat(flat: FlatFrame, bar: float, tracked: Tracked,
               configurations: FloatArray) -> int:
    """How many samples of ``tracked`` hold the flat frame within ``bar`` radians of up."""
    angles = flat.angles(tracked.positions, configurations)
    return int(np.count_nonzero(angles <= bar))


def _most_reached(problem: TrackingProblem, firsts: list[FloatArray]
                  ) -> tuple[Tracked, TrackingHistory]:
    """The samples tracked to the end from each of ``firsts``: the tracking that reaches the
    most (the earlier on ties)."""
    best: tuple[Tracked, TrackingHistory] | None = None
    best_count = -1
    for first in firsts:
        history = TrackingHistory(first)
        tracked = track_targets(problem, history)
        count = int(np.count_nonzero(tracked.reached))
        if count > best_count:
            best, best_count = (tracked, history), count
    assert best is not None
    return best
