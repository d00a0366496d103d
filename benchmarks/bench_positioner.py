"""Flat welding and process windows: ``solve_joints(flat=...)`` and ``solve_joints(tilt=...)``
against the same solves without them.

Flat: a UR5 of example-robot-data at the floor's origin holds its tool0 (z free, a torch) on
a pipe's girth seam, half a turn sampled at 1,000 and 10,000 points, on a two-axis (tilt,
turn) positioner solved with it: 8 joints for 5 rows. ``solve_joints`` runs with
``flat="seam"`` (the freedom left keeps the seam's face up) and without it (the smallest
motion); the flat solution's largest angle between the seam's face and up is checked with
Pinocchio on the positioner's URDF. Windows: the UR5 alone (z free) follows a target that
wanders and tilts by up to 0.3 rad about its x and 0.2 rad about its y, 1,000 and 10,000
samples, with ``tilt=(0.2, 0.2)`` and without.

The solves of a case run in alternation with a reference that shares no code with
pinframes: Pinocchio called directly for the least any sample-by-sample solve does, one
``framesForwardKinematics`` and one ``computeFrameJacobian`` per sample. The table gives
medians of the time per call and ratios to the plain solve per round.

Run from the repository root after ``pip install ".[bench]"``::

    python benchmarks/bench_positioner.py            # 5 rounds
    python benchmarks/bench_positioner.py --quick    # 3 rounds
"""

from __future__ import annotations

import json
import sys
import tempfile
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings

RADIUS, ALONG = 0.1, 0.05  # m: the pipe's radius, the seam's height on the faceplate
BASE = [0.55, 0.0, 0.0]  # m: the positioner's base in the floor
PLAIN = "solve_joints (plain)"
WINDOWS = (0.2, 0.2)  # rad about the target's x and y
POSITIONER = """<?xml version="1.0"?>
<robot name="positioner">
  <link name="base"/><link name="cradle"/><link name="faceplate"/>
  <joint name="tilt_x" type="revolute"><parent link="base"/><child link="cradle"/>
    <origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" velocity="1" effort="1"/></joint>
  <joint name="turn" type="revolute"><parent link="cradle"/><child link="faceplate"/>
    <axis xyz="0 0 1"/><limit lower="-6" upper="6" velocity="1" effort="1"/></joint>
</robot>
"""


def ur5_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "ur5_robot.urdf":
            return Path(str(file.locate()))
    raise SystemExit("example-robot-data is not installed")


def girth_seam(count: int) -> tuple[np.ndarray, np.ndarray]:
    """Origins (T, 3) and axes (T, 3, 3) on the faceplate: x along, z out of the pipe."""
    around = np.linspace(0.0, np.pi, count)
    zeros = np.zeros(count)
    origins = np.stack([RADIUS * np.cos(around), RADIUS * np.sin(around), zeros + ALONG], 1)
    outward = np.stack([np.cos(around), np.sin(around), zeros], 1)
    travel = np.stack([-np.sin(around), np.cos(around), zeros], 1)
    return origins, np.stack([travel, np.cross(outward, travel), outward], axis=2)


def face_from_up(positioner_urdf: Path, positioner: np.ndarray, axes: np.ndarray) -> float:
    """Largest angle (deg) between the seam's z and up, by Pinocchio on the URDF."""
    model = pin.buildModelFromUrdf(str(positioner_urdf))
    data = model.createData()
    plate = model.getFrameId("faceplate")
    worst = 0.0
    for q, seam in zip(positioner, axes, strict=True):
        pin.framesForwardKinematics(model, data, q)
        face = data.oMf[plate].rotation @ seam[:, 2]
        worst = max(worst, float(np.degrees(np.arccos(min(1.0, face[2])))))
    return worst


