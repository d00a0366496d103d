"""Closed-form inverse kinematics: ``solve_joints`` along a path on an OPW arm and on the UR5
against the per-sample pink loop, and ``ik_solutions`` per solution.

The arms: the KUKA KR 6 R900 sixx (an OPW arm, its kinematics in tests/data) and the UR5 of
example-robot-data. As in bench_ik.py, a smooth joint trajectory inside the limits at
100 Hz gives the tool poses (Pinocchio called directly), the targets; ``solve_joints``
tracks them from the first configuration (the seed, whose branch the closed form keeps) and
pink's loop (``pink.solve_ik`` with a ``FrameTask``, daqp, warmed up on the first 100
samples) steps from the previous solution until within the same tolerances (1e-6 m,
1e-6 rad), on the first 1,000 samples. ``ik_solutions`` gives every solution of every sample
(whole turns of the joints that span more than a turn included, and without them); its
time per solution is the call's time over the solutions it returns (the UR5's whole turns
at 10^5 samples return (10^5, 256, 6) doubles: the child's peak is about 1.4 GB). Every
solution of ``solve_joints`` is checked with Pinocchio on the URDF.

Run from the repository root after ``pip install ".[bench]"``::

    python benchmarks/bench_closed_form.py            # 10^3, 10^4, 10^5 samples
    python benchmarks/bench_closed_form.py --quick    # 10^3 and 10^4 samples, fewer rounds
"""

from __future__ import annotations

import json
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _machine import SETTINGS, describe_machine, format_seconds, quick_or_child, run_in_settings
from bench_ik import (
    PINK_SAMPLES,
    SAMPLE_RATE_HZ,
    TESTS_DATA,
    largest_errors,
    pink_loop,
    robots_folder,
    tool_poses,
    trajectory,
)

ROBOTS = {  # name: (URDF, tool frame, home, swing)
    "KR6 R900 (OPW)": (str(TESTS_DATA / "ros_industrial_arms" / "kuka_experimental"
                           / "kr6r900sixx.urdf"), "tool0",
                       [0.3, -1.2, 1.5, 0.4, 0.8, 0.2], [0.6, 0.3, 0.3, 0.6, 0.4, 0.8]),
    "UR5 (UR-type)": ("ur_description/urdf/ur5_robot.urdf", "tool0",
                      [0.0, -1.2, 1.5, -1.8, -1.571, 0.0], [0.8, 0.3, 0.4, 0.4, 0.4, 0.8]),
}
WARM_UP = 100  # samples pink solves before it is timed


