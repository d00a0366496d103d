"""``pinframes solve --configuration``: the welding robot (an OPW arm) kept on a requested
branch, the CSV checked with Pinocchio on the URDF, and the summary naming the branch."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import pinocchio as pin

from pinframes import read_joint_trajectory

ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
HOME = np.array([0.2, 0.4, -0.6, 0.1, 0.9, 0.3])  # rad: front, up, no flip


def test_solve_keeps_the_requested_configuration(run_cli, tmp_path):
    model = pin.buildModelFromUrdf(str(ROBOT))
    data = model.createData()
    flange = model.getFrameId("flange")
    pin.framesForwardKinematics(model, data, HOME)
    seam = data.oMf[flange].copy()
    quaternion = pin.Quaternion(seam.rotation).coeffs()
    scene = tmp_path / "cell.yaml"
    scene.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        name: cell
        frames:
          - name: seam
            parent: world
            xyz: {seam.translation.tolist()}
            quaternion: {quaternion.tolist()}
        robots:
          - {{name: welder, urdf: {ROBOT}, parent: world, prefix: robot/}}
        """))
    out = tmp_path / "joints.csv"
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam",
                     "--start", "0", "--stop", "1", "--step", "0.5",
                     "--configuration", "front,down,flip", "-o", out)
    assert result.returncode == 0, result.stderr
    assert "3 samples, 3 reached" in result.stderr
    assert "configuration front,down,flip" in result.stderr
    _, positions, _ = read_joint_trajectory(out)
    for q in positions:
        pin.framesForwardKinematics(model, data, q)
        error = pin.log6(data.oMf[flange].inverse() * seam).vector
        assert np.linalg.norm(error) <= 1e-9
        assert q[4] < 0.0 and abs(q[2] - HOME[2]) > 0.5  # flipped wrist, the other elbow
