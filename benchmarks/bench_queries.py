"""Time ``FrameTree.pose`` beside a plain vectorised numpy computation of the same work.

Cases (issue 2):
  (a) a chain of 6 frames, 3 of them moving with 1,000 keyframes each on non-aligned time
      grids, queried at 1,000 / 10,000 / 100,000 times;
  (b) a 1,000-frame static tree, 10,000 random pair queries;
  (c) the latency of one query at one time (static pair, moving path);
  (d) scale: a tree of 10,000 static and 1,000 moving frames: build time, a query between
      random frames, resident memory.

Run: ``python benchmarks/bench_queries.py [--quick]``. Prints medians and ratios
(pinframes / numpy reference); the machine is named at the top.
"""

from __future__ import annotations

import argparse
import resource
import time

import numpy as np

from _machine import describe_machine, median_time
from pinframes import FrameTree, Pose
from pinframes.values.rotations import matrix_from_quaternion


def random_unit_quaternions(rng: np.random.Generator, count: int, step: float) -> np.ndarray:
    """A random walk of rotations with steps below ``step`` radians, as quaternions."""
    axes = rng.normal(size=(count, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    angles = rng.uniform(0, step, size=count)
    steps = np.concatenate([axes * np.sin(angles / 2)[:, None], np.cos(angles / 2)[:, None]],
                           axis=1)
    out = np.empty((count, 4))
    out[0] = [0.0, 0.0, 0.0, 1.0]
    for i in range(1, count):  # quaternion product out[i-1] * steps[i]
        x1, y1, z1, w1 = out[i - 1]
        x2, y2, z2, w2 = steps[i]
        out[i] = [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                  w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]
    return out


# -- the numpy reference: interpolate each frame, then compose 4x4 matrices ----------------
def reference_interpolate(times, keyframe_times, translations, quaternions):
    """Linear translation + SLERP at ``times`` (float seconds), held outside, as (N, 4, 4)."""
    index = np.clip(np.searchsorted(keyframe_times, times, side="right") - 1, 0,
                    len(keyframe_times) - 2)
    w = np.clip((times - keyframe_times[index])
                / (keyframe_times[index + 1] - keyframe_times[index]), 0.0, 1.0)
    q0, q1 = quaternions[index], quaternions[index + 1]
    dot = np.sum(q0 * q1, axis=1)
    q1 = np.where(dot[:, None] < 0, -q1, q1)
    theta = np.arccos(np.clip(np.abs(dot), -1.0, 1.0))
    sin_theta = np.sin(theta)
    small = sin_theta < 1e-9
    a = np.where(small, 1 - w, np.sin((1 - w) * theta) / np.where(small, 1, sin_theta))
    b = np.where(small, w, np.sin(w * theta) / np.where(small, 1, sin_theta))
    q = a[:, None] * q0 + b[:, None] * q1
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    out = np.zeros((len(times), 4, 4))
    out[:, :3, :3] = matrix_from_quaternion(q)
    out[:, :3, 3] = (1 - w)[:, None] * translations[index] + w[:, None] * translations[index + 1]
    out[:, 3, 3] = 1.0
    return out


def reference_chain(times, edges):
    """Compose the chain's edges (static (4, 4) or keyframe tuples) at ``times``."""
    result = None
    for edge in edges:
        matrix = edge if isinstance(edge, np.ndarray) else reference_interpolate(times, *edge)
        result = matrix if result is None else result @ matrix
    return result


def bench_chain(rng, sizes, repeats):
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
            quaternions = random_unit_quaternions(rng, 1000, 0.5)
            tree.add(name, parent, Pose(translations, quaternions, times=grid))
            edges.append((grid, translations, quaternions))
        else:
            pose = Pose(rng.normal(size=3), random_unit_quaternions(rng, 2, 3.0)[1])
            tree.add(name, parent, pose)
            edges.append(pose.matrix)
        parent = name
    rows = []
    for size in sizes:
        times = np.round(np.sort(rng.uniform(-5, 105, size=size)), 6)
        reference = reference_chain(times, edges)
        result = tree.pose("f5", "world", times=times)
        error = float(np.max(np.abs(result.matrix - reference)))
        ours = median_time(lambda t=times: tree.pose("f5", "world", times=t), repeats)
        theirs = median_time(lambda t=times: reference_chain(t, edges), repeats)
        rows.append((f"(a) chain 6 frames, 3 moving, {size:>7,} times", ours, theirs, error))
    return rows


def bench_static_pairs(rng, pair_count, repeats):
    tree = FrameTree()
    names = ["world"]
    world_matrices = [np.eye(4)]
    for index in range(1, 1000):
        parent = int(rng.integers(index))
        pose = Pose(rng.normal(size=3), random_unit_quaternions(rng, 2, 3.0)[1])
        names.append(f"n{index}")
        tree.add(names[-1], names[parent], pose)
        world_matrices.append(world_matrices[parent] @ pose.matrix)
    world = np.array(world_matrices)
    pairs = rng.integers(1000, size=(pair_count, 2))

    def ours():
        return [tree.pose(names[a], names[b]) for a, b in pairs]

    def reference():
        return np.linalg.inv(world[pairs[:, 1]]) @ world[pairs[:, 0]]

    error = float(np.max(np.abs(np.array([p.matrix for p in ours()]) - reference())))
    row = (f"(b) static tree 1,000 frames, {pair_count:,} pairs", median_time(ours, repeats),
           median_time(reference, repeats), error)
    return [row]


def bench_latency(rng, repeats):
    tree = FrameTree()
    tree.add("a", "world", Pose.from_xyz_rpy(1, 2, 3, 0.1, 0.2, 0.3))
    tree.add("b", "a", Pose.from_xyz_rpy(0, 1, 0, 0.3, 0.2, 0.1))
    grid = np.linspace(0, 10, 1000)
    tree.add("m", "a", Pose(rng.normal(size=(1000, 3)), random_unit_quaternions(rng, 1000, 0.3),
                            times=grid))
    tree.add("tool", "m", Pose([0, 0, 0.4]))
    static_matrix = tree.local_pose("b").matrix
    moving = (grid, tree.local_pose("m").translation, tree.local_pose("m").quaternion)
    tool = tree.local_pose("tool").matrix
    edges = [moving, tool]
    at = np.array([4.321])
    rows = []
    for label, call, reference in [
        ("(c) one query, static pair", lambda: tree.pose("b", "a"),
         lambda: np.linalg.inv(static_matrix)),
        ("(c) one query, one time, moving path", lambda: tree.pose("tool", "a", times=4.321),
         lambda: reference_chain(at, edges)),
    ]:
        call()
        rows.append((label, median_time(call, repeats * 200),
                     median_time(reference, repeats * 200), float("nan")))
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
            pose = Pose(rng.normal(size=(20, 3)), random_unit_quaternions(rng, 20, 0.3),
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats and sizes")
    args = parser.parse_args()
    rng = np.random.default_rng(7)
    repeats = 3 if args.quick else 7
    sizes = [1_000, 10_000] if args.quick else [1_000, 10_000, 100_000]
    print(describe_machine())
    build, query, grown_mb, total_mb = bench_scale(rng, 10_000, 1_000)
    print(f"\n(d) 10,000 static + 1,000 moving frames: build {build:.2f} s, "
          f"query between random frames at 100 times {query * 1e3:.2f} ms (mean of 200), "
          f"resident memory grew {grown_mb:.0f} MB (process {total_mb:.0f} MB)")
    rows = bench_chain(rng, sizes, repeats)
    rows += bench_static_pairs(rng, 2_000 if args.quick else 10_000, repeats)
    rows += bench_latency(rng, repeats)
    print(f"\n{'case':<50} {'pinframes':>12} {'numpy ref':>12} {'ratio':>7} {'max |err|':>10}")
    for label, ours, theirs, error in rows:
        print(f"{label:<50} {_fmt(ours):>12} {_fmt(theirs):>12} {ours / theirs:>7.2f} "
              f"{error:>10.1e}")


def _fmt(seconds: float) -> str:
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} us"
    if seconds < 1:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


if __name__ == "__main__":
    main()
