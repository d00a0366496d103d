"""The bundled welding-cell scene and ``pinframes demo``, checked against the seam geometry.

The geometry comes from models/README.md: the torch tip rides the seam, a half circle of
radius 0.10955 m about the pipe axis (the workpiece z axis), at constant speed over 20 s.
"""

import io
from pathlib import Path

import numpy as np
import pytest
import yaml
from scipy.spatial.transform import Rotation

import pinframes
from pinframes import read_scene
from pinframes.cli.demo import bundled_scene

MODELS = Path(__file__).resolve().parents[2] / "models"
RADIUS = 0.10955
DURATION = 20.0


def quaternion_close(actual, expected):
    actual, expected = np.asarray(actual), np.asarray(expected) / np.linalg.norm(expected)
    return min(np.abs(actual - expected).max(), np.abs(actual + expected).max()) < 1e-11


def test_bundled_scene_ships_the_files_of_models():
    """Editable or installed, the package holds models/ as it is in the repository."""
    shipped = bundled_scene().parents[1]
    for name in ("welding_cell/scene.yaml", "welding_cell/robot_motion.csv",
                 "welding_cell/cell_design.yaml", "welding_robot/welding_robot.urdf"):
        assert (shipped / name).read_bytes() == (MODELS / name).read_bytes(), name


def test_bundled_scene_matches_cell_description():
    cell = yaml.safe_load((MODELS / "welding_cell" / "cell_design.yaml").read_text())
    tree = read_scene(MODELS / "welding_cell" / "scene.yaml")
    for frame in cell["frames"]:
        name = frame["name"]
        assert tree.parent(name) == frame["parent"]
        pose = tree.local_pose(name)
        if "curve" in frame:
            check_arc_frame(pose, frame["curve"])
            continue
        np.testing.assert_array_equal(np.atleast_2d(pose.translation),
                                      np.atleast_2d(frame["xyz"]).repeat(len(pose), axis=0))
        if "keyframes" in frame:
            np.testing.assert_array_equal(pose.times.astype(np.int64) / 1e9,
                                          frame["keyframes"]["times_s"])
            for actual, expected in zip(pose.quaternion, frame["keyframes"]["quat_xyzw"],
                                        strict=True):
                assert quaternion_close(actual, expected), name
        else:
            assert quaternion_close(pose.quaternion, frame["quat_xyzw"]), name
    robot = cell["robot"]
    joints = [robot["prefix"] + name for name in robot["joint_names"]]
    assert list(tree.joints) == joints
    motion = np.loadtxt(MODELS / "welding_cell" / robot["joint_trajectory"], delimiter=",",
                        skiprows=1)
    for column, joint in enumerate(joints, start=1):
        track = tree.joint_track(joint)
        np.testing.assert_array_equal(track.values, motion[:, column])
        np.testing.assert_array_equal(track.times, np.round(motion[:, 0] * 1e9))


def check_arc_frame(pose, curve):
    """A frame along an arc of cell_design.yaml: points on the arc at equal steps of time, x
    the tangent (at the two ends the parabola's through the last three points: equal chords,
    4 p1 - 3 p0 - p2), z away from the centre."""
    arc = curve["arc"]
    count, axis = arc["count"], np.array(arc["axis_xyz"])
    centre, start = np.array(arc["centre_xyz"]), np.array(arc["start_xyz"])
    angles = np.linspace(0.0, arc["angle"], count)
    turns = Rotation.from_rotvec(angles[:, None] * axis).as_matrix()
    points = centre + turns @ (start - centre)
    np.testing.assert_array_equal(pose.times.astype(np.int64),
                                  np.round(np.linspace(0.0, curve["duration_s"], count) * 1e9))
    np.testing.assert_allclose(pose.translation, points, atol=1e-14)
    tangents = np.cross(axis, points - centre)
    tangents[0] = 4 * points[1] - 3 * points[0] - points[2]
    tangents[-1] = 3 * points[-1] - 4 * points[-2] + points[-3]
    tangents /= np.linalg.norm(tangents, axis=1)[:, None]
    np.testing.assert_allclose(pose.rotation[:, :, 0], tangents, atol=1e-12)
    outward = (points - centre) / np.linalg.norm(points - centre, axis=1)[:, None]
    outward -= np.sum(outward * tangents, axis=1)[:, None] * tangents
    outward /= np.linalg.norm(outward, axis=1)[:, None]
    np.testing.assert_allclose(pose.rotation[:, :, 2], outward, atol=1e-12)


