"""Time ``FrameTree.pose`` beside an independent numpy computation of the same work.

Cases:
  (a) a chain of 6 frames, 3 of them moving with 1,000 keyframes each on non-aligned time
      grids, queried at 1,000 / 10,000 / 100,000 times; weldx and pytransform3d beside it
      when installed;
  (b) a 1,000-frame static tree, 10,000 random pairs: one ``pose()`` call per pair, and all
      pairs in one ``poses()`` call;
  (c) the latency of one query at one time (static pair, moving path);
  (d) scale: a tree of 10,000 static and 1,000 moving frames: build time, a query between
      random frames, resident memory (not with --quick).

Every case runs twice, each time in a child process: with one BLAS/OpenMP thread, and with
the default threads while a spinning process keeps a core busy. The reference is numpy alone
(``_reference.py``), run in the same process.

Run: ``python benchmarks/bench_queries.py [--quick]``.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import _reference as ref
from _machine import (
    describe_machine,
    interleaved,
    interleaved_per_call,
    print_table,
    quick_or_child,
    row,
    run_in_settings,
)
from pinframes import FrameTree, Pose

try:
    from pytransform3d.transform_manager import (
        NumpyTimeseriesTransform,
        StaticTransform,
        TemporalTransformManager,
    )
except ImportError:
    TemporalTransformManager = None


def chain_case(rng):
    """The tree and the reference's edges of case (a)."""
    tree = FrameTree()
    edges, parent = [], "world"
    for index in range(6):
        name = f"f{index}"
        if index % 2:
            # Strictly increasing, non-aligned across frames, on whole microseconds so that
            # pinframes' nanosecond times and the reference's float seconds agree exactly.
            grid = np.round(np.sort(rng.uniform(0, 100, size=1000)), 6)
            grid += np.arange(1000) * 1e-6
            translations = rng.normal(size=(1000, 3))
            quaternions = ref.random_walk_quaternions(rng, 1000, 0.5)
            tree.add(name, parent, Pose(translations, quaternions, times=grid))
            edges.append((grid, translations, quaternions))
        else:
            pose = Pose(rng.normal(size=3), ref.random_walk_quaternions(rng, 2, 3.0)[1])
            tree.add(name, parent, pose)
            edges.append(pose.matrix)
        parent = name
    return tree, edges


def weldx_chain(edges, times, repeats):
    """(median seconds, result) of weldx on the chain, in its own interpreter; or None."""
    python = os.environ.get("PINFRAMES_WELDX_PYTHON")
    if not python:
        return None
    with tempfile.TemporaryDirectory() as folder:
        arrays = {"query_times": times}
        for index, edge in enumerate(edges):
            if isinstance(edge, np.ndarray):
                arrays[f"edge{index}_matrix"] = edge
            else:
                for key, value in zip(("times", "translations", "quaternions"), edge,
                                      strict=True):
                    arrays[f"edge{index}_{key}"] = value
        source, target = Path(folder) / "in.npz", Path(folder) / "out.npz"
        np.savez(source, **arrays)
        subprocess.run([python, str(Path(__file__).with_name("_weldx_chain.py")), str(source),
                        str(target), str(repeats)], check=True, env=os.environ.copy())
        result = np.load(target)
        return float(result["seconds"]), result["matrix"]


def pytransform3d_chain(edges):
    """A pytransform3d TemporalTransformManager of the chain (it interpolates with ScLERP)."""
    manager = TemporalTransformManager()
    parent = "world"
    for index, edge in enumerate(edges):
        if isinstance(edge, np.ndarray):
            transform = StaticTransform(edge)
        else:
            grid, translations, quaternions = edge
            pqs = np.hstack([translations, quaternions[:, 3:], quaternions[:, :3]])
            transform = NumpyTimeseriesTransform(grid, pqs, time_clipping=True)
        manager.add_transform(f"f{index}", parent, transform)
        parent = f"f{index}"
    return lambda times: manager.get_transform_at_time(parent, "world", times)


