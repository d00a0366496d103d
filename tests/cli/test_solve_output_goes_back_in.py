"""Output that goes back in: ``solve -o joints.csv`` over a robot and a positioner writes one
file with both robots' joints, and each scene robot's ``trajectory:`` takes its own columns
from it (by prefixed or unprefixed name); ``solve --step`` does not warn that the joints it
solves have no samples. The joints read back are checked against the CSV by numpy, and the
torch on the seam by Pinocchio on the two URDFs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import TILT_TURN, example_robot, faceplates, pipe_scene
from pinframes import read_scene
from pinframes.errors import FileFormatError, JointWithoutSamplesWarning

ARM = [f"ur/{name}" for name in ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                 "wrist_1_joint", "wrist_2_joint", "wrist_3_joint")]
BASE = pin.SE3(np.eye(3), np.array([0.55, 0.0, 0.0]))  # the positioner's base in the world
HALF = np.pi / 8  # the seam of pipe_scene turns by twice this


def seam_rotation(time: float) -> np.ndarray:
    """The seam's axes on the faceplate: its two keyframes slerped (time in 0..1 s)."""
    start = pin.Quaternion(0.5, 0.5, 0.5, 0.5)  # w x y z
    later = pin.Quaternion(np.cos(HALF), 0.0, np.sin(HALF), 0.0)
    return start.slerp(time, later).matrix()


@pytest.fixture
def cell(tmp_path: Path) -> tuple[Path, Path]:
    positioner = tmp_path / "positioner.urdf"
    positioner.write_text(TILT_TURN)
    scene = tmp_path / "pipe.yaml"
    scene.write_text(pipe_scene(positioner))
    return scene, positioner


def solve(run_cli, scene: Path, *times: str, output: Path | None = None):
    return run_cli("solve", scene, "--frame", "ur/tool0", "--target", "torch_target",
                   "--free-axis", "z", "--joints", *ARM, "pos/tilt_x", "pos/turn",
                   "--flat", "seam", *times, *(() if output is None else ("-o", output)))


def test_the_solved_csv_drives_both_robots_of_a_scene(run_cli, cell, tmp_path):
    scene, positioner = cell
    joints = tmp_path / "joints.csv"
    result = solve(run_cli, scene, "--start", "0", "--stop", "1", "--step", "0.25",
                   output=joints)
    assert result.returncode == 0, result.stderr
    assert "have no samples" not in result.stderr  # --step: the solved joints need none
    header = joints.read_text().splitlines()[0].split(",")
    assert header == ["time_s", *ARM, "pos/tilt_x", "pos/turn"]
    table = np.loadtxt(joints, delimiter=",", skiprows=1)
    # both robots read their own columns of the one file: by prefixed name
    driven = tmp_path / "driven.yaml"
    driven.write_text(pipe_scene(positioner, ("joints.csv", "joints.csv")))
    tree = read_scene(driven)
    snapshots = [tree.snapshot(time) for time in table[:, 0]]
    for row, snapshot in zip(table, snapshots, strict=True):
        np.testing.assert_allclose([snapshot.joint_values[name] for name in ARM], row[1:7],
                                   atol=1e-12)
        np.testing.assert_allclose([snapshot.joint_values["pos/tilt_x"],
                                    snapshot.joint_values["pos/turn"]], row[7:], atol=1e-12)
    # and those joints put the torch on the seam, by Pinocchio on the URDFs
    robot = pin.buildModelFromUrdf(str(example_robot("ur5_robot.urdf")))
    data = robot.createData()
    plates = faceplates(positioner, BASE, table[:, 7:])
    for row, plate in zip(table, plates, strict=True):
        pin.framesForwardKinematics(robot, data, row[1:7])
        seam = plate * pin.SE3(seam_rotation(row[0]), np.array([0.0, 0.0, 0.05]))
        target = seam * pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.1]))
        assert np.linalg.norm(data.oMf[robot.getFrameId("tool0")].translation
                              - target.translation) <= 1e-6


def test_unprefixed_columns_and_a_column_no_robot_has(cell, tmp_path):
    _, positioner = cell
    (tmp_path / "arm.csv").write_text(
        "time_s,shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,"
        "wrist_2_joint,wrist_3_joint,pos/turn\n0,0.1,-1.2,1.5,-1.8,-1.5,0.2,0.3\n"
        "1,0.2,-1.2,1.5,-1.8,-1.5,0.2,0.4\n")
    driven = tmp_path / "driven.yaml"
    driven.write_text(pipe_scene(positioner, ("arm.csv", "arm.csv")))
    tree = read_scene(driven)
    with pytest.warns(JointWithoutSamplesWarning, match="pos/tilt_x"):  # not in the file
        snapshot = tree.snapshot(1.0)
    assert snapshot.joint_values["ur/shoulder_pan_joint"] == pytest.approx(0.2)
    assert snapshot.joint_values["pos/turn"] == pytest.approx(0.4)
    (tmp_path / "ghost.csv").write_text("time_s,shoulder_pan_joint,cell/ghost\n0,0,0\n")
    driven.write_text(pipe_scene(positioner, ("ghost.csv", "ghost.csv")))
    with pytest.raises(FileFormatError, match=r"no joint 'ur/cell/ghost' nor 'cell/ghost'"):
        read_scene(driven)
