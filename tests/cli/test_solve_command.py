"""``pinframes solve``: joint trajectory CSVs checked with Pinocchio on the URDF, and the
command's shell habits (standard output, summary, exit status, errors)."""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from pinframes import read_joint_trajectory

ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
HOME = np.array([0.2, 0.4, -0.6, 0.1, 0.9, 0.3])  # rad
TURN_DEG = 20.0  # the table turns this much about its vertical axis in 2 s


def flange_poses(configurations: np.ndarray) -> list[pin.SE3]:
    model = pin.buildModelFromUrdf(str(ROBOT))
    data = model.createData()
    frame = model.getFrameId("flange")
    poses = []
    for q in configurations:
        pin.framesForwardKinematics(model, data, q)
        poses.append(data.oMf[frame].copy())
    return poses


@pytest.fixture
def cell(tmp_path: Path) -> tuple[Path, pin.SE3, pin.SE3]:
    """The welding robot at the root, a table turning 20 degrees in 2 s in front of it, and
    ``seam`` on the table where the flange is at the robot's home configuration."""
    tool = flange_poses(HOME[None])[0]
    centre = tool.translation + np.array([0.15, 0.0, 0.0])
    seam_in_table = pin.SE3(tool.rotation, tool.translation - centre)
    quaternion = pin.Quaternion(seam_in_table.rotation).coeffs()  # x y z w
    half = np.radians(TURN_DEG) / 2
    path = tmp_path / "cell.yaml"
    path.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        name: cell
        frames:
          - name: table
            parent: world
            xyz: {centre.tolist()}
            keyframes:
              - {{time: 0, quaternion: [0, 0, 0, 1]}}
              - {{time: 2, quaternion: [0, 0, {float(np.sin(half))!r}, {float(np.cos(half))!r}]}}
          - name: seam
            parent: table
            xyz: {seam_in_table.translation.tolist()}
            quaternion: {quaternion.tolist()}
        robots:
          - {{name: welder, urdf: {ROBOT}, parent: world, prefix: robot/}}
        """))
    return path, pin.SE3(np.eye(3), centre), seam_in_table


def seam_targets(table: pin.SE3, seam_in_table: pin.SE3, seconds: np.ndarray) -> list[pin.SE3]:
    """The seam in the world by hand: the table turned linearly in angle (SLERP about one
    axis) up to 2 s."""
    angles = np.radians(TURN_DEG) * np.clip(seconds, 0.0, 2.0) / 2.0
    return [table * pin.SE3(pin.utils.rotate("z", angle), np.zeros(3)) * seam_in_table
            for angle in angles]


def test_solve_writes_a_trajectory_the_robot_follows_onto_the_seam(cell, run_cli, tmp_path):
    scene, table, seam_in_table = cell
    out = tmp_path / "joints.csv"
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam",
                     "--start", "0", "--stop", "2", "--step", "0.02", "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    assert "101 samples, 101 reached" in result.stderr
    assert "closest to a joint limit" in result.stderr
    times, positions, names = read_joint_trajectory(out)
    assert names == [f"joint_{index}" for index in range(1, 7)]  # the URDF's, for a scene
    np.testing.assert_allclose(times, np.linspace(0.0, 2.0, 101), atol=1e-12)
    targets = seam_targets(table, seam_in_table, times)
    for placement, target in zip(flange_poses(positions), targets, strict=True):
        offset = target.actInv(placement)
        assert np.linalg.norm(offset.translation) <= 1e-6
        assert np.linalg.norm(pin.log3(offset.rotation)) <= 1e-6
    # the file drives the scene's robot: the flange then sits on the seam
    driven = scene.with_name("driven.yaml")
    driven.write_text(scene.read_text().replace("prefix: robot/}",
                                                f"prefix: robot/, trajectory: {out}}}"))
    pose = run_cli("pose", driven, "robot/flange", "-r", "seam", "--times", "0.5", "1.5")
    assert pose.returncode == 0, pose.stderr
    rows = np.loadtxt(pose.stdout.splitlines()[1:], delimiter=",")
    np.testing.assert_allclose(rows[:, 1:4], 0.0, atol=1e-6)


def test_solve_writes_to_standard_output_with_a_free_axis(cell, run_cli):
    scene, table, seam_in_table = cell
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam",
                     "--free-axis", "x", "--times", "0", "1", "2")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "time_s,joint_1,joint_2,joint_3,joint_4,joint_5,joint_6"
    rows = np.array([[float(cell) for cell in line.split(",")] for line in lines[1:]])
    targets = seam_targets(table, seam_in_table, rows[:, 0])
    for placement, target in zip(flange_poses(rows[:, 1:]), targets, strict=True):
        assert np.linalg.norm(placement.translation - target.translation) <= 1e-6
        axis, wanted = placement.rotation[:, 0], target.rotation[:, 0]
        assert np.arctan2(np.linalg.norm(np.cross(axis, wanted)), axis @ wanted) <= 1e-6


def test_solve_out_of_reach(cell, run_cli, tmp_path):
    scene, _, _ = cell
    far = scene.with_name("far.yaml")
    far.write_text(scene.read_text() + "tools:\n  - {name: far, parent: seam, xyz: [0, 0, 5]}\n")
    kept = run_cli("solve", far, "--frame", "robot/flange", "--target", "far", "--times", "0",
                   "1")
    assert kept.returncode == 0, kept.stderr
    assert "2 samples, 0 reached" in kept.stderr
    strict = run_cli("solve", far, "--frame", "robot/flange", "--target", "far", "--times", "0",
                     "1", "--strict", "-o", tmp_path / "never.csv")
    assert strict.returncode == 1
    assert "pinframes: error:" in strict.stderr and "not reached at 0 s" in strict.stderr
    assert not (tmp_path / "never.csv").exists()


@pytest.mark.parametrize(("arguments", "words"), [
    (["--frame", "robot/flang", "--target", "seam"], "robot/flang"),
    (["--frame", "robot/flange", "--target", "seam", "--joints", "robot/joint_9"],
     "robot/joint_9"),
    (["--frame", "robot/flange", "--target", "seam", "--position-tolerance", "-1"],
     "position_tolerance"),
])
def test_solve_errors_name_what_is_wrong(cell, run_cli, arguments, words):
    scene, _, _ = cell
    result = run_cli("solve", scene, *arguments)
    assert result.returncode == 1
    assert result.stderr.startswith("pinframes: error:") and words in result.stderr


BUNDLED = Path(__file__).resolve().parents[2] / "models" / "welding_cell"


def test_solve_reproduces_the_bundled_robot_motion(run_cli, tmp_path):
    """make_motion.py writes robot_motion.csv with solve_joints (from its seed, to 1e-9);
    the command with its defaults starts from the file's first sample and stays within
    the default tolerances of it."""
    out = tmp_path / "robot_motion.csv"
    result = run_cli("solve", BUNDLED / "scene.yaml", "--frame", "torch_tcp", "--target",
                     "torch_target", "-o", out)
    assert result.returncode == 0, result.stderr
    assert "2001 samples, 2001 reached" in result.stderr
    times, positions, names = read_joint_trajectory(out)
    recorded_times, recorded, recorded_names = read_joint_trajectory(BUNDLED / "robot_motion.csv")
    assert names == recorded_names
    np.testing.assert_allclose(times, recorded_times, atol=1e-12)
    # two solutions within 1e-6 m and 1e-6 rad of one target differ by a few micro-radians
    # at the joints (the torch is about 0.5 m from the wrist)
    np.testing.assert_allclose(positions, recorded, atol=5e-6)


@pytest.mark.parametrize("add", [False, True], ids=["--joints", "--add-joints"])
def test_solve_keeps_a_seam_flat_with_a_positioner(run_cli, tmp_path, add):
    """--flat: a tilt-turn positioner turns a seam whose face turns a quarter turn about
    the faceplate's z so that the face looks up; the CSV checked with Pinocchio on the
    positioner's URDF. The positioner's joints named with the arm's (--joints), or added to
    the default set, the arm's (--add-joints)."""
    from ik_paths import pipe_scene, serial_urdf
    positioner = tmp_path / "positioner.urdf"
    positioner.write_text(serial_urdf("positioner", [
        ("tilt_x", "revolute", "cradle", "0 0 0.3", -2.0, 2.0),
        ("turn", "revolute", "faceplate", "0 0 0", -6.0, 6.0)]))
    half = np.pi / 8  # half the quarter turn
    scene = tmp_path / "pipe.yaml"
    scene.write_text(pipe_scene(positioner))
    arm = [f"ur/{name}" for name in ("shoulder_pan_joint", "shoulder_lift_joint",
                                     "elbow_joint", "wrist_1_joint", "wrist_2_joint",
                                     "wrist_3_joint")]
    joints = ["--add-joints"] if add else ["--joints", *arm]
    result = run_cli("solve", scene, "--frame", "ur/tool0", "--target", "torch_target",
                     "--free-axis", "z", *joints, "pos/tilt_x", "pos/turn",
                     "--flat", "seam", "--up", "0", "0", "2", "--times", "0", "0.5", "1")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[0].split(",")[1:] == [*arm, "pos/tilt_x", "pos/turn"]
    assert "3 samples, 3 reached" in result.stderr
    rows = np.array([[float(cell) for cell in line.split(",")]
                     for line in result.stdout.splitlines()[1:]])
    model = pin.buildModelFromUrdf(str(positioner))
    data = model.createData()
    plate = model.getFrameId("faceplate")
    for time, tilt, turn in rows[:, [0, 7, 8]]:
        pin.framesForwardKinematics(model, data, np.array([tilt, turn]))
        start = pin.Quaternion(0.5, 0.5, 0.5, 0.5).matrix()  # w x y z
        later = pin.Quaternion(np.cos(half), 0.0, np.sin(half), 0.0).matrix()
        seam = pin.Quaternion(start).slerp(time, pin.Quaternion(later)).matrix()
        face = data.oMf[plate].rotation @ seam[:, 2]
        assert np.degrees(np.arccos(min(1.0, face[2]))) <= 2.0


