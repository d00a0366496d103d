"""Inverse kinematics along a path: ``FrameTree.solve_joints`` against a per-sample pink loop.

For the UR5 (6 axes, tool0) and the Panda (7 axes, panda_hand) of example-robot-data and
UFACTORY's xArm7 (7 axes, link_eef; its kinematics in tests/data), a smooth joint trajectory
inside the limits is sampled at 100 Hz; Pinocchio (called directly)
gives the tool poses, which become the targets. ``solve_joints`` tracks them from the first
configuration; the reference is pink (``pink.solve_ik`` with a ``FrameTask``, QP solver daqp
or quadprog) in the loop people write: per sample, steps from the previous solution until
the tool is within the same tolerances (1e-6 m, 1e-6 rad), at most 50 steps.

pink's cost per sample does not depend on how many samples there are (each sample is its own
problem), so it runs on the first 1,000 samples of each case; ``solve_joints`` runs on all
of them (10^3 to 10^5), which shows whether its cost is linear in the samples. The table
gives medians of the time per sample and the ratio pink / solve_joints per round (the two
run in alternation); every solution is checked with Pinocchio on the URDF.

Run from the repository root after ``pip install ".[bench]"``::

    python benchmarks/bench_ik.py            # 10^3, 10^4, 10^5 samples, a few minutes
    python benchmarks/bench_ik.py --quick    # 10^3 and 10^4 samples, fewer rounds
"""

from __future__ import annotations

import json
import statistics
import sys
import time
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _machine import SETTINGS, describe_machine, format_seconds, quick_or_child, run_in_settings

TOLERANCE = 1e-6  # metres and radians, for both solvers
PINK_SAMPLES = 1_000
PINK_MAX_STEPS = 50
SAMPLE_RATE_HZ = 100.0
TESTS_DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
ROBOTS = {  # name: (URDF below example-robot-data's robots folder or a path, tool frame,
    #              home, swing)
    "UR5": ("ur_description/urdf/ur5_robot.urdf", "tool0",
            [0.0, -1.2, 1.5, -1.8, -1.571, 0.0], [0.8, 0.3, 0.4, 0.4, 0.4, 0.8]),
    "Panda": ("panda_description/urdf/panda.urdf", "panda_hand",
              [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, 0.02, 0.02],
              [0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6, 0.0, 0.0]),
    "xArm7": (str(TESTS_DATA / "xarm7" / "xarm7.urdf"), "link_eef",
              [0.0, -0.3, 0.0, 1.0, 0.0, 1.3, 0.0], [0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6]),
}


def robots_folder() -> Path:
    """example-robot-data's ``robots`` folder (version 6 ships no Python module: its files
    are found through the package's file list)."""
    for file in metadata.files("example-robot-data") or []:
        if file.name == "ur5_robot.urdf":
            return Path(str(file.locate())).parents[2]
    raise SystemExit("example-robot-data is not installed: pip install '.[bench]'")


def trajectory(home: list[float], swing: list[float], count: int) -> np.ndarray:
    """Joint values (count, nq) at 100 Hz: each joint swings about ``home`` at its own slow
    frequency (0.4 to 0.8 rad/s), inside the limits."""
    times = np.arange(count)[:, None] / SAMPLE_RATE_HZ
    joint = np.arange(len(home))[None, :]
    return np.asarray(home) + np.asarray(swing) * np.sin(0.4 * times * (1 + 0.15 * joint) + joint)


def tool_poses(model: pin.Model, tool: str, configurations: np.ndarray) -> list[pin.SE3]:
    data = model.createData()
    frame = model.getFrameId(tool)
    poses = []
    for q in configurations:
        pin.framesForwardKinematics(model, data, q)
        poses.append(data.oMf[frame].copy())
    return poses


def pink_loop(model: pin.Model, tool: str, targets: list[pin.SE3], start: np.ndarray,
              solver: str) -> tuple[np.ndarray, int]:
    """Per sample, pink steps from the previous solution until within the tolerances."""
    import pink
    from pink.tasks import FrameTask

    configuration = pink.Configuration(model, model.createData(), start.copy())
    task = FrameTask(tool, position_cost=1.0, orientation_cost=1.0)
    solutions = np.empty((len(targets), model.nq))
    reached = 0
    for index, target in enumerate(targets):
        task.set_target(target)
        for _ in range(PINK_MAX_STEPS):
            error = target.actInv(configuration.get_transform_frame_to_world(tool))
            if (np.linalg.norm(error.translation) <= TOLERANCE
                    and np.linalg.norm(pin.log3(error.rotation)) <= TOLERANCE):
                reached += 1
                break
            velocity = pink.solve_ik(configuration, [task], 1.0, solver=solver)
            configuration.integrate_inplace(velocity, 1.0)
        solutions[index] = configuration.q
    return solutions, reached


