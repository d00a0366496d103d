"""The command line on robots as ROS packages hold them: ``--xacro-arg``, ``--srdf``,
``--package-dir``, and scenes whose robots name theirs."""

from __future__ import annotations

import csv
import io
import json
import textwrap

import numpy as np
import pytest

from urdf.ros_packages import CELL, MA2010_XACRO, MOTOMAN, UR_XACRO
from urdf.test_srdf_files import pinocchio_clearance


def test_info_expands_a_xacro_with_its_arguments(run_cli):
    finished = run_cli("info", UR_XACRO, "--xacro-arg", "name:=arm",
                       "--xacro-arg", "ur_type:=ur5e")
    assert finished.returncode == 0, finished.stderr
    assert "shoulder_pan_joint" in finished.stdout
    missing = run_cli("info", UR_XACRO)
    assert missing.returncode == 1
    assert "--xacro-arg" in missing.stderr


def test_info_names_the_srdf_groups_and_states(run_cli):
    finished = run_cli("info", CELL / "cell.urdf", "--srdf", CELL / "cell.srdf", "-f", "json")
    assert finished.returncode == 0, finished.stderr
    (robot,) = json.loads(finished.stdout)["srdf"]
    assert robot["groups"]["wrist"] == ["ma2010_joint_4_r", "ma2010_joint_5_b",
                                        "ma2010_joint_6_t"]  # as cell.srdf lists them
    assert robot["group_states"] == {"weld_ready": "ma2010", "level": "d500"}
    assert robot["disabled_pairs"] == 14
    text = run_cli("info", CELL / "cell.urdf", "--srdf", CELL / "cell.srdf").stdout
    assert "groups 'ma2010' (6 joints), 'd500' (2 joints), 'cell' (8 joints)" in text


def test_a_malformed_xacro_argument_is_a_usage_error(run_cli):
    finished = run_cli("info", UR_XACRO, "--xacro-arg", "ur_type=ur5e")
    assert finished.returncode == 2
    assert "NAME:=VALUE" in finished.stderr


@pytest.mark.parametrize("srdf_flags", [[], ["--no-srdf-exclude"]], ids=["srdf", "all pairs"])
def test_clearance_of_the_cell_with_its_srdf_equals_pinocchio(run_cli, srdf_flags):
    finished = run_cli("clearance", CELL / "cell.urdf", "*", "*", "--srdf", CELL / "cell.srdf",
                       "--package-dir", MOTOMAN, *srdf_flags)
    assert finished.returncode == 0, finished.stderr
    row = next(csv.DictReader(io.StringIO(finished.stdout)))
    expected, _ = pinocchio_clearance([], [np.zeros(0)], remove_srdf_pairs=not srdf_flags)
    np.testing.assert_allclose(float(row["distance_m"]), expected[0], atol=1e-7)


def test_srdf_and_xacro_arguments_are_for_robot_files(run_cli, turntable):
    finished = run_cli("info", turntable, "--srdf", CELL / "cell.srdf")
    assert finished.returncode == 1
    assert "--srdf is for URDF and xacro files" in finished.stderr


def test_a_scene_robot_from_a_xacro_with_srdf_and_package_dirs(run_cli, tmp_path):
    scene = tmp_path / "cell.yaml"
    scene.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        name: cell
        robots:
          - name: robot
            urdf: {MA2010_XACRO}
            xacro: true
            prefix: "r/"
            srdf: {MOTOMAN / "motoman_ma2010_moveit_config/config/motoman_ma2010.srdf"}
            package_dirs: [{MOTOMAN}]
        frames:
          - {{name: target, parent: world, xyz: [1.2, 0.1, 1.0], rpy: [0, 1.5707963, 0]}}
        """))
    solved = run_cli("solve", scene, "--frame", "r/tool0", "--target", "target",
                     "--joints", "manipulator")
    assert solved.returncode == 0, solved.stderr
    header = solved.stdout.splitlines()[0].split(",")
    assert header[1:] == [f"joint_{n}" for n in ("1_s", "2_l", "3_u", "4_r", "5_b", "6_t")]
    # the meshes are found through the scene's package_dirs, remembered with the robot
    clearance = run_cli("clearance", scene, "r/base_link", "r/link_3_u")
    assert clearance.returncode == 0, clearance.stderr
    disabled = run_cli("clearance", scene, "r/link_1_s", "r/link_3_u")  # "Never" in the SRDF
    assert disabled.returncode == 1
    assert "--no-srdf-exclude" in disabled.stderr
