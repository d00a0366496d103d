"""The demo's clearance lines on the bundled cell, against distances worked out on their own.

- ``robot/link_1`` turns on ``joint_1`` about the vertical axis 0.2 m above its base plate,
  and its collision cylinder (models/README.md: radius 0.14 m, from 0 to 0.2 m in the link)
  hangs over the riser box (0.45 m wide, its top at the base plate): 200.0 mm at every time.
- The torch's neck cylinder against the pipe's cylinder, placed by the link poses and
  measured by coal called directly, for the pair the demo leaves out.
"""

from __future__ import annotations

import re
from pathlib import Path

import coal
import numpy as np
import pytest

from pinframes import read_scene

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell"


def torch_to_pipe_mm(times) -> float:
    """The smallest distance between the torch's three collision cylinders and the pipe's,
    over ``times``, from the URDF numbers and coal alone (poses from the tree)."""
    tree = read_scene(CELL / "scene.yaml")
    neck_roll = 0.383972435  # geometry/torch.urdf: the neck cylinder's origin
    torch = [(coal.Cylinder(0.035, 0.06), np.eye(3), [0, 0, 0.03]),
             (coal.Cylinder(0.022, 0.19), np.eye(3), [0, 0, 0.155]),
             (coal.Cylinder(0.011, 0.145),
              np.array([[1, 0, 0], [0, np.cos(neck_roll), -np.sin(neck_roll)],
                        [0, np.sin(neck_roll), np.cos(neck_roll)]]), [0, -0.027159, 0.317221])]
    pipe = coal.Cylinder(0.10955, 0.58)
    flange = tree.pose("torch", "world", times=times).matrix
    workpiece = tree.pose("pipe", "world", times=times).matrix
    smallest = np.inf
    for k in range(len(times)):
        pipe_at = coal.Transform3s(workpiece[k][:3, :3], workpiece[k][:3, 3])
        for shape, rotation, xyz in torch:
            placed = flange[k] @ np.block([[rotation, np.array(xyz)[:, None]], [0, 0, 0, 1]])
            result = coal.DistanceResult()
            smallest = min(smallest, coal.distance(
                shape, coal.Transform3s(placed[:3, :3], placed[:3, 3]), pipe, pipe_at,
                coal.DistanceRequest(), result))
    return 1000 * smallest


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_demo_names_the_closest_pair_and_the_pairs_it_leaves_out(run_cli, tmp_path):
    result = run_cli("demo", "--out", "results", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    lines = {line.split("  ", 1)[0]: line.split("  ", 1)[1].strip()
             for line in result.stdout.splitlines()[1:]}
    assert re.fullmatch(r"200\.0 mm between robot/link_1 and fixtures at [0-9.]+ s; no contact",
                        lines["robot-cell clearance"]), lines["robot-cell clearance"]
    left_out = lines["pairs not counted"]
    assert "robot/base_link-fixtures (the robot stands on its riser)" in left_out
    seam = re.search(r"torch-pipe \(the torch works at the seam: ([0-9.]+) mm", left_out)
    assert seam is not None, left_out
    times = read_scene(CELL / "scene.yaml").clearance_times("torch", "pipe")
    assert float(seam.group(1)) == round(torch_to_pipe_mm(times.offsets / 1e9), 1)
