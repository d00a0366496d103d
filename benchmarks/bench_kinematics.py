"""Measured data into the world, and tool velocities, on the Panda on a moving mount.

Case (issue 16), built as in ``bench_robot.py``: the Panda of example-robot-data on a mount
frame moving with 1,000 keyframes, its arm driven by joint samples.

(a) 1,000,000 time-stamped points given in the hand frame (one point per sample time) into
    the world: ``tree.transform_points`` beside an independent numpy reference (interpolate
    the mount, forward kinematics of the arm from the Pinocchio model's placements, apply).
(b) Velocities of the hand relative to the world at 10,000 samples: ``tree.velocity``
    beside ``tree.pose`` at the same times (the cost of the poses alone), and a per-sample
    Pinocchio loop (``forwardKinematics(model, data, q, v)`` + ``getFrameVelocity``) that
    also checks the numbers.

Run: ``python benchmarks/bench_kinematics.py [--quick]`` (``--quick``: 100,000 points).
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np
import pinocchio as pin

from _machine import describe_machine, median_time
from bench_robot import arm_chain, build_case, numpy_reference, panda_urdf

LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED


def reference_points(hand, chain, mount, times, positions, points):
    """Numpy: the hand's poses in the world (interpolate, FK), then ``R @ p + t`` per row."""
    world = numpy_reference(hand, chain, mount, times, positions)
    return np.einsum("nij,nj->ni", world[:, :3, :3], points) + world[:, :3, 3]


def pinocchio_velocities(mount, times, positions):
    """Per sample: q and v of a free-flyer Panda by hand, then Pinocchio's frame velocity."""
    grid, translation, quaternions = mount
    rotation = np.array([pin.Quaternion(w, x, y, z).toRotationMatrix()
                         for x, y, z, w in quaternions])
    model = pin.buildModelFromUrdf(str(panda_urdf()), pin.JointModelFreeFlyer())
    data = model.createData()
    hand = model.getFrameId("panda_hand")
    count = len(times)
    segment = np.clip(np.searchsorted(grid, times, side="right") - 1, 0, len(grid) - 2)
    joint_segment = np.clip(np.arange(count), 0, count - 2)
    spans = np.diff(times)[joint_segment]
    rates = (positions[joint_segment + 1] - positions[joint_segment]) / spans[:, None]
    out = np.empty((count, 6))
    q = pin.neutral(model)
    v = np.zeros(model.nv)

    def run():
        for i in range(count):
            k = segment[i]
            span = grid[k + 1] - grid[k]
            f = min(max((times[i] - grid[k]) / span, 0.0), 1.0)
            step = pin.log3(rotation[k].T @ rotation[k + 1])
            turned = rotation[k] @ pin.exp3(f * step)
            q[:7] = pin.SE3ToXYZQUAT(pin.SE3(turned, (1 - f) * translation[k]
                                             + f * translation[k + 1]))
            q[7:14] = positions[i]
            v[:3] = turned.T @ (translation[k + 1] - translation[k]) / span
            v[3:6] = step / span
            v[6:13] = rates[i]
            pin.forwardKinematics(model, data, q, v)
            pin.updateFramePlacement(model, data, hand)
            out[i] = pin.getFrameVelocity(model, data, hand, LWA).vector
        return out

    return run


def table(title, rows, base_label):
    base = dict((label, seconds) for label, seconds, _ in rows)[base_label]
    print(f"\n{title}")
    print(f"{'method':<40} {'median':>10} {'ratio':>7}  {'max |diff|':>10}")
    for label, seconds, diff in rows:
        print(f"{label:<40} {seconds * 1e3:>8.1f} ms {seconds / base:>7.2f}  "
              f"{'' if diff is None else f'{diff:.1e}':>10}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="100,000 points instead of 10^6")
    args = parser.parse_args()
    print(describe_machine())
    threads = {name: os.environ.get(name, "default")
               for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    print(f"threads: {threads}; the machine is shared: read the ratios (interleaved runs in "
          "one process), not the times")
    rng = np.random.default_rng(3)

    count = 100_000 if args.quick else 1_000_000
    tree, mount, times, positions = build_case(rng, count)
    model = pin.buildModelFromUrdf(str(panda_urdf()))
    hand = model.frames[model.getFrameId("panda_hand")].placement.homogeneous
    chain = arm_chain(model)
    points = rng.normal(scale=0.1, size=(count, 3))
    ours = tree.transform_points(points, "panda_hand", "world", times, per_time=True)
    reference = reference_points(hand, chain, mount, times, positions, points)
    medians = interleaved_medians({
        "ours": lambda: tree.transform_points(points, "panda_hand", "world", times, per_time=True),
        "reference": lambda: reference_points(hand, chain, mount, times, positions, points),
    }, 5)
    table(f"(a) {count:,} time-stamped points, hand frame -> world", [
        ("pinframes tree.transform_points", medians["ours"],
         float(np.max(np.abs(ours - reference)))),
        ("numpy: interpolate, FK, apply (reference)", medians["reference"], None),
    ], "numpy: interpolate, FK, apply (reference)")

    tree, mount, times, positions = build_case(rng, 10_000)
    velocity = tree.velocity("panda_hand", "world", times=times)
    loop = pinocchio_velocities(mount, times, positions)
    expected = loop().copy()
    diff = float(np.max(np.abs(np.concatenate([velocity.linear, velocity.angular], axis=1)
                               - expected)))
    # interleaved, so that a neighbour's load falls on all three alike
    medians = interleaved_medians({
        "velocity": lambda: tree.velocity("panda_hand", "world", times=times),
        "pose": lambda: tree.pose("panda_hand", "world", times=times),
        "jacobian": lambda: tree.jacobian("panda_hand", "world", times=times),
    }, 21)
    table("(b) hand velocity in the world at 10,000 samples", [
        ("pinframes tree.velocity", medians["velocity"], diff),
        ("pinframes tree.pose (the poses alone)", medians["pose"], None),
        ("pinframes tree.jacobian (7 + 2 joints)", medians["jacobian"], None),
        ("Pinocchio loop per sample (v, getFrameVelocity)", median_time(loop, 1), 0.0),
    ], "pinframes tree.pose (the poses alone)")


def interleaved_medians(calls, repeats):
    """Median seconds of each call, the calls taking turns ``repeats`` times (after a
    warm-up of each)."""
    samples = {name: [] for name in calls}
    for call in calls.values():
        call()
    for _ in range(repeats):
        for name, call in calls.items():
            start = time.perf_counter()
            call()
            samples[name].append(time.perf_counter() - start)
    return {name: statistics.median(values) for name, values in samples.items()}


if __name__ == "__main__":
    main()
