"""What the command line says about a bag a new user hands it: a missing robot points at
--robot-description, mesh warnings of a bag's robot say where they looked (once per mesh),
counts read "1 message". Bags written with rosbags' own writers."""

from __future__ import annotations

from pathlib import Path

import pytest

pytest.importorskip("rosbags")
from ros.bag_writing import (
    STRING,
    Message,
    Transform,
    string,
    tf_messages,
    write_bag,
)

URDF = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
START = 1_700_000_000 * 1_000_000_000

TWO_LINKS_ONE_MESH = """\
<?xml version="1.0"?>
<robot name="gripper">
  <link name="base_link">
    <visual><geometry><mesh filename="package://gripper_parts/meshes/finger.stl"/></geometry></visual>
  </link>
  <link name="finger">
    <visual><geometry><mesh filename="package://gripper_parts/meshes/finger.stl"/></geometry></visual>
  </link>
  <joint name="slide" type="prismatic">
    <parent link="base_link"/><child link="finger"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.05" velocity="0.1" effort="10"/>
  </joint>
</robot>
"""


def tf_only_bag(tmp_path: Path) -> Path:
    """world -> base_link on /tf_static, one message; no /robot_description."""
    return write_bag(tmp_path / "cell", "mcap", tf_messages(
        2, [Transform("world", "base_link", START, (0.5, 0.0, 0.0))], topic="/tf_static"))


def test_a_frame_missing_from_a_bag_without_a_robot_points_at_robot_description(
        run_cli, tmp_path):
    bag = tf_only_bag(tmp_path)
    result = run_cli("pose", bag, "flange", "-r", "world")
    assert result.returncode == 1
    assert "'flange'" in result.stderr and "--robot-description" in result.stderr
    given = run_cli("--robot-description", URDF, "pose", bag, "flange", "-r", "world")
    assert given.returncode == 0, given.stderr


def test_a_frame_missing_from_a_bag_with_its_robot_gets_no_such_hint(run_cli, tmp_path):
    bag = tf_only_bag(tmp_path)
    result = run_cli("--robot-description", URDF, "pose", bag, "no_such_link")
    assert result.returncode == 1
    assert "--robot-description" not in result.stderr


def test_one_message_is_one_message(run_cli, tmp_path):
    result = run_cli("info", tf_only_bag(tmp_path))
    assert result.returncode == 0, result.stderr
    assert "(tf2_msgs/msg/TFMessage, 1 message)" in result.stdout
    assert "1 messages" not in result.stdout


def test_a_missing_mesh_of_a_bags_robot_is_one_warning_that_says_where_it_looked(
        run_cli, tmp_path, monkeypatch):
    pytest.importorskip("trimesh")
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    messages = tf_messages(2, [Transform("world", "base_link", START)], topic="/tf_static")
    messages.append(Message("/robot_description", STRING, START,
                            string(2, TWO_LINKS_ONE_MESH)))
    bag = write_bag(tmp_path / "gripper", "mcap", messages)
    result = run_cli("view", bag, "-o", tmp_path / "page.html")
    assert result.returncode == 0, result.stderr
    lines = [line for line in result.stderr.splitlines() if "finger.stl" in line]
    assert len(lines) == 1, result.stderr  # two links, one mesh: one warning
    assert lines[0].startswith("pinframes: warning: ")
    assert "looked in )" not in lines[0]
    assert "no folder to look in" in lines[0] and "--package-dir" in lines[0]

    parts = tmp_path / "parts"
    result = run_cli("view", bag, "--package-dir", parts, "-o", tmp_path / "page2.html")
    lines = [line for line in result.stderr.splitlines() if "finger.stl" in line]
    assert len(lines) == 1 and "no package 'gripper_parts'" in lines[0]
    assert f"in {parts}" in lines[0]
