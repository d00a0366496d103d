"""Tool poses of a robot per sample: pinframes beside a vectorised numpy forward kinematics.

Case (issue 5): the Panda of example-robot-data on a mount frame that moves with 1,000
keyframes, 10,000 joint samples, the hand pose in the world at every sample. Also shown: a
hand-written Pinocchio loop (forwardKinematics per sample) and a 1,000,000-sample run (time
and peak memory).

Run: ``python benchmarks/bench_robot.py [--quick]``.
"""

from __future__ import annotations

import argparse
import resource
import time
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin

from _machine import describe_machine, median_time
from bench_queries import reference_interpolate
from pinframes import FrameTree, Pose
from pinframes.values.rotations import matrix_from_axis_angle, quaternion_from_matrix


def panda_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "panda.urdf":
            return Path(file.locate())
    raise SystemExit("example-robot-data is not installed (pip install '.[test]')")


def build_case(rng, samples):
    urdf = panda_urdf()
    tree = FrameTree()
    grid = np.round(np.linspace(0.0, 10.0, 1000), 6)  # whole microseconds: exact in ns
    mount_translation = np.cumsum(rng.normal(scale=0.01, size=(1000, 3)), axis=0)
    mount_rotation = np.array([pin.exp3(np.array([0.0, 0.0, 0.002 * i])) for i in range(1000)])
    tree.add("mount", "world", Pose(mount_translation, mount_rotation, times=grid))
    tree.attach_urdf(urdf, "mount")
    arm = [f"panda_joint{i}" for i in range(1, 8)]
    times = np.round(np.linspace(0.0, 10.0, samples), 6)
    joints = [tree.joints[name] for name in arm]
    middle = np.array([(j.lower + j.upper) / 2 for j in joints])
    half_range = np.array([(j.upper - j.lower) / 2 for j in joints])
    positions = middle + 0.8 * half_range * np.sin(np.outer(times, np.arange(1, 8) * 0.3))
    tree.set_joint_trajectory(times, positions, arm)
    return tree, urdf, grid, mount_translation, mount_rotation, times, positions


def numpy_reference(model, chain, mount, times, positions):
    """Vectorised numpy FK of the mount and the 7 revolute joints, straight from the model."""
    world = reference_interpolate(times, *mount)
    for column, (placement, axis) in enumerate(chain):
        step = np.zeros((len(times), 4, 4))
        step[:, :3, :3] = placement.rotation @ matrix_from_axis_angle(axis, positions[:, column])
        step[:, :3, 3] = placement.translation
        step[:, 3, 3] = 1.0
        world = world @ step
    return world @ model.frames[model.getFrameId("panda_hand")].placement.homogeneous


def arm_chain(model):
    chain = []
    for joint_id in range(1, 8):
        joint = model.joints[joint_id]
        axis = {"JointModelRZ": (0.0, 0.0, 1.0)}.get(joint.shortname())
        if axis is None:
            raise SystemExit(f"unexpected joint {joint.shortname()}")
        chain.append((model.jointPlacements[joint_id], np.array(axis)))
    return chain


def pinocchio_loop(model, data, frame_id, mount_matrices, positions):
    out = np.empty((len(positions), 4, 4))
    q = pin.neutral(model)
    for i, row in enumerate(positions):
        q[:7] = row
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacement(model, data, frame_id)
        out[i] = mount_matrices[i] @ data.oMf[frame_id].homogeneous
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the 1,000,000-sample run")
    args = parser.parse_args()
    rng = np.random.default_rng(3)
    print(describe_machine())
    tree, urdf, grid, translation, rotation, times, positions = build_case(rng, 10_000)
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    mount = (grid, translation, quaternion_from_matrix(rotation))
    chain = arm_chain(model)

    ours = tree.pose("panda_hand", "world", times=times).matrix
    reference = numpy_reference(model, chain, mount, times, positions)
    mount_matrices = tree.pose("mount", "world", times=times).matrix
    loop = pinocchio_loop(model, data, model.getFrameId("panda_hand"), mount_matrices, positions)
    rows = [
        ("pinframes tree.pose", median_time(
            lambda: tree.pose("panda_hand", "world", times=times), 7), ours),
        ("numpy vectorised FK (reference)", median_time(
            lambda: numpy_reference(model, chain, mount, times, positions), 7), reference),
        ("Pinocchio loop per sample", median_time(
            lambda: pinocchio_loop(model, data, model.getFrameId("panda_hand"), mount_matrices,
                                   positions), 3), loop),
    ]
    base = rows[1][1]
    print("\nPanda on a moving mount (1,000 keyframes), hand in world at 10,000 samples")
    print(f"{'method':<34} {'median':>10} {'vs numpy':>9} {'max |diff| to pinframes':>24}")
    for label, seconds, result in rows:
        print(f"{label:<34} {seconds * 1e3:>8.2f} ms {seconds / base:>9.2f} "
              f"{np.max(np.abs(result - ours)):>24.1e}")

    if not args.quick:
        big_tree, *_ , big_times, _ = build_case(rng, 1_000_000)
        before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        start = time.perf_counter()
        big_tree.pose("panda_hand", "world", times=big_times)
        elapsed = time.perf_counter() - start
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"\n1,000,000 samples: {elapsed:.2f} s, process peak resident memory {peak:.0f} MB "
              f"(before the query {before:.0f} MB)")


if __name__ == "__main__":
    main()