def test_solve_with_process_windows_keeps_the_tilt_within_them(cell, run_cli):
    """--tilt in radians: the flange's z within 0.1 rad of the seam's about its x and y,
    by Pinocchio on the URDF; the summary names the largest tilt."""
    scene, table, seam_in_table = cell
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam",
                     "--free-axis", "z", "--tilt", "0.1", "0.1", "--times", "0", "1", "2")
    assert result.returncode == 0, result.stderr
    assert "3 samples, 3 reached" in result.stderr
    assert "largest tilt" in result.stderr
    rows = np.array([[float(cell) for cell in line.split(",")]
                     for line in result.stdout.splitlines()[1:]])
    targets = seam_targets(table, seam_in_table, rows[:, 0])
    for placement, target in zip(flange_poses(rows[:, 1:]), targets, strict=True):
        offset = target.actInv(placement)
        assert np.linalg.norm(offset.translation) <= 1e-6
        x, y, z = offset.rotation[:, 2]
        assert abs(np.arctan2(-y, z)) <= 0.1 + 1e-6 and abs(np.arcsin(x)) <= 0.1 + 1e-6


def joint_linear(rows: np.ndarray, between: int) -> np.ndarray:
    """The CSV's rows (time, joints) interpolated linearly, ``between`` points inside each
    interval besides its ends: (times, joints) rows."""
    fine = np.unique(np.concatenate([np.linspace(start, end, between + 2)
                                     for start, end in zip(rows[:-1, 0], rows[1:, 0],
                                                           strict=True)]))
    return np.column_stack([fine] + [np.interp(fine, rows[:, 0], column)
                                     for column in rows[:, 1:].T])


