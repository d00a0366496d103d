"""Joint trajectories written by ``pinframes.write_joint_trajectory``, ``pinframes solve -o``
and ``pinframes convert --time`` (the URDF's ``.joints.csv``) read back exactly, whatever the
joint names (a comma, ``time_s``), and as bags they carry a ``JointTrajectory`` and the
joint states (decoded by rosbags and by the ``mcap`` library)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

import pinframes
from pinframes import FrameTree, Pose

# a planar arm whose joints are named as a CSV header cannot hold unquoted
ARM = """\
<robot name="odd_names">
  <link name="base"/><link name="upper"/><link name="fore"/><link name="tool"/>
  <joint name="a,b" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <joint name="time_s" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <joint name="tool_mount" type="fixed">
    <parent link="fore"/><child link="tool"/><origin xyz="0.4 0 0"/>
  </joint>
</robot>
"""
NAMES = ["a,b", "time_s"]
TIMES = np.array([0.0, 0.5, 1.0, 1.5, 2.0])
Q1 = 0.2 + 0.3 * TIMES  # rad
Q2 = 0.9 - 0.2 * TIMES


def tool_in_world(q1: np.ndarray, q2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The tool of the planar arm, by hand: positions (T, 3) and yaw angles (T,)."""
    x = 0.5 * np.cos(q1) + 0.4 * np.cos(q1 + q2)
    y = 0.5 * np.sin(q1) + 0.4 * np.sin(q1 + q2)
    return np.column_stack([x, y, np.full_like(x, 0.1)]), q1 + q2


@pytest.fixture
def scene(tmp_path: Path) -> Path:
    """The arm (prefix ``arm/``) and a target that moves where the tool is at Q1, Q2."""
    (tmp_path / "arm.urdf").write_text(ARM)
    positions, yaws = tool_in_world(Q1, Q2)
    keyframes = "\n".join(
        f"      - {{time: {float(t)!r}, xyz: {p.tolist()}, rpy: [0, 0, {float(yaw)!r}]}}"
        for t, p, yaw in zip(TIMES, positions, yaws, strict=True))
    path = tmp_path / "cell.yaml"
    path.write_text("pinframes_scene: 1\nname: cell\nframes:\n  - name: target\n"
                    "    parent: world\n    keyframes:\n" + keyframes + "\n"
                    + textwrap.dedent("""\
                        robots:
                          - {name: arm, urdf: arm.urdf, parent: world, prefix: arm/}
                        """))
    return path


def test_solution_csv_and_npz_read_back_exactly(scene, tmp_path):
    tree = pinframes.read_scene(scene)
    solution = tree.solve_joints("arm/tool", "target", times=TIMES)
    assert solution.all_reached  # within 1e-6 m and rad: joint values within a few 1e-6 rad
    np.testing.assert_allclose(solution.positions, np.column_stack([Q1, Q2]), atol=1e-5)
    for name in ("q.csv", "q.npz"):
        pinframes.write_joint_trajectory(solution, tmp_path / name, tree=tree)
        times, positions, names = pinframes.read_joint_trajectory(tmp_path / name)
        assert names == NAMES  # the URDF's names: the scene's prefix removed
        assert np.array_equal(positions, solution.positions)
        seconds = times if times.dtype.kind == "f" else times.astype(np.int64) / 1e9
        assert np.array_equal(seconds, TIMES)
    # without tree=: the solution knows its robot and names the joints as the URDF does
    assert solution.urdf_joint_names == tuple(NAMES)
    pinframes.write_joint_trajectory(solution, tmp_path / "no_tree.csv")
    assert pinframes.read_joint_trajectory(tmp_path / "no_tree.csv")[2] == NAMES
    # a bag for the robot's controller: the JointTrajectory names, read by the mcap library
    pinframes.write_joint_trajectory(solution, tmp_path / "motion.mcap")
    assert _trajectory_joint_names(tmp_path / "motion.mcap") == NAMES


def test_a_scene_robot_reads_what_solve_wrote(scene, tmp_path, run_cli):
    result = run_cli("solve", scene, "--frame", "arm/tool", "--target", "target",
                     "--times", *map(str, TIMES), "-o", tmp_path / "arm.csv")
    assert result.returncode == 0, result.stderr
    text = (tmp_path / "arm.csv").read_text()
    assert text.splitlines()[0] == 'time_s,"a,b",time_s'
    driven = scene.read_text().replace("prefix: arm/}", "prefix: arm/, trajectory: arm.csv}")
    (tmp_path / "driven.yaml").write_text(driven)
    tree = pinframes.read_scene(tmp_path / "driven.yaml")
    pose = tree.pose("arm/tool", "world", times=TIMES)
    expected, yaws = tool_in_world(Q1, Q2)
    np.testing.assert_allclose(pose.translation, expected, atol=1e-6)
    np.testing.assert_allclose(np.arctan2(pose.rotation[:, 1, 0], pose.rotation[:, 0, 0]),
                               yaws, atol=1e-6)


