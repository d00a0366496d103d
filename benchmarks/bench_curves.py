"""Cost curves: how the time of ``FrameTree.pose`` grows with the size of the work.

- time per sample against the number of samples (the Panda on a moving mount, 10^2..10^7),
  with the peak memory of the query and of the process (each size in a fresh process);
- time per sample against the keyframes of each moving frame (the 6-frame chain with 3
  moving frames, 10^1..10^6 keyframes, 10^5 times);
- time per sample against the depth of the path (a chain of 1..1,000 frames, every other
  one moving, 1,000 times), and the first query (which compiles the path's model);
- time per query against the size of the tree (10^2..10^5 frames, 10 % moving, random
  pairs at 100 times), and the build time per frame.

Runs with one BLAS/OpenMP thread (``OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1``, set for the
child processes). Each point is the *minimum* over repeats: on a shared machine load only
ever adds time, and a curve of medians there shows the neighbours more than the code.
Writes ``cost_curves.md`` (the table) and ``cost_curves.png`` beside this file.
``--quick`` stops every curve early (a minute or so); the full run takes about 10 minutes
on two cores.

Run: ``python benchmarks/bench_curves.py [--quick]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

from _machine import THREAD_VARIABLES, describe_machine, repeated_times
from pinframes import FrameTree, Pose

HERE = Path(__file__).resolve().parent


def random_quaternions(rng, count):
    """Random unit quaternions, each on the hemisphere of the one before (short arcs)."""
    q = rng.normal(size=(count, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    q[1:] *= np.sign(np.sum(q[1:] * q[:-1], axis=1))[:, None]
    return q


def samples_point(samples: int) -> dict:
    """Panda hand in the world at ``samples`` joint samples: time and peak memory."""
    from bench_robot import build_case

    built = build_case(np.random.default_rng(3), samples)
    tree, times = built[0], built[2]
    del built  # the joint positions now live in the tree's joint tracks only
    resident = resident_bytes()
    repeats = 7 if samples <= 100_000 else 3 if samples <= 1_000_000 else 1
    seconds = min(repeated_times(
        lambda: tree.pose("panda_hand", "world", times=times), repeats))
    tracemalloc.start()
    tree.pose("panda_hand", "world", times=times)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    process_peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    return {"samples": samples, "per_sample": seconds / samples, "query_peak": peak,
            "result": samples * 12 * 8, "before_query": resident,
            "process_peak": process_peak}


def resident_bytes() -> int:
    """Current resident memory of this process (Linux)."""
    with open("/proc/self/statm", encoding="ascii") as handle:
        return int(handle.read().split()[1]) * resource.getpagesize()


def chain_tree(rng, depth, keyframes, moving_every=2):
    tree = FrameTree()
    parent = "world"
    grid = np.linspace(0.0, 100.0, keyframes)
    for index in range(depth):
        name = f"f{index}"
        if index % moving_every == 1 or depth == 1:
            pose = Pose(rng.normal(size=(keyframes, 3)), random_quaternions(rng, keyframes),
                        times=grid)
        else:
            pose = Pose(rng.normal(size=3), random_quaternions(rng, 1)[0])
        tree.add(name, parent, pose)
        parent = name
    return tree, parent


def keyframes_point(keyframes: int) -> dict:
    tree, last = chain_tree(np.random.default_rng(1), 6, keyframes)
    times = np.sort(np.random.default_rng(2).uniform(-5, 105, size=100_000))
    seconds = min(repeated_times(lambda: tree.pose(last, "world", times=times), 7))
    return {"keyframes": keyframes, "per_sample": seconds / times.size}


def depth_point(depth: int) -> dict:
    tree, last = chain_tree(np.random.default_rng(1), depth, 10)
    times = np.linspace(-5, 105, 1_000)
    start = time.perf_counter()
    tree.pose(last, "world", times=times)
    first = time.perf_counter() - start
    seconds = min(repeated_times(lambda: tree.pose(last, "world", times=times), 7))
    return {"depth": depth, "per_sample": seconds / times.size, "first_query": first}


def tree_point(size: int) -> dict:
    rng = np.random.default_rng(5)
    start = time.perf_counter()
    tree = FrameTree()
    names = ["world"]
    grid = np.linspace(0, 10, 20)
    for index in range(1, size):
        parent = names[int(rng.integers(len(names)))]
        if rng.random() < 0.1:
            pose = Pose(rng.normal(size=(20, 3)), random_quaternions(rng, 20), times=grid)
        else:
            pose = Pose(rng.normal(size=3))
        names.append(f"n{index}")
        tree.add(names[-1], parent, pose)
    build = time.perf_counter() - start
    pairs = rng.integers(size, size=(200, 2))
    times = np.linspace(0, 10, 100)
    start = time.perf_counter()
    for a, b in pairs:  # first queries: each compiles its path
        tree.pose(names[a], names[b], times=times)
    first = (time.perf_counter() - start) / len(pairs)
    again = min(repeated_times(
        lambda: [tree.pose(names[a], names[b], times=times) for a, b in pairs], 5)) / len(pairs)
    return {"frames": size, "build_per_frame": build / size, "first_query": first,
            "query": again}


POINTS = {"samples": samples_point, "keyframes": keyframes_point, "depth": depth_point,
          "tree": tree_point}
FULL = {"samples": [10**k for k in range(2, 8)], "keyframes": [10**k for k in range(1, 7)],
        "depth": [1, 3, 10, 30, 100, 300, 1000], "tree": [10**k for k in range(2, 6)]}
QUICK = {"samples": [10**k for k in range(2, 6)], "keyframes": [10**k for k in range(1, 5)],
         "depth": [1, 10, 100], "tree": [100, 1000]}


def measure(curve: str, value: int) -> dict:
    """One point, in a fresh child process with one thread (so peak memory is its own)."""
    environment = os.environ | dict.fromkeys(THREAD_VARIABLES, "1")
    output = subprocess.run([sys.executable, str(Path(__file__)), "--child", curve, str(value)],
                            env=environment, check=True, capture_output=True, text=True).stdout
    return json.loads(output.strip().splitlines()[-1])


def table(results: dict[str, list[dict]]) -> str:
    lines = []
    mb = 2**20
    lines += ["| samples | time per sample | query peak memory | of which the result | "
              "process before the query | process peak |", "|---:|---:|---:|---:|---:|---:|"]
    lines += [f"| {r['samples']:,} | {r['per_sample'] * 1e9:.0f} ns | "
              f"{r['query_peak'] / mb:,.0f} MB | {r['result'] / mb:,.0f} MB | "
              f"{r['before_query'] / mb:,.0f} MB | {r['process_peak'] / mb:,.0f} MB |"
              for r in results["samples"]]
    lines += ["", "| keyframes per moving frame | time per sample |", "|---:|---:|"]
    lines += [f"| {r['keyframes']:,} | {r['per_sample'] * 1e9:.0f} ns |"
              for r in results["keyframes"]]
    lines += ["", "| path depth (frames) | time per sample | per sample and frame | "
              "first query (compiles) |", "|---:|---:|---:|---:|"]
    lines += [f"| {r['depth']:,} | {r['per_sample'] * 1e9:,.0f} ns | "
              f"{r['per_sample'] / r['depth'] * 1e9:.0f} ns | {r['first_query'] * 1e3:.1f} ms |"
              for r in results["depth"]]
    lines += ["", "| tree size (frames) | build per frame | first query | query |",
              "|---:|---:|---:|---:|"]
    lines += [f"| {r['frames']:,} | {r['build_per_frame'] * 1e6:.0f} us | "
              f"{r['first_query'] * 1e3:.2f} ms | {r['query'] * 1e3:.3f} ms |"
              for r in results["tree"]]
    return "\n".join(lines)


def plot(results: dict[str, list[dict]], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    panels = [
        ("samples", "samples", "per_sample", 1e9, "time per sample (ns)", "Panda, moving mount"),
        ("samples", "samples", "query_peak", 2**-20, "query peak memory (MB)",
         "Panda: memory"),
        ("keyframes", "keyframes", "per_sample", 1e9, "time per sample (ns)",
         "chain, 10^5 times"),
        ("depth", "depth", "per_sample", 1e9, "time per sample (ns)", "path depth, 1,000 times"),
        ("tree", "frames", "query", 1e3, "time per query (ms)", "tree size, 100 times"),
        ("tree", "frames", "build_per_frame", 1e6, "build per frame (us)", "tree size: build"),
    ]
    for axis, (curve, x, y, scale, label, title) in zip(axes.flat, panels, strict=True):
        points = results[curve]
        axis.loglog([p[x] for p in points], [p[y] * scale for p in points], "o-")
        axis.set_xlabel(x)
        axis.set_ylabel(label)
        axis.set_title(title)
        axis.grid(True, which="both", alpha=0.3)
    figure.suptitle("pinframes cost curves (1 thread, minimum of repeats; shared 2-core machine)")
    figure.tight_layout()
    figure.savefig(path, dpi=90)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="shorter curves")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        curve, value = args.child
        print(json.dumps(POINTS[curve](int(value))))
        return
    print(describe_machine())
    results = {curve: [] for curve in POINTS}
    for curve, values in (QUICK if args.quick else FULL).items():
        for value in values:
            results[curve].append(measure(curve, value))
            print(f"  {curve} {value:,}: {results[curve][-1]}", flush=True)
    text = table(results)
    print("\n" + text)
    (HERE / "cost_curves.md").write_text(
        f"Cost curves ({'--quick' if args.quick else 'full run'}); {describe_machine()}\n\n"
        f"{text}\n", encoding="utf-8")
    plot(results, HERE / "cost_curves.png")
    print(f"\nwrote {HERE / 'cost_curves.md'} and {HERE / 'cost_curves.png'}")


if __name__ == "__main__":
    main()