@pytest.mark.parametrize(("tolerance", "metres", "radians"), [
    ((), 1e-4, np.radians(0.1)), (("--path-tolerance", "1e-3", "0.01"), 1e-3, 0.01),
    (("--path-tolerance", "2e-5", "2e-4"), 2e-5, 2e-4)])
def test_solve_path_tolerance_bounds_the_tool_between_samples(cell, run_cli, tmp_path,
                                                              tolerance, metres, radians):
    """Without times, the seam's two keyframes become as many samples as keep the
    joint-linear flange within --path-tolerance of the seam (metres, radians; default 0.1 mm
    and 0.1 degree): checked by Pinocchio 20 times per interval against the table turned by
    hand; the looser tolerance needs fewer samples, the tighter more."""
    scene, table, seam_in_table = cell
    out = tmp_path / "joints.csv"
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam", *tolerance,
                     "-o", out)
    assert result.returncode == 0, result.stderr
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    assert f"{rows.shape[0]} samples, {rows.shape[0]} reached" in result.stderr
    fine = joint_linear(rows, 20)
    targets = seam_targets(table, seam_in_table, fine[:, 0])
    position, angle = [], []
    for placement, target in zip(flange_poses(fine[:, 1:]), targets, strict=True):
        offset = target.actInv(placement)
        position.append(np.linalg.norm(offset.translation))
        angle.append(np.linalg.norm(pin.log3(offset.rotation)))
    assert max(position) <= 1.01 * metres and max(angle) <= 1.01 * radians
    counts = {1e-3: (2, 9), 1e-4: (9, 9), 2e-5: (10, 10 ** 4)}[metres]  # default: 9 samples
    assert counts[0] <= rows.shape[0] <= counts[1] and (rows.shape[0] == 9) == (metres == 1e-4)