def test_solve_writes_a_joint_trajectory_bag(scene, tmp_path, run_cli):
    pytest.importorskip("mcap_ros2")
    from ros.bag_decoding import READERS, decode

    result = run_cli("solve", scene, "--frame", "arm/tool", "--target", "target",
                     "--times", *map(str, TIMES), "-o", tmp_path / "arm.mcap")
    assert result.returncode == 0, result.stderr
    csv = run_cli("solve", scene, "--frame", "arm/tool", "--target", "target",
                  "--times", *map(str, TIMES), "-o", tmp_path / "arm.csv")
    assert csv.returncode == 0, csv.stderr
    _, positions, _ = pinframes.read_joint_trajectory(tmp_path / "arm.csv")
    for reader in READERS:
        records = decode(tmp_path / "arm.mcap", reader)
        (trajectory,) = records["/joint_trajectory"]
        assert trajectory["names"] == NAMES
        assert trajectory["stamp_ns"] == 0  # a controller starts it on receipt
        assert [point[0] for point in trajectory["points"]] == (TIMES * 1e9).astype(int).tolist()
        assert np.array_equal([point[1] for point in trajectory["points"]], positions)
        states = records["/joint_states"]
        assert [row["stamp_ns"] for row in states] == (TIMES * 1e9).astype(int).tolist()
        assert np.array_equal([row["positions"] for row in states], positions)
        assert all(row["names"] == NAMES for row in states)


@pytest.mark.parametrize("name", ["m.mcap", "m.bag"])
def test_a_trajectory_bag_drives_the_robot_read_with_its_urdf(tmp_path, name):
    """``pinframes.read`` of a trajectory bag, given the robot's URDF, puts the tool where
    the samples put it (joint values exact)."""
    (tmp_path / "arm.urdf").write_text(ARM)
    reference = np.datetime64("2024-03-01T08:00:00", "ns")
    times = reference + (TIMES * 1e9).astype("timedelta64[ns]")
    pinframes.write_joint_trajectory((times, np.column_stack([Q1, Q2]), NAMES),
                                     tmp_path / name)
    tree = pinframes.read(tmp_path / name, robot_description=tmp_path / "arm.urdf")
    assert tree.reference_time == reference
    assert np.array_equal(tree.joint_trajectory("a,b").values, Q1)
    assert np.array_equal(tree.joint_trajectory("time_s").values, Q2)
    expected, _ = tool_in_world(Q1, Q2)
    np.testing.assert_allclose(tree.pose("tool", "base", times=times).translation,
                               expected - [0, 0, 0], atol=1e-12)


def test_convert_time_writes_joint_values_that_read_back(scene, tmp_path, run_cli):
    pinframes.write_joint_trajectory((TIMES, np.column_stack([Q1, Q2]), NAMES),
                                     tmp_path / "arm.csv")
    driven = scene.read_text().replace("prefix: arm/}", "prefix: arm/, trajectory: arm.csv}")
    (tmp_path / "moving.yaml").write_text(driven)
    result = run_cli("convert", tmp_path / "moving.yaml", tmp_path / "cell.urdf",
                     "--time", "1.25")
    assert result.returncode == 0, result.stderr
    back = pinframes.read_urdf(tmp_path / "cell.urdf")
    snapshot = back.snapshot(1.25)
    np.testing.assert_allclose(snapshot.joint_values["arm/a,b"], 0.2 + 0.3 * 1.25, atol=1e-15)
    np.testing.assert_allclose(snapshot.joint_values["arm/time_s"], 0.9 - 0.2 * 1.25,
                               atol=1e-15)


def test_bad_trajectories_are_refused_with_the_field(tmp_path):
    with pytest.raises(pinframes.InvalidTimeError, match="increasing"):
        pinframes.write_joint_trajectory(([0.0, 0.0], [[1.0], [2.0]], ["j"]),
                                         tmp_path / "q.csv")
    with pytest.raises(pinframes.InvalidDataError, match="shape"):
        pinframes.write_joint_trajectory(([0.0, 1.0], [[1.0, 2.0]], ["j"]), tmp_path / "q.csv")
    with pytest.raises(pinframes.InvalidDataError, match="twice"):
        pinframes.write_joint_trajectory(([0.0], [[1.0, 2.0]], ["j", "j"]), tmp_path / "q.csv")
    with pytest.raises(pinframes.FileFormatError, match="unknown joint trajectory file type"):
        pinframes.write_joint_trajectory(([0.0], [[1.0]], ["j"]), tmp_path / "q.xlsx")
    assert not list(tmp_path.iterdir())


def test_a_tree_with_joints_not_from_a_urdf_puts_them_on_tf(tmp_path):
    pytest.importorskip("rosbags")
    tree = FrameTree("world")
    tree.attach_joint("wheel", "world", pinframes.Joint("spin", "continuous", (0, 0, 1)),
                      Pose(translation=[1, 0, 0]))
    tree.set_joint_trajectory([0.0, 1.0, 2.0], [[0.0], [2.0], [6.0]], ["spin"])
    pinframes.write(tree, tmp_path / "w.mcap")
    back = pinframes.read(tmp_path / "w.mcap")
    instants = np.array([0, 10**9, 2 * 10**9]).astype("datetime64[ns]")
    np.testing.assert_allclose(back.pose("wheel", times=instants).matrix,
                               tree.pose("wheel", times=[0.0, 1.0, 2.0]).matrix, atol=1e-12)


def _trajectory_joint_names(path):
    """The joint names of the first /joint_trajectory message, decoded by the mcap library."""
    with open(path, "rb") as handle:
        reader = make_reader(handle, decoder_factories=[DecoderFactory()])
        for _, _, _, message in reader.iter_decoded_messages(topics=["/joint_trajectory"]):
            return list(message.joint_names)
    raise AssertionError("no /joint_trajectory message")