def measure(quick: bool) -> list[dict]:
    """The rows of one thread setting (run in a child process)."""
    import pinframes

    counts = (1_000, 10_000) if quick else (1_000, 10_000, 100_000)
    rounds = 3 if quick else 5
    rows = []
    for robot, (urdf, tool, home, swing) in ROBOTS.items():
        path = robots_folder() / urdf  # an absolute path stays as it is
        model = pin.buildModelFromUrdf(str(path))
        tree = pinframes.FrameTree("floor")
        tree.attach_urdf(str(path), "floor")
        for count in counts:
            configurations = trajectory(home, swing, count)
            targets = tool_poses(model, tool, configurations)
            target = pinframes.Pose(np.array([t.translation for t in targets]),
                                    np.array([t.rotation for t in targets]),
                                    times=np.arange(count) / SAMPLE_RATE_HZ)
            pink_loop(model, tool, targets[:WARM_UP], configurations[0], "daqp")
            tree.solve_joints(tool, target, seed=configurations[0])  # compiled, cached
            ours: list[tuple[float, float]] = []  # (wall, CPU) seconds per sample
            pink: list[tuple[float, float]] = []
            solutions: dict[str, list[tuple[float, float]]] = {"whole turns": [],
                                                               "one per branch": []}
            found = {}
            for _ in range(rounds):
                solution, elapsed = timed(tree.solve_joints, tool, target,
                                          seed=configurations[0])
                ours.append((elapsed[0] / count, elapsed[1] / count))
                (_, pink_reached), elapsed = timed(pink_loop, model, tool,
                                                   targets[:PINK_SAMPLES], configurations[0],
                                                   "daqp")
                pink.append((elapsed[0] / PINK_SAMPLES, elapsed[1] / PINK_SAMPLES))
                for kind, whole in (("whole turns", True), ("one per branch", False)):
                    every, elapsed = timed(tree.ik_solutions, tool, target,
                                           whole_turns=whole)
                    found[kind] = int(every.valid.sum())
                    solutions[kind].append((elapsed[0] / found[kind],
                                            elapsed[1] / found[kind]))
            position, orientation = largest_errors(model, tool, targets, configurations,
                                                   solution.joint_names, solution.positions)
            case = f"{robot}, {count:,}"
            rows.append({"case": case, "method": "solve_joints", **medians(ours, pink),
                         "note": f"reached {int(solution.reached.sum()):,}/{count:,}; max "
                                 f"error {position:.1e} m, {orientation:.1e} rad"})
            rows.append({"case": case, "method": f"pink + daqp ({PINK_SAMPLES:,})",
                         **medians(pink, pink),
                         "note": f"reached {pink_reached:,}/{PINK_SAMPLES:,}"})
            for kind, times in solutions.items():
                if not times:
                    continue
                rows.append({"case": case, "method": f"ik_solutions, {kind}",
                             **medians(times, None),
                             "note": f"per solution: {found[kind]:,} solutions "
                                     f"({found[kind] / count:.1f} per sample)"})
    return rows


def timed(function: Any, *args: Any, **kwargs: Any) -> tuple[Any, tuple[float, float]]:
    """``function(*args, **kwargs)`` and its wall and CPU (this process) seconds."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = function(*args, **kwargs)
    return result, (time.perf_counter() - wall, time.process_time() - cpu)


def medians(ours: list[tuple[float, float]], theirs: list[tuple[float, float]] | None
            ) -> dict[str, float]:
    """Median wall and CPU seconds, and the medians of ``theirs / ours`` per round (NaN
    without a reference)."""
    def ratio(column: int) -> float:
        if theirs is None:
            return float("nan")
        return statistics.median(other[column] / mine[column]
                                 for other, mine in zip(theirs, ours, strict=True))
    return {"seconds": statistics.median(wall for wall, _ in ours), "ratio": ratio(0),
            "cpu": statistics.median(cpu for _, cpu in ours), "cpu_ratio": ratio(1)}


def child(quick: bool) -> None:
    print(json.dumps(measure(quick)))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "10^3 and 10^4 samples, 3 rounds")
    if quick is None:
        return
    print(describe_machine())
    results = run_in_settings(__file__, ["--quick"] if quick else [])
    header = "".join(f" {setting:>10} {'pink/ours':>9} {'CPU':>9} {'pink/ours':>9}"
                     for setting in SETTINGS)
    print(f"\n{'case':<24} {'method':<30}{header}  note (1 thread)")
    for index, entry in enumerate(results[SETTINGS[0]]):
        cells = "".join(f" {format_seconds(results[s][index]['seconds']):>10} "
                        f"{results[s][index]['ratio']:>9.1f} "
                        f"{format_seconds(results[s][index]['cpu']):>9} "
                        f"{results[s][index]['cpu_ratio']:>9.1f}" for s in SETTINGS)
        print(f"{entry['case']:<24} {entry['method']:<30}{cells}  {entry['note']}")
    print(f"\nload average at the end: {', '.join(f'{v:.1f}' for v in os.getloadavg())}")
    print("\ntimes: medians over rounds, per sample (solve_joints, pink) or per solution "
          "(ik_solutions), wall clock and CPU time of this process (on a shared machine the "
          "CPU time is the steadier); pink/ours: median over rounds of pink's time per "
          "sample / solve_joints' (above 1: solve_joints is faster); pink runs on the first "
          "1,000 samples of each case, warmed up.\n1 thread: "
          "OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1; busy: default threads beside a spinning "
          "process")


if __name__ == "__main__":
    main()