def test_solve_jump_threshold_and_strict_name_the_first_jump(cell, run_cli):
    """--jump-threshold 0.5 on three samples a second apart: both steps pass half the
    median step and 0.1 rad, as numpy finds on the CSV; the summary counts them, --strict
    fails naming the first time and its joint; with the default (10 times) none."""
    scene, _, _ = cell
    times = ("--times", "0", "1", "2")
    loose = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam", *times)
    assert loose.returncode == 0, loose.stderr
    assert "jumps" not in loose.stderr
    result = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam", *times,
                     "--jump-threshold", "0.5")
    assert result.returncode == 0, result.stderr
    rows = np.array([[float(cell) for cell in line.split(",")]
                     for line in result.stdout.splitlines()[1:]])
    steps = np.abs(np.diff(rows[:, 1:], axis=0))
    largest = steps.max(axis=1)
    jumps = np.flatnonzero(largest > max(0.5 * np.median(largest), 0.1)) + 1
    assert jumps.tolist() == [1, 2]
    assert "2 jumps (the first at 1 s)" in result.stderr
    strict = run_cli("solve", scene, "--frame", "robot/flange", "--target", "seam", *times,
                     "--jump-threshold", "0.5", "--strict")
    assert strict.returncode == 1
    joint = f"robot/joint_{int(np.argmax(steps[0])) + 1}"
    assert "at 1 s" in strict.stderr and f"joint {joint!r}" in strict.stderr


def test_solve_flat_tolerance_sets_how_flat(run_cli, tmp_path):
    """--flat-tolerance in radians: at 1e-9 the seam's face is within 1e-8 rad of up at every
    sample (Pinocchio on the positioner's URDF), where the default (0.5 degree) leaves it
    further at one of them; a negative one is an error naming it."""
    from ik_paths import TILT_TURN, pipe_scene
    positioner = tmp_path / "positioner.urdf"
    positioner.write_text(TILT_TURN)
    scene = tmp_path / "pipe.yaml"
    scene.write_text(pipe_scene(positioner))
    model = pin.buildModelFromUrdf(str(positioner))
    data = model.createData()
    plate = model.getFrameId("faceplate")
    half = np.pi / 8  # the seam's face turns by twice this about the faceplate's y in 1 s

    def largest_angle_from_up(*flat_tolerance: str) -> float:
        result = run_cli("solve", scene, "--frame", "ur/tool0", "--target", "torch_target",
                         "--free-axis", "z", "--add-joints", "pos/tilt_x", "pos/turn",
                         "--flat", "seam", "--times", "0", "0.5", "1", *flat_tolerance)
        assert result.returncode == 0, result.stderr
        assert "3 samples, 3 reached" in result.stderr
        rows = np.array([[float(cell) for cell in line.split(",")]
                         for line in result.stdout.splitlines()[1:]])
        angles = []
        for time, tilt, turn in rows[:, [0, 7, 8]]:
            pin.framesForwardKinematics(model, data, np.array([tilt, turn]))
            start = pin.Quaternion(0.5, 0.5, 0.5, 0.5)  # w x y z
            seam = start.slerp(time, pin.Quaternion(np.cos(half), 0.0, np.sin(half), 0.0))
            face = data.oMf[plate].rotation @ seam.matrix()[:, 2]
            angles.append(np.arctan2(np.linalg.norm(face[:2]), face[2]))
        return max(angles)

    assert largest_angle_from_up() > 1e-8
    assert largest_angle_from_up("--flat-tolerance", "1e-9") <= 1e-8
    wrong = run_cli("solve", scene, "--frame", "ur/tool0", "--target", "torch_target",
                    "--flat", "seam", "--flat-tolerance", "-1")
    assert wrong.returncode == 1 and "flat_tolerance" in wrong.stderr