def largest_errors(model: pin.Model, tool: str, targets: list[pin.SE3], others: np.ndarray,
                   names: tuple[str, ...], positions: np.ndarray) -> tuple[float, float]:
    """Largest position (m) and orientation (rad) error of the solutions, by Pinocchio on
    the URDF (not pinframes' kinematics)."""
    data = model.createData()
    frame = model.getFrameId(tool)
    slots = [model.idx_qs[model.getJointId(name)] for name in names]
    worst = [0.0, 0.0]
    for index, target in enumerate(targets):
        q = others[index].copy()
        q[slots] = positions[index]
        pin.framesForwardKinematics(model, data, q)
        error = target.actInv(data.oMf[frame])
        worst[0] = max(worst[0], float(np.linalg.norm(error.translation)))
        worst[1] = max(worst[1], float(np.linalg.norm(pin.log3(error.rotation))))
    return worst[0], worst[1]


def measure(quick: bool) -> list[dict]:
    """The rows of one thread setting (run in a child process)."""
    import pinframes

    counts = (1_000, 10_000) if quick else (1_000, 10_000, 100_000)
    rounds = 3 if quick else 5
    folder = robots_folder()
    rows = []
    for robot, (urdf, tool, home, swing) in ROBOTS.items():
        path = folder / urdf  # an absolute path stays as it is
        model = pin.buildModelFromUrdf(str(path))
        tree = pinframes.FrameTree("floor")
        tree.attach_urdf(str(path), "floor")
        support = model.supports[model.frames[model.getFrameId(tool)].parentJoint]
        arm = [model.names[joint] for joint in list(support)[1:]]  # the joints moving the tool
        for count in counts:
            configurations = trajectory(home, swing, count)
            targets = tool_poses(model, tool, configurations)
            target = pinframes.Pose(np.array([t.translation for t in targets]),
                                    np.array([t.rotation for t in targets]),
                                    times=np.arange(count) / SAMPLE_RATE_HZ)
            seed = {name: float(configurations[0][model.idx_qs[model.getJointId(name)]])
                    for name in arm}
            pink_targets = targets[:PINK_SAMPLES]
            timings: dict[str, list[float]] = {"solve_joints": [], "pink + daqp": [],
                                               "pink + quadprog": []}
            for _ in range(rounds):
                start = time.perf_counter()
                solution = tree.solve_joints(tool, target, seed=seed)
                timings["solve_joints"].append((time.perf_counter() - start) / count)
                for method in ("pink + daqp", "pink + quadprog"):
                    start = time.perf_counter()
                    _, pink_reached = pink_loop(model, tool, pink_targets, configurations[0],
                                                method.split()[-1])
                    timings[method].append((time.perf_counter() - start) / len(pink_targets))
            position, orientation = largest_errors(model, tool, targets, configurations,
                                                   solution.joint_names, solution.positions)
            columns = [model.idx_qs[model.getJointId(name)] for name in solution.joint_names]
            returned = float(np.abs(solution.positions - configurations[:, columns]).max())
            steps = np.linalg.norm(np.diff(solution.positions, axis=0), axis=1).max() / (
                np.linalg.norm(np.diff(configurations[:, columns], axis=0), axis=1).max())
            case = f"{robot}, {count:,} samples"
            ours = timings["solve_joints"]
            rows.append({"case": case, "method": "solve_joints",
                         "seconds": statistics.median(ours), "ratio": 1.0,
                         "note": f"reached {int(solution.reached.sum()):,}/{count:,}; max "
                                 f"error {position:.1e} m, {orientation:.1e} rad; max "
                                 f"|q - trajectory| {returned:.1e}; largest step "
                                 f"{steps:.2f}x the trajectory's"})
            for method in ("pink + daqp", "pink + quadprog"):
                rows.append({"case": case, "method": method + f" ({len(pink_targets):,})",
                             "seconds": statistics.median(timings[method]),
                             "ratio": statistics.median(
                                 theirs / mine for theirs, mine in
                                 zip(timings[method], ours, strict=True)),
                             "note": f"reached {pink_reached:,}/{len(pink_targets):,}"})
    return rows


def child(quick: bool) -> None:
    print(json.dumps(measure(quick)))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "10^3 and 10^4 samples, 3 rounds")
    if quick is None:
        return
    print(describe_machine())
    results = run_in_settings(__file__, ["--quick"] if quick else [])
    header = "".join(f" {setting + ' per sample':>21} {'pink/ours':>9}" for setting in SETTINGS)
    print(f"\n{'case':<26} {'method':<24}{header}  note (1 thread)")
    for index, entry in enumerate(results[SETTINGS[0]]):
        cells = "".join(f" {format_seconds(results[s][index]['seconds']):>21} "
                        f"{results[s][index]['ratio']:>9.1f}" for s in SETTINGS)
        print(f"{entry['case']:<26} {entry['method']:<24}{cells}  {entry['note']}")
    print("\nper sample: median over rounds of the call's time / its samples; pink/ours: median "
          "over rounds of pink's time per sample / solve_joints' (above 1: solve_joints is "
          "faster); pink runs on the first 1,000 samples of each case.\n1 thread: "
          "OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1; busy: default threads beside a spinning "
          "process")


if __name__ == "__main__":
    main()
