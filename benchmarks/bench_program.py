"""Planning a welding program against the inverse kinematics it needs.

The program: the bundled six-axis welding robot at the origin, a tool 0.2 m out on its
flange, three straight seams of 0.2 m (10 s each on their own times) welded with a 50 mm
approach and retract, and four air moves (point to point: to each seam's approach point and
home). ``WeldProgram.plan`` (4 ms step, no clearance check) beside ``FrameTree.solve_joints``
called directly on the same samples: the calls one plan makes (every node of every approach,
seam and retract path and every approach point, each from where the program stands),
recorded once and replayed (the goal: planning at most 2x those solves). Beside them, for
scale, the plan with the clearance check of the robot's links against a box beside the
seams (``check=``).

Run from the repository root after ``pip install ".[bench]"``::

    python benchmarks/bench_program.py            # 5 rounds
    python benchmarks/bench_program.py --quick    # 3 rounds
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

import pinframes

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings

ROBOT = Path(__file__).resolve().parents[1] / "models" / "welding_robot" / "welding_robot.urdf"
HOME = np.array([0.0, 0.3, -0.3, 0.0, 0.8, 0.0])  # rad
SEAMS = [([0.55, -0.1, 0.3], [0.55, 0.1, 0.3]), ([0.7, -0.1, 0.25], [0.7, 0.1, 0.25]),
         ([0.6, 0.15, 0.35], [0.8, 0.15, 0.35])]  # m: each seam's start and end
SOLVES = "solve_joints, same samples"


def cell() -> pinframes.FrameTree:
    tree = pinframes.FrameTree("world")
    tree.attach_urdf(ROBOT, parent="world", prefix="robot/")
    tree.add("tcp", "robot/flange", pinframes.Pose([0.0, 0.0, 0.2]))
    down = pinframes.Pose.from_xyz_rpy(roll=np.pi)
    for number, (start, end) in enumerate(SEAMS, 1):
        travel = np.subtract(end, start)
        heading = np.arctan2(travel[1], travel[0])
        axes = pinframes.Pose.from_xyz_rpy(yaw=heading).rotation
        tree.add(f"seam_{number}", "world",
                 pinframes.Pose(np.array([start, end]), axes, times=[0.0, 10.0]))
        tree.add(f"torch_{number}", f"seam_{number}", down)
    tree.add("box", "world", pinframes.Pose([0.9, -0.3, 0.2]))
    tree.add_geometry("box", pinframes.Box([0.2, 0.2, 0.4]))
    return tree


def program(tree: pinframes.FrameTree) -> pinframes.WeldProgram:
    limits = {f"joint_{i}": {"acceleration": 6.0} for i in range(1, 7)}
    planned = pinframes.WeldProgram(tree, "tcp", limits=limits, start=HOME)
    for number in range(1, len(SEAMS) + 1):
        planned.weld(f"seam_{number}", torch=f"torch_{number}", name=f"seam {number}")
    planned.move_joints(list(HOME), name="home")
    return planned


def recorded_solves(tree: pinframes.FrameTree, planned: pinframes.WeldProgram
                    ) -> list[tuple[tuple, dict]]:
    """The arguments of every ``solve_joints`` call one plan makes (the same samples, seeds
    and reference frames), recorded by standing in for the tree's method once."""
    calls: list[tuple[tuple, dict]] = []
    solve = tree.solve_joints

    def recording(*args: object, **kwargs: object) -> object:
        calls.append((args, kwargs))
        return solve(*args, **kwargs)

    tree.solve_joints = recording  # type: ignore[method-assign]
    try:
        planned.plan()
    finally:
        del tree.solve_joints
    return calls


def same_solves(tree: pinframes.FrameTree, calls: list[tuple[tuple, dict]]) -> None:
    """``solve_joints`` called directly with the arguments the plan called it with."""
    for args, kwargs in calls:
        tree.solve_joints(*args, **kwargs)


def child(quick: bool) -> None:
    tree = cell()
    planned = program(tree)
    motion = planned.plan()
    assert motion.all_reached
    calls = recorded_solves(tree, planned)
    samples = sum(len(kwargs["times"]) for _, kwargs in calls)
    check = dict(a="robot/*", b="box")
    rows = interleaved(f"3 seams + 4 air moves, {samples:,} IK samples",
                       {SOLVES: lambda: same_solves(tree, calls),
                        "plan()": planned.plan,
                        "plan(check=...)": lambda: planned.plan(check=check)},
                       3 if quick else 5, reference=SOLVES)
    for entry in rows:
        entry["note"] = f"{len(motion):,} samples, cycle {motion.cycle_time:.2f} s"
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "3 rounds instead of 5")
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference=SOLVES)


if __name__ == "__main__":
    main()
