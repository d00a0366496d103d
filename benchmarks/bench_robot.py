"""Tool poses of a robot per sample: pinframes beside an independent numpy forward kinematics.

Case: the Panda of example-robot-data on a mount frame that moves with 1,000 keyframes,
10,000 joint samples, the hand pose in the world at every sample, and at one time (4.321 s,
between samples: the joint values and the mount interpolated there). Also timed: a
hand-written Pinocchio loop (forwardKinematics per sample, mount poses given). Both thread
settings, each in a child process (see ``_machine.py``); time and memory against the number
of samples are in ``bench_curves.py``.

Run: ``python benchmarks/bench_robot.py [--quick]``.
"""

from __future__ import annotations

import json
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin

import _reference as ref
from _machine import (
    describe_machine,
    interleaved,
    interleaved_per_call,
    print_table,
    quick_or_child,
    run_in_settings,
)
from pinframes import FrameTree, Pose

ARM = [f"panda_joint{i}" for i in range(1, 8)]


def panda_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "panda.urdf":
            return Path(file.locate())
    raise SystemExit("example-robot-data is not installed (pip install '.[test]')")


def build_case(rng, samples):
    """The tree, and the mount's keyframes (seconds, metres, quaternions), times, positions."""
    tree = FrameTree()
    grid = np.round(np.linspace(0.0, 10.0, 1000), 6)  # whole microseconds: exact in ns
    mount_translation = np.cumsum(rng.normal(scale=0.01, size=(1000, 3)), axis=0)
    turn = 0.001 * np.arange(1000)  # about z: quaternion (0, 0, sin, cos) of half the angle
    mount_quaternion = np.stack([0 * turn, 0 * turn, np.sin(turn), np.cos(turn)], axis=1)
    tree.add("mount", "world", Pose(mount_translation, mount_quaternion, times=grid))
    tree.attach_urdf(panda_urdf(), "mount")
    times = np.round(np.linspace(0.0, 10.0, samples), 6)
    joints = [tree.joints[name] for name in ARM]
    middle = np.array([(j.lower + j.upper) / 2 for j in joints])
    half_range = np.array([(j.upper - j.lower) / 2 for j in joints])
    positions = np.outer(times, np.arange(1, 8) * 0.3)  # in place: 10^7 samples are 560 MB
    np.sin(positions, out=positions)
    positions *= 0.8 * half_range
    positions += middle
    tree.set_joint_trajectory(times, positions, ARM)
    return tree, (grid, mount_translation, mount_quaternion), times, positions


def arm_chain(model):
    """Per arm joint: its placement in the parent joint (4, 4) and its unit axis."""
    chain = []
    for joint_id in range(1, 8):
        joint = model.joints[joint_id]
        if joint.shortname() != "JointModelRZ":
            raise SystemExit(f"unexpected joint {joint.shortname()}")
        chain.append((model.jointPlacements[joint_id].homogeneous, np.array([0.0, 0.0, 1.0])))
    return chain


def numpy_reference(hand, chain, mount, times, positions):
    """Vectorised numpy FK: the mount interpolated, then each joint's placement @ rotation."""
    world = ref.interpolate(times, *mount)
    for column, (placement, axis) in enumerate(chain):
        step = np.zeros((len(times), 4, 4))
        step[:, :3, :3] = placement[:3, :3] @ ref.rodrigues(axis, positions[:, column])
        step[:, :3, 3] = placement[:3, 3]
        step[:, 3, 3] = 1.0
        world = world @ step
    return world @ hand


def pinocchio_loop(model, data, frame_id, mount_matrices, positions):
    out = np.empty((len(positions), 4, 4))
    q = pin.neutral(model)
    for i, row in enumerate(positions):
        q[:7] = row
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacement(model, data, frame_id)
        out[i] = mount_matrices[i] @ data.oMf[frame_id].homogeneous
    return out


def child(quick: bool) -> None:
    tree, mount, times, positions = build_case(np.random.default_rng(3), 10_000)
    model = pin.buildModelFromUrdf(str(panda_urdf()))
    data = model.createData()
    chain = arm_chain(model)
    hand_id = model.getFrameId("panda_hand")
    hand = model.frames[hand_id].placement.homogeneous
    mount_matrices = ref.interpolate(times, *mount)
    case = "Panda on moving mount, 10,000 samples"
    calls = {
        "pinframes": lambda: tree.pose("panda_hand", "world", times=times),
        "numpy reference": lambda: numpy_reference(hand, chain, mount, times, positions),
        "Pinocchio loop": lambda: pinocchio_loop(model, data, hand_id, mount_matrices,
                                                 positions),
    }
    rows = interleaved(case, calls, 3 if quick else 9)
    expected = calls["numpy reference"]()
    rows[0]["error"] = float(np.max(np.abs(calls["pinframes"]().matrix - expected)))
    rows[2]["error"] = float(np.max(np.abs(calls["Pinocchio loop"]() - expected)))
    rows += one_time_rows(tree, hand, chain, mount, times, positions, quick)
    print(json.dumps(rows))


def one_time_rows(tree, hand, chain, mount, times, positions, quick):
    """The hand at one time between joint samples: pinframes beside numpy, which
    interpolates the seven joint values and the mount there and runs its forward kinematics."""
    at = np.array([4.321])

    def reference():
        values = np.array([[np.interp(at[0], times, column) for column in positions.T]])
        return numpy_reference(hand, chain, mount, at, values)

    case = "Panda on moving mount, one time"
    calls = {"pinframes": lambda: tree.pose("panda_hand", "world", times=4.321),
             "numpy reference": reference}
    rows = interleaved_per_call(case, calls, 6 if quick else 30)
    rows[0]["error"] = float(np.max(np.abs(calls["pinframes"]().matrix - reference())))
    return rows


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child)
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []))


if __name__ == "__main__":
    main()