def measure(quick: bool) -> list[dict]:
    """The rows of one thread setting (run in a child process)."""
    import pinframes

    rounds = 3 if quick else 5
    robot = pin.buildModelFromUrdf(str(ur5_urdf()))
    robot_data = robot.createData()
    tool = robot.getFrameId("tool0")
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        urdf = Path(folder) / "positioner.urdf"
        urdf.write_text(POSITIONER)
        for count in (1_000, 10_000):
            tree = pinframes.FrameTree("floor")
            tree.attach_urdf(ur5_urdf(), "floor")
            tree.add("positioner_base", "floor", pinframes.Pose(BASE))
            tree.attach_urdf(urdf, "positioner_base", prefix="positioner/")
            origins, axes = girth_seam(count)
            tree.add("seam", "positioner/faceplate",
                     pinframes.Pose(origins, axes, times=np.linspace(0.0, 60.0, count)))
            tree.add("torch_target", "seam",
                     pinframes.Pose([0.0, 0.0, 0.0], [[1, 0, 0], [0, -1, 0], [0, 0, -1]]))
            joints = [*(name for name in tree.joints if not name.startswith("positioner/")),
                      "positioner/tilt_x", "positioner/turn"]
            configurations = np.zeros((count, robot.nq))
            solutions: dict[str | None, pinframes.JointSolution] = {}

            def solve(flat: str | None, tree: pinframes.FrameTree = tree,
                      joints: list[str] = joints,
                      solutions: dict[str | None, pinframes.JointSolution] = solutions) -> None:
                solutions[flat] = tree.solve_joints("tool0", "torch_target", joints=joints,
                                                    free_axis="z", flat=flat)

            def pinocchio_per_sample(configurations: np.ndarray = configurations) -> None:
                for q in configurations:
                    pin.framesForwardKinematics(robot, robot_data, q)
                    pin.computeFrameJacobian(robot, robot_data, q, tool,
                                             pin.ReferenceFrame.LOCAL)

            case = f"UR5 + tilt-turn, {count:,} samples"
            measured = interleaved(case, {PLAIN: lambda: solve(None),
                                          "flat=seam": lambda: solve("seam"),
                                          "Pinocchio FK+Jacobian": pinocchio_per_sample},
                                   rounds, reference=PLAIN)
            flat = solutions["seam"]
            plain = solutions[None]
            for entry in measured:
                if entry["method"] == "flat=seam":
                    entry["note"] = (f"reached {int(flat.reached.sum()):,}/{count:,}; face "
                                     f"{face_from_up(urdf, flat.positions[:, 6:], axes):.2g} "
                                     "deg from up at most")
                if entry["method"] == PLAIN:
                    entry["note"] = (f"reached {int(plain.reached.sum()):,}/{count:,}; face "
                                     f"{face_from_up(urdf, plain.positions[:, 6:], axes):.2g} "
                                     "deg from up at most")
            rows.extend(measured)
        for count in (1_000, 10_000):
            rows.extend(windows_case(pinframes, robot, count, rounds))
    return rows


def windows_case(pinframes: Any, robot: pin.Model, count: int, rounds: int) -> list[dict]:
    """The rows of the process-window case at ``count`` samples."""
    data = robot.createData()
    tool = robot.getFrameId("tool0")
    pin.framesForwardKinematics(robot, data, np.array([0.2, -1.2, 1.5, -1.8, -1.571, 0.0]))
    start = data.oMf[tool].copy()
    times = np.linspace(0.0, 10.0, count)
    targets = [start * pin.SE3(pin.utils.rotate("x", 0.3 * np.sin(t))
                               @ pin.utils.rotate("y", 0.2 * np.sin(0.7 * t)),
                               np.array([0.1 * np.sin(0.5 * t), 0.01 * t, 0.0]))
               for t in times]
    target = pinframes.Pose(np.array([t.translation for t in targets]),
                            np.array([t.rotation for t in targets]), times=times)
    tree = pinframes.FrameTree("floor")
    tree.attach_urdf(ur5_urdf(), "floor")
    configurations = np.zeros((count, robot.nq))
    solutions = {}

    def solve(tilt: tuple[float, float] | None) -> None:
        solutions[tilt] = tree.solve_joints("tool0", target, free_axis="z", tilt=tilt)

    def pinocchio_per_sample() -> None:
        for q in configurations:
            pin.framesForwardKinematics(robot, data, q)
            pin.computeFrameJacobian(robot, data, q, tool, pin.ReferenceFrame.LOCAL)

    measured = interleaved(f"UR5 windows, {count:,} samples",
                           {PLAIN: lambda: solve(None), "tilt=(0.2, 0.2)": lambda: solve(WINDOWS),
                            "Pinocchio FK+Jacobian": pinocchio_per_sample},
                           rounds, reference=PLAIN)
    for entry in measured:
        solution = solutions.get(None if entry["method"] == PLAIN else WINDOWS)
        if entry["method"] != "Pinocchio FK+Jacobian" and solution is not None:
            note = f"reached {int(solution.reached.sum()):,}/{count:,}"
            if solution.tilt is not None:
                largest = np.abs(solution.tilt).max(axis=0)
                note += f"; largest tilt {largest[0]:.4f}, {largest[1]:.4f} rad"
            entry["note"] = note
    return measured


def child(quick: bool) -> None:
    print(json.dumps(measure(quick)))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0] + __doc__.splitlines()[1], child,
                           "3 rounds")
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference=PLAIN)


if __name__ == "__main__":
    main()
