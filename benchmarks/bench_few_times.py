"""Where a query at a few times should leave the one-time path: Pinocchio's kinematics time by
time against the batched kernels, at 1 to 32 times (the measurement behind
``pinframes.kinematics._one_time.FEW_TIMES``).

Cases: bench_queries' moving path (a frame moving with 1,000 keyframes between two static
frames) and bench_robot's Panda on a moving mount (10^4 joint samples), each queried through
``FrameTree.pose`` at N times spread over the keyframes. For each call the threshold is set
so that the query takes one path or the other; the ratio is one-time / batched (below 1: the
one-time path is faster). Both thread settings, each in a child process (``_machine.py``).

Run: ``python benchmarks/bench_few_times.py [--quick]``.
"""

from __future__ import annotations

import json

import numpy as np

import _reference as ref
import pinframes.kinematics._one_time as one_time
from _machine import (
    describe_machine,
    interleaved,
    print_table,
    quick_or_child,
    run_in_settings,
)
from bench_robot import build_case
from pinframes import FrameTree, Pose

COUNTS = (1, 2, 4, 8, 12, 16, 24, 32)


def moving_path(rng) -> FrameTree:
    """bench_queries' case (c): world <- a <- m (1,000 keyframes) <- tool."""
    tree = FrameTree()
    tree.add("a", "world", Pose.from_xyz_rpy(1, 2, 3, 0.1, 0.2, 0.3))
    tree.add("m", "a", Pose(rng.normal(size=(1000, 3)), ref.random_walk_quaternions(rng, 1000, 0.3),
                            times=np.linspace(0, 10, 1000)))
    tree.add("tool", "m", Pose([0, 0, 0.4]))
    return tree


def on_path(limit: int, call):
    """``call`` with the one-time path taking queries of at most ``limit`` times."""
    def timed():
        saved, one_time.FEW_TIMES = one_time.FEW_TIMES, limit
        try:
            return call()
        finally:
            one_time.FEW_TIMES = saved
    return timed


def child(quick: bool) -> None:
    rng = np.random.default_rng(7)
    tree = moving_path(rng)
    panda = build_case(np.random.default_rng(3), 10_000)[0]
    rows = []
    for name, query in [
        ("moving path", lambda times: tree.pose("tool", "a", times=times)),
        ("Panda on a moving mount", lambda times: panda.pose("panda_hand", "world",
                                                             times=times)),
    ]:
        for count in COUNTS:
            times = np.linspace(1.2345, 8.77, count)
            calls = {"one-time path": on_path(count, lambda q=query, t=times: q(t)),
                     "batched kernels": on_path(0, lambda q=query, t=times: q(t))}
            rows += interleaved(f"{name}, {count} times", calls, 50 if quick else 200,
                                reference="batched kernels")
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child)
    if quick is None:
        return
    print(describe_machine())
    print(f"FEW_TIMES = {one_time.FEW_TIMES}")
    print_table(run_in_settings(__file__, ["--quick"] if quick else []),
                reference="batched kernels")


if __name__ == "__main__":
    main()
