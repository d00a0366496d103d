"""docs/examples/small_cell.yaml, the scene that docs/scene-format.md shows whole, runs:
its poses are checked by hand, the joint values ``pinframes solve`` writes for it with
Pinocchio on the URDF."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pinocchio as pin

from pinframes import read_joint_trajectory, read_scene
from robot_checks import placements

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "docs" / "examples" / "small_cell.yaml"
ROBOT = ROOT / "models" / "welding_robot" / "welding_robot.urdf"


def seam_in_world(seconds: np.ndarray) -> np.ndarray:
    """The seam point by hand: 0.2 m along the table's x in 10 s (from -0.1 m, 0.05 m up),
    the table at (0.9, 0, 0.3) m turning linearly to 0.3 rad about z."""
    along = -0.1 + 0.02 * np.clip(seconds, 0.0, 10.0)
    yaw = 0.03 * np.clip(seconds, 0.0, 10.0)
    return np.column_stack([0.9 + along * np.cos(yaw), along * np.sin(yaw),
                            np.full(seconds.shape, 0.35)])


def test_the_document_shows_the_example_whole():
    blocks = re.findall(r"```yaml\n(.*?)```", (ROOT / "docs" / "scene-format.md").read_text(),
                        re.S)
    assert EXAMPLE.read_text() in blocks


def test_the_example_reads_with_the_poses_it_describes():
    tree = read_scene(EXAMPLE)
    assert {"table", "seam_point", "torch_target", "torch_tcp", "robot/flange"} <= set(
        tree.frames)
    seconds = np.array([0.0, 2.5, 5.0, 10.0])
    pose = tree.pose("seam_point", relative_to="world", times=seconds)
    np.testing.assert_allclose(pose.translation, seam_in_world(seconds), atol=1e-12)
    target = tree.pose("torch_target", relative_to="world", times=[5.0])
    # the torch's z points down into the plate
    np.testing.assert_allclose(target.rotation[0][:, 2], [0.0, 0.0, -1.0], atol=1e-12)


def test_the_documented_solve_runs_and_keeps_the_torch_on_the_seam(run_cli, tmp_path):
    out = tmp_path / "joints.csv"
    result = run_cli("solve", "docs/examples/small_cell.yaml", "--frame", "torch_tcp",
                     "--target", "torch_target", "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    seconds, positions, names = read_joint_trajectory(out)
    # the seam's keyframes, and between them as many samples as keep the torch on it
    assert f"{len(seconds)} samples, {len(seconds)} reached" in result.stderr
    assert len(seconds) > 3 and set(seconds).issuperset({0.0, 5.0, 10.0})
    assert names == [f"joint_{index}" for index in range(1, 7)]
    tips = [flange * pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.3]))
            for flange in placements(ROBOT, "flange", positions)]
    np.testing.assert_allclose([tip.translation for tip in tips], seam_in_world(seconds),
                               atol=1e-6)
    for tip in tips:
        assert math.isclose(tip.rotation[2, 2], -1.0, abs_tol=1e-9)
    # what a controller does: the joints linear between the samples, on a 10 ms grid
    fine = np.linspace(0.0, 10.0, 1001)
    between = np.stack([np.interp(fine, seconds, column) for column in positions.T], axis=1)
    tips = [flange * pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.3]))
            for flange in placements(ROBOT, "flange", between)]
    strays = np.linalg.norm([tip.translation for tip in tips] - seam_in_world(fine), axis=1)
    assert strays.max() <= 1e-4  # the default path tolerance, 0.1 mm
    assert max(tip.rotation[2, 2] for tip in tips) <= -math.cos(math.radians(0.1))  # down