def test_seam_point_rides_the_seam_at_the_travel_speed():
    """seam_point stays within a few micrometres of the design seam, and the torch_target
    above it has the design torch rotation."""
    cell = yaml.safe_load((MODELS / "welding_cell" / "cell_design.yaml").read_text())
    seam = cell["seam"]
    tree = read_scene(MODELS / "welding_cell" / "scene.yaml")
    times = np.linspace(0.0, DURATION, 20_001)
    pose = tree.pose("seam_point", relative_to=seam["frame"], times=times)
    angle = np.pi * times / DURATION
    on_seam = np.column_stack([RADIUS * np.sin(angle), np.zeros_like(angle),
                               RADIUS * np.cos(angle) - RADIUS])
    gap = np.linalg.norm(pose.translation - on_seam, axis=1)
    assert gap.max() < 4e-8  # the sagitta of a 0.17 mm chord: r (1 - cos(pi / 4000))
    assert seam["radius"] == RADIUS and seam["end_time_s"] == DURATION
    design = tree.pose("torch_target", relative_to="seam_point").rotation
    x, y, z, w = cell["torch"]["tcp_quat_xyzw_in_seam_point"]
    np.testing.assert_allclose(design, Rotation.from_quat([x, y, z, w]).as_matrix(),
                               atol=1e-11)
    wire = design[:, 2]
    np.testing.assert_allclose(wire, [np.sin(np.radians(10)), 0.0, -np.cos(np.radians(10))],
                               atol=1e-11)  # 10 degrees ahead, square across the seam


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_demo_prints_summary_and_writes_csv_and_png(run_cli, tmp_path):
    result = run_cli("demo", "--out", "results", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == "torch_tcp relative to workpiece (scene.yaml)"
    summary = dict(line.split("  ", 1) for line in lines[1:])
    summary = {key.strip(): value.strip() for key, value in summary.items()}
    seam_length = np.pi * RADIUS
    assert summary["samples"] == "2001"
    assert summary["time span"] == "0.000 s .. 20.000 s (20.000 s)"
    assert summary["seam length travelled"] == f"{1000 * seam_length:.1f} mm"  # 344.2 mm
    assert summary["mean travel speed"] == f"{1000 * seam_length / DURATION:.2f} mm/s"
    # the exact speed of the interpolated motion: the joint samples follow the arc, and
    # linear joint interpolation between them speeds the tip up by at most 0.1 %
    fastest = float(summary["max travel speed"].removesuffix(" mm/s"))
    assert 1000 * seam_length / DURATION <= fastest <= 1.001 * 1000 * seam_length / DURATION
    # the welding process along seam_point: the ranges of speed, angles and offset
    def span(name, unit):
        low, high = summary[name].removesuffix(f" {unit}").split(" .. ")
        return float(low), float(high)

    design_speed = 1000 * seam_length / DURATION
    assert design_speed * 0.999 <= span("travel speed", "mm/s")[0]
    assert span("travel speed", "mm/s")[1] <= design_speed * 1.001
    assert span("travel angle", "deg") == (10.0, 10.0)
    assert span("work angle", "deg") == (90.0, 90.0)
    for name in ("offset along", "offset across", "offset normal"):
        assert span(name, "mm") == (0.0, 0.0)
    # the welding positions: up (the world's z) in seam_point's axes, by numpy
    seam_axes = read_scene(MODELS / "welding_cell" / "scene.yaml").pose(
        "seam_point", relative_to="world").rotation
    up = seam_axes[:, 2, :]  # rows of R^T e_z: the world's z in seam axes
    slope = np.degrees(np.arctan2(up[:, 0], np.hypot(up[:, 1], up[:, 2])))
    turned = np.degrees(np.arctan2(up[:, 1], up[:, 2]))
    assert np.abs(slope).max() < 45 and np.abs(turned).max() < 22.5  # flat: PA throughout
    assert span("slope", "deg") == (round(slope.min(), 2), round(slope.max(), 2))
    assert summary["positions"] == "PA 2001 of 2001"

    text = (tmp_path / "results" / "torch_poses.csv").read_text()
    assert text.startswith("time_s,x_m,y_m,z_m,qx,qy,qz,qw\n")
    rows = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)
    np.testing.assert_allclose(rows[:, 0], np.linspace(0.0, DURATION, 2001), atol=1e-12)
    angle = np.pi * rows[:, 0] / DURATION
    seam_point = np.column_stack([RADIUS * np.cos(angle), RADIUS * np.sin(angle),
                                  np.zeros_like(angle)])
    np.testing.assert_allclose(rows[:, 1:4], seam_point, atol=1e-6)
    np.testing.assert_allclose(np.linalg.norm(rows[:, 4:], axis=1), 1.0, atol=1e-12)
    png = (tmp_path / "results" / "torch_path.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # the run as a ROS recording: the torch path read back from it with rosbags' help
    assert summary["ROS recording"].startswith(str(Path("results") / "cell_run.mcap"))
    bag = tmp_path / "results" / "cell_run.mcap"
    assert bag.read_bytes()[:8] == b"\x89MCAP0\r\n"
    recorded = pinframes.read(bag).pose("torch_tcp", "workpiece",
                                        times=(rows[:, 0] * 1e9).astype("datetime64[ns]"))
    np.testing.assert_allclose(recorded.translation, rows[:, 1:4], atol=1e-9)
