"""``pinframes info`` names a robot's SRDF by the robot (its URDF's name), and counts the
robot joints that carry samples."""

from __future__ import annotations

import json
from pathlib import Path

DUARO = Path(__file__).resolve().parents[1] / "data" / "kawasaki"


def test_info_names_the_srdf_by_its_robot(run_cli):
    finished = run_cli("info", DUARO / "duaro.urdf", "--srdf", DUARO / "khi_duaro.srdf")
    assert finished.returncode == 0, finished.stderr
    # the URDF's <robot name>, not its root link 'world'
    assert "srdf of robot 'khi_duaro' (top frame 'world')" in finished.stdout
    described = json.loads(run_cli("info", DUARO / "duaro.urdf", "--srdf",
                                   DUARO / "khi_duaro.srdf", "-f", "json").stdout)
    assert [robot["robot"] for robot in described["srdf"]] == ["khi_duaro"]
