"""Timing joint motions: ``time_along_path`` beside TOPP-RA, ``time_point_to_point`` beside
Ruckig, on the same paths, moves and limits.

(a) A path: a 6-joint (and a 7-joint) path through random waypoints, sampled at N points,
timed from rest to rest within velocity and acceleration limits by ``time_along_path`` and by
``toppra`` (``TOPPRA`` with its ``SplineInterpolator`` through the same samples, the samples
its grid, ``ParametrizeConstAccel``), each call building everything it needs from the samples.
The table's last column is the relative difference of the two durations. (b) A point-to-point
move of 6 joints, with and without jerk limits, by ``time_point_to_point`` and by Ruckig's
``calculate``. Each case runs in the two settings of ``_machine`` (one BLAS thread; default
threads beside a spinning process), methods in alternating rounds. Run from the repository
root: ``python benchmarks/bench_timing.py [--quick]``.
"""

from __future__ import annotations

import json
import logging

import numpy as np
import toppra
import toppra.algorithm
import toppra.constraint
from ruckig import InputParameter, Ruckig, Trajectory

from _machine import (
    describe_machine,
    interleaved,
    interleaved_per_call,
    print_table,
    quick_or_child,
    run_in_settings,
)
from pinframes.kinematics.timing import MotionLimits, time_along_path, time_point_to_point

SAMPLES = (100, 300, 1000, 3000)


def waypoint_path(rng: np.random.Generator, joints: int, samples: int) -> tuple[np.ndarray, ...]:
    """Joints along a smooth path through six random waypoints, at ``samples`` parameters
    from 0 to 1 (a cubic through the waypoints, in numpy: Catmull-Rom)."""
    waypoints = rng.uniform(-1.5, 1.5, (6, joints))
    padded = np.vstack([waypoints[:1], waypoints, waypoints[-1:]])
    parameters = np.linspace(0.0, 1.0, samples)
    position = parameters * (len(waypoints) - 1)
    index = np.minimum(position.astype(int), len(waypoints) - 2)
    t = (position - index)[:, None]
    p0, p1, p2, p3 = (padded[index + shift] for shift in range(4))
    positions = 0.5 * (2 * p1 + (p2 - p0) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t**2
                       + (3 * p1 - p0 - 3 * p2 + p3) * t**3)
    return positions, parameters, rng.uniform(0.5, 3.0, joints), rng.uniform(1.0, 10.0, joints)


def toppra_timing(positions, parameters, velocity, acceleration):
    """TOPP-RA from the samples: its spline, velocity and acceleration constraints, grid."""
    path = toppra.SplineInterpolator(parameters, positions)
    constraints = [
        toppra.constraint.JointVelocityConstraint(np.stack([-velocity, velocity], axis=1)),
        toppra.constraint.JointAccelerationConstraint(
            np.stack([-acceleration, acceleration], axis=1))]
    problem = toppra.algorithm.TOPPRA(constraints, path, gridpoints=parameters,
                                      parametrizer="ParametrizeConstAccel")
    return problem.compute_trajectory(0, 0)


def path_rows(quick: bool) -> list[dict]:
    rng = np.random.default_rng(43)
    rows = []
    for joints, samples in [(6, count) for count in SAMPLES] + [(7, 1000)]:
        rows += path_case(f"path, {joints} joints, {samples} samples",
                          *waypoint_path(rng, joints, samples), rounds=3 if quick else 9)
    return rows


def path_case(case: str, positions: np.ndarray, parameters: np.ndarray, velocity: np.ndarray,
              acceleration: np.ndarray, rounds: int) -> list[dict]:
    """Both timings of one path in alternating rounds, and the difference of durations."""
    limits = MotionLimits(velocity, acceleration)
    ours = time_along_path(positions, parameters, limits).duration
    theirs = toppra_timing(positions, parameters, velocity, acceleration).duration
    measured = interleaved(case, {
        "toppra": lambda: toppra_timing(positions, parameters, velocity, acceleration),
        "time_along_path": lambda: time_along_path(positions, parameters, limits),
    }, rounds, reference="toppra")
    measured[1]["error"] = ours / theirs - 1
    measured[1]["note"] = f"durations {ours:.3f} s / {theirs:.3f} s"
    return measured


def ruckig_calculate(start, goal, velocity, acceleration, jerk) -> float:
    """Ruckig's duration of the synchronised rest-to-rest move."""
    count = len(start)
    inputs = InputParameter(count)
    inputs.current_position, inputs.target_position = list(start), list(goal)
    inputs.max_velocity, inputs.max_acceleration = list(velocity), list(acceleration)
    inputs.max_jerk = list(jerk)
    trajectory = Trajectory(count)
    Ruckig(count).calculate(inputs, trajectory)
    return float(trajectory.duration)


def point_to_point_rows(quick: bool) -> list[dict]:
    rng = np.random.default_rng(44)
    start, goal = rng.uniform(-2, 2, 6), rng.uniform(-2, 2, 6)
    velocity, acceleration = rng.uniform(0.5, 3, 6), rng.uniform(1, 10, 6)
    rows = []
    for jerk in (None, rng.uniform(20, 200, 6)):
        limits = MotionLimits(velocity, acceleration, jerk)
        jerks = np.full(6, np.inf) if jerk is None else jerk
        ours = time_point_to_point(start, goal, limits).duration
        theirs = ruckig_calculate(start, goal, velocity, acceleration, jerks)
        case = f"point to point, 6 joints, {'no jerk' if jerk is None else 'jerk'} limit"
        measured = interleaved_per_call(case, {
            "ruckig": lambda jerks=jerks: ruckig_calculate(start, goal, velocity, acceleration,
                                                          jerks),
            "time_point_to_point": lambda limits=limits: time_point_to_point(start, goal,
                                                                             limits),
        }, 5 if quick else 15, in_a_row=20, reference="ruckig")
        measured[1]["error"] = ours / theirs - 1
        measured[1]["note"] = f"durations {ours:.4f} s / {theirs:.4f} s"
        rows += measured
    return rows


def child(quick: bool) -> None:
    logging.getLogger("toppra").setLevel(logging.ERROR)
    print(json.dumps(path_rows(quick) + point_to_point_rows(quick)))


def main() -> None:
    quick = quick_or_child(__doc__ or "", child)
    if quick is None:
        return
    print(describe_machine())
    results = run_in_settings(__file__, ["--quick"] if quick else [])
    print_table(results, reference="toppra")
    print("for the point-to-point rows the ratio is to ruckig; max|diff| there and for the "
          "paths: our duration / the reference's - 1")


if __name__ == "__main__":
    main()