def bench_chain(rng, sizes, repeats):
    tree, edges = chain_case(rng)
    peer = pytransform3d_chain(edges) if TemporalTransformManager is not None else None
    rows = []
    for size in sizes:
        case = f"(a) chain 6 frames, 3 moving, {size:,} times"
        # unique: weldx refuses repeated query times
        times = np.unique(np.round(rng.uniform(-5, 105, size=size), 6))
        reference = ref.chain(times, edges)
        calls = {"pinframes": lambda t=times: tree.pose("f5", "world", times=t),
                 "numpy reference": lambda t=times: ref.chain(t, edges)}
        if peer is not None:
            calls["pytransform3d"] = lambda t=times: peer(t)
        measured_rows = interleaved(case, calls, repeats)
        errors = {"pinframes": tree.pose("f5", "world", times=times).matrix,
                  "pytransform3d": None if peer is None else peer(times)}
        for entry in measured_rows:
            result = errors.get(entry["method"])
            if result is not None:
                entry["error"] = float(np.max(np.abs(result - reference)))
            if entry["method"] == "pytransform3d":
                entry["note"] = "ScLERP"
        rows += measured_rows
        measured = weldx_chain(edges, times, max(1, repeats // 2))
        if measured is not None:
            rows.append(row(case, "weldx 0.8.2", measured[0],
                            float(np.max(np.abs(measured[1] - reference)))))
    return rows


def bench_static_pairs(rng, pair_count, repeats):
    tree = FrameTree()
    names = ["world"]
    world_matrices = [np.eye(4)]
    for index in range(1, 1000):
        parent = int(rng.integers(index))
        pose = Pose(rng.normal(size=3), ref.random_walk_quaternions(rng, 2, 3.0)[1])
        names.append(f"n{index}")
        tree.add(names[-1], names[parent], pose)
        world_matrices.append(world_matrices[parent] @ pose.matrix)
    world = np.array(world_matrices)
    pairs = rng.integers(1000, size=(pair_count, 2))
    frames = [names[a] for a in pairs[:, 0]]
    relative_to = [names[b] for b in pairs[:, 1]]
    case = f"(b) static tree 1,000 frames, {pair_count:,} pairs"

    def one_by_one():
        return np.array([tree.pose(a, b).matrix for a, b in zip(frames, relative_to,
                                                                strict=True)])

    def reference():
        return np.linalg.inv(world[pairs[:, 1]]) @ world[pairs[:, 0]]

    calls = {"pinframes pose() loop": one_by_one}
    if hasattr(tree, "poses"):
        calls["pinframes poses()"] = lambda: tree.poses(frames, relative_to=relative_to)
    calls["numpy reference"] = reference
    rows = interleaved(case, calls, repeats)
    expected = reference()
    rows[0]["error"] = float(np.max(np.abs(one_by_one() - expected)))
    if hasattr(tree, "poses"):
        rows[1]["error"] = float(np.max(np.abs(calls["pinframes poses()"]().matrix - expected)))
    return rows


def bench_latency(rng, repeats):
    tree = FrameTree()
    tree.add("a", "world", Pose.from_xyz_rpy(1, 2, 3, 0.1, 0.2, 0.3))
    tree.add("b", "a", Pose.from_xyz_rpy(0, 1, 0, 0.3, 0.2, 0.1))
    grid = np.linspace(0, 10, 1000)
    quaternions = ref.random_walk_quaternions(rng, 1000, 0.3)
    translations = rng.normal(size=(1000, 3))
    tree.add("m", "a", Pose(translations, quaternions, times=grid))
    tree.add("tool", "m", Pose([0, 0, 0.4]))
    static_matrix = tree.local_pose("b").matrix
    tool = np.eye(4)
    tool[2, 3] = 0.4
    edges = [(grid, translations, quaternions), tool]
    at = np.array([4.321])
    rows = []
    for case, call, reference in [
        ("(c) one query, static pair", lambda: tree.pose("b", "a"),
         lambda: np.linalg.inv(static_matrix)),
        ("(c) one query, one time, moving path", lambda: tree.pose("tool", "a", times=4.321),
         lambda: ref.chain(at, edges)),
    ]:
        rows += interleaved_per_call(case, {"pinframes": call, "numpy reference": reference},
                                     repeats * 6)
    return rows


def resident_mb() -> float:
    """Current resident memory of this process in MB (Linux)."""
    with open("/proc/self/statm", encoding="ascii") as handle:
        return int(handle.read().split()[1]) * resource.getpagesize() / 2**20


def bench_scale(rng, static_count, moving_count):
    start_mb = resident_mb()
    start = time.perf_counter()
    tree = FrameTree()
    names = ["world"]
    total = static_count + moving_count
    moving_at = set(rng.choice(np.arange(1, total + 1), size=moving_count, replace=False).tolist())
    grid = np.linspace(0, 10, 20)
    for index in range(1, total + 1):
        parent = names[int(rng.integers(len(names)))]
        name = f"n{index}"
        if index in moving_at:
            pose = Pose(rng.normal(size=(20, 3)), ref.random_walk_quaternions(rng, 20, 0.3),
                        times=grid)
        else:
            pose = Pose(rng.normal(size=3))
        tree.add(name, parent, pose)
        names.append(name)
    build = time.perf_counter() - start
    queries = rng.integers(len(names), size=(200, 2))
    start = time.perf_counter()
    for a, b in queries:
        tree.pose(names[a], names[b], times=np.linspace(0, 10, 100))
    query = (time.perf_counter() - start) / len(queries)
    return build, query, resident_mb() - start_mb, resident_mb()


def child(quick: bool) -> None:
    rng = np.random.default_rng(7)
    repeats = 3 if quick else 7
    sizes = [1_000, 10_000] if quick else [1_000, 10_000, 100_000]
    rows = bench_chain(rng, sizes, repeats)
    rows += bench_static_pairs(rng, 2_000 if quick else 10_000, repeats)
    rows += bench_latency(rng, repeats)
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "fewer repeats and sizes")
    if quick is None:
        return
    print(describe_machine())
    if TemporalTransformManager is None:
        print("pytransform3d is not installed: its rows are skipped (pip install pytransform3d)")
    if not os.environ.get("PINFRAMES_WELDX_PYTHON"):
        print("PINFRAMES_WELDX_PYTHON is not set: the weldx rows are skipped")
    print_table(run_in_settings(__file__, ["--quick"] if quick else []))
    if not quick:
        build, query, grown_mb, total_mb = bench_scale(np.random.default_rng(7), 10_000, 1_000)
        print(f"\n(d) 10,000 static + 1,000 moving frames: build {build:.2f} s, "
              f"query between random frames at 100 times {query * 1e3:.2f} ms (mean of 200), "
              f"resident memory grew {grown_mb:.0f} MB (process {total_mb:.0f} MB)")


if __name__ == "__main__":
    main()
