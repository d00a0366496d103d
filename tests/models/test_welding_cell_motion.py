"""The bundled welding cell and its recorded robot motion, checked independently.

The torch TCP is computed with Pinocchio directly from the CSV samples and compared with the
seam, which is rebuilt here in plain numpy from ``cell_design.yaml`` (own quaternion, SLERP and
axis-angle code), so the check does not reuse the generator's code. Nothing here uses
pinframes.
"""

from __future__ import annotations

import csv
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import yaml
import yourdfpy

REPO = Path(__file__).resolve().parents[2]
CELL_DIR = REPO / "models" / "welding_cell"
URDF_PATH = REPO / "models" / "welding_robot" / "welding_robot.urdf"
HEADER = ["time_s", *(f"joint_{i}" for i in range(1, 7))]

# Stated tolerances of the recorded motion (the CSV keeps 9 significant digits).
TCP_POSITION_TOLERANCE_M = 1e-6
TCP_ANGLE_TOLERANCE_RAD = 1e-6


def _matrix_from_quat_xyzw(quat) -> np.ndarray:
    x, y, z, w = np.asarray(quat, dtype=float) / np.linalg.norm(quat)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def _slerp(q0: np.ndarray, q1: np.ndarray, u: float) -> np.ndarray:
    """Shortest-arc spherical interpolation of unit quaternions (x, y, z, w)."""
    dot = float(np.dot(q0, q1))
    if dot < 0:
        q1, dot = -q1, -dot
    angle = np.arccos(min(dot, 1.0))
    if angle < 1e-12:
        return q0
    return (np.sin((1 - u) * angle) * q0 + np.sin(u * angle) * q1) / np.sin(angle)


def _axis_angle(axis, angle: float) -> np.ndarray:
    """Rodrigues' rotation matrix about a unit ``axis`` by ``angle`` radians."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    skew = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * skew + (1 - np.cos(angle)) * skew @ skew


def _homogeneous(rotation, translation) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3] = rotation
    out[:3, 3] = translation
    return out


def _static(entry: dict) -> np.ndarray:
    return _homogeneous(_matrix_from_quat_xyzw(entry["quat_xyzw"]), entry["xyz"])


def _rotation_angle(rotation: np.ndarray) -> float:
    """Angle (rad) of a rotation matrix, accurate for tiny angles too."""
    skew = rotation - rotation.T
    sine = np.linalg.norm([skew[2, 1], skew[0, 2], skew[1, 0]]) / 2
    return float(np.arctan2(sine, (np.trace(rotation) - 1) / 2))


@pytest.fixture(scope="module")
def cell() -> dict:
    return yaml.safe_load((CELL_DIR / "cell_design.yaml").read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def frames(cell) -> dict:
    return {entry["name"]: entry for entry in cell["frames"]}


@pytest.fixture(scope="module")
def motion() -> np.ndarray:
    return np.loadtxt(CELL_DIR / "robot_motion.csv", delimiter=",", skiprows=1)


@pytest.fixture(scope="module")
def urdf() -> yourdfpy.URDF:
    return yourdfpy.URDF.load(str(URDF_PATH), load_meshes=False)


def _positioner_in_base(keyframes: dict, time_s: float) -> np.ndarray:
    times = np.asarray(keyframes["times_s"])
    quats = np.asarray(keyframes["quat_xyzw"], dtype=float)
    index = int(np.clip(np.searchsorted(times, time_s, side="right") - 1, 0, len(times) - 2))
    u = float(np.clip((time_s - times[index]) / (times[index + 1] - times[index]), 0.0, 1.0))
    return _matrix_from_quat_xyzw(_slerp(quats[index], quats[index + 1], u))


def _seam_points_in_world(cell, frames, times_s, *, hold_positioner=False) -> np.ndarray:
    """(T, 4, 4) pose of the seam point under the torch, in the world, per sample."""
    seam = cell["seam"]
    keyframes = frames["positioner"]["keyframes"]
    positioner_base_in_world = _static(frames["positioner_base"])
    seam_in_positioner = _static(frames["workpiece"]) @ _static(frames["weld_seam"])
    out = []
    for time_s in times_s:
        fraction = (time_s - seam["start_time_s"]) / (seam["end_time_s"] - seam["start_time_s"])
        angle = seam["start_angle"] + fraction * (seam["end_angle"] - seam["start_angle"])
        turn = _axis_angle(seam["axis_xyz"], angle)
        point_in_seam = _homogeneous(
            turn, np.asarray(seam["centre_xyz"]) + turn @ [0.0, 0.0, seam["radius"]]
        )
        positioner_time = keyframes["times_s"][0] if hold_positioner else time_s
        positioner = _homogeneous(_positioner_in_base(keyframes, positioner_time), np.zeros(3))
        out.append(positioner_base_in_world @ positioner @ seam_in_positioner @ point_in_seam)
    return np.array(out)


def _tcp_in_world(frames, joint_samples) -> np.ndarray:
    """(T, 4, 4) pose of torch_tcp in the world from Pinocchio forward kinematics."""
    model = pin.buildModelFromUrdf(str(URDF_PATH))
    data = model.createData()
    flange_id = model.getFrameId("flange")
    robot_base_in_world = _static(frames["robot_base"])
    tcp_in_flange = _static(frames["torch_tcp"])
    out = []
    for q in joint_samples:
        pin.framesForwardKinematics(model, data, q)
        out.append(robot_base_in_world @ data.oMf[flange_id].homogeneous @ tcp_in_flange)
    return np.array(out)


def test_csv_has_the_documented_header_and_time_axis(motion):
    with (CELL_DIR / "robot_motion.csv").open(encoding="utf-8", newline="") as handle:
        assert next(csv.reader(handle)) == HEADER
    assert motion.shape == (2001, 7)
    np.testing.assert_allclose(motion[:, 0], np.arange(2001) / 100.0, rtol=0, atol=1e-12)


def test_motion_stays_within_the_urdf_position_and_velocity_limits(motion, urdf):
    limits = {joint.name: joint.limit for joint in urdf.robot.joints if joint.type == "revolute"}
    dt = np.diff(motion[:, 0])
    for column, name in enumerate(HEADER[1:], start=1):
        values = motion[:, column]
        assert limits[name].lower <= values.min(), name
        assert values.max() <= limits[name].upper, name
        speed = np.abs(np.diff(values)) / dt
        assert speed.max() < limits[name].velocity, name
    assert np.ptp(motion[:, 1:], axis=0).min() > 0.1  # every joint takes part


def test_cell_frames_form_a_tree_with_unit_quaternions(cell, frames, urdf):
    prefix = cell["robot"]["prefix"]
    known = {cell["root"], *(prefix + link.name for link in urdf.robot.links)}
    for entry in cell["frames"]:
        assert entry["parent"] in known, entry["name"]
        assert entry["name"] not in known, entry["name"]
        known.add(entry["name"])
        if "curve" in entry:
            continue  # its pose comes from the curve (test_seam_point_follows_the_seam)
        assert len(entry["xyz"]) == 3
        quats = entry["keyframes"]["quat_xyzw"] if "keyframes" in entry else [entry["quat_xyzw"]]
        np.testing.assert_allclose(np.linalg.norm(quats, axis=1), 1.0, atol=1e-11)
    for name in ("robot_base", "positioner_base", "positioner", "workpiece", "weld_seam",
                 "seam_point", "torch_target"):
        assert name in frames
    assert frames["torch_tcp"]["parent"] == prefix + "flange"
    assert cell["robot"]["mount_frame"] == "robot_base"
    assert (CELL_DIR / cell["robot"]["urdf"]).resolve() == URDF_PATH
    assert cell["robot"]["joint_trajectory"] == "robot_motion.csv"


def test_seam_point_follows_the_seam_and_torch_target_is_the_design_torch(cell, frames):
    """seam_point's arc is the seam of the design, swept over its times; torch_target sits on
    it with the design torch rotation."""
    seam, seam_point = cell["seam"], frames["seam_point"]
    assert seam_point["parent"] == seam["frame"]
    arc, duration = seam_point["curve"]["arc"], seam_point["curve"]["duration_s"]
    assert duration == seam["end_time_s"] - seam["start_time_s"] and seam["start_time_s"] == 0
    assert arc["centre_xyz"] == seam["centre_xyz"] and arc["axis_xyz"] == seam["axis_xyz"]
    assert arc["angle"] == seam["end_angle"] - seam["start_angle"]
    start = np.asarray(seam["centre_xyz"]) + _axis_angle(seam["axis_xyz"], seam["start_angle"]) @ [
        0.0, 0.0, seam["radius"]]
    np.testing.assert_allclose(arc["start_xyz"], start, atol=1e-15)
    # a chord of the polyline passes r (1 - cos(step / 2)) inside the circle: under a few um
    step = arc["angle"] / (arc["count"] - 1)
    assert seam["radius"] * (1 - np.cos(step / 2)) < 2.5e-6
    target = frames["torch_target"]
    assert target["parent"] == "seam_point" and target["xyz"] == [0.0, 0.0, 0.0]
    assert target["quat_xyzw"] == cell["torch"]["tcp_quat_xyzw_in_seam_point"]


def test_positioner_keyframes_turn_about_one_horizontal_axis(frames):
    keyframes = frames["positioner"]["keyframes"]
    times = np.asarray(keyframes["times_s"])
    quats = np.asarray(keyframes["quat_xyzw"])
    np.testing.assert_allclose(times, np.arange(41) * 0.5, rtol=0, atol=0)
    assert np.all(np.sum(quats[1:] * quats[:-1], axis=1) > np.cos(np.radians(45) / 2))
    np.testing.assert_array_equal(quats[:, :2], 0.0)  # about the positioner_base z axis
    axis_in_world = _matrix_from_quat_xyzw(frames["positioner_base"]["quat_xyzw"])[:, 2]
    assert abs(axis_in_world[2]) < 1e-12  # horizontal
    turned = _rotation_angle(_matrix_from_quat_xyzw(quats[0]).T @ _matrix_from_quat_xyzw(quats[-1]))
    assert turned > np.radians(90)


def test_torch_is_about_0_4_m_long_with_a_22_to_45_degree_neck(frames):
    tcp_in_flange = _static(frames["torch_tcp"])
    assert 0.35 <= np.linalg.norm(tcp_in_flange[:3, 3]) <= 0.45
    neck = np.degrees(np.arccos(tcp_in_flange[2, 2]))  # flange z against TCP z
    assert 22.0 - 1e-9 <= neck <= 45.0


def test_tcp_follows_the_seam_as_the_positioner_turns(cell, frames, motion):
    times = motion[:, 0]
    tcp = _tcp_in_world(frames, motion[:, 1:])
    seam_points = _seam_points_in_world(cell, frames, times)

    position_error = np.linalg.norm(tcp[:, :3, 3] - seam_points[:, :3, 3], axis=1)
    assert position_error.max() < TCP_POSITION_TOLERANCE_M

    wanted = _matrix_from_quat_xyzw(cell["torch"]["tcp_quat_xyzw_in_seam_point"])
    tcp_in_point = np.einsum("tji,tjk->tik", seam_points[:, :3, :3], tcp[:, :3, :3])
    angle_error = [_rotation_angle(wanted.T @ rotation) for rotation in tcp_in_point]
    assert max(angle_error) < TCP_ANGLE_TOLERANCE_RAD

    # torch angles from the seam point axes: x travel, y lateral (pipe axis), z normal
    wire = tcp_in_point[:, :, 2]
    push = np.arccos(np.clip(-wire[:, 2], -1, 1))
    np.testing.assert_allclose(push, cell["torch"]["push_angle"], atol=TCP_ANGLE_TOLERANCE_RAD)
    assert np.all(wire[:, 0] > 0)  # the wire points forward: pushing
    assert np.abs(wire[:, 1]).max() < TCP_ANGLE_TOLERANCE_RAD  # work angle 90 degrees

    # the same TCP misses the seam by far if the positioner were ignored
    held = _seam_points_in_world(cell, frames, times, hold_positioner=True)
    assert np.linalg.norm(tcp[:, :3, 3] - held[:, :3, 3], axis=1).max() > 0.1


def test_travel_speed_along_the_seam_matches_the_cell(cell, frames, motion):
    times = motion[:, 0]
    tcp = _tcp_in_world(frames, motion[:, 1:])
    seam_in_world = np.array(
        [
            _homogeneous(_positioner_in_base(frames["positioner"]["keyframes"], t), np.zeros(3))
            for t in times
        ]
    )
    base = _static(frames["positioner_base"])
    seam_frame = _static(frames["workpiece"]) @ _static(frames["weld_seam"])
    tcp_in_seam = np.linalg.inv(base @ seam_in_world @ seam_frame) @ tcp
    steps = np.linalg.norm(np.diff(tcp_in_seam[:, :3, 3], axis=0), axis=1)
    travelled = steps.sum()
    seam = cell["seam"]
    assert travelled == pytest.approx(seam["length"], rel=1e-4)
    assert seam["length"] == pytest.approx(np.pi * seam["radius"], rel=1e-12)
    speed = steps / np.diff(times)
    np.testing.assert_allclose(speed, seam["travel_speed_m_per_s"], rtol=1e-3)


def test_generator_reproduces_the_files(tmp_path, cell, motion):
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
    subprocess.run(
        [sys.executable, str(CELL_DIR / "make_motion.py"), "--out", str(tmp_path)],
        check=True,
        env=env,
        capture_output=True,
        timeout=120,
    )
    assert yaml.safe_load((tmp_path / "cell_design.yaml").read_text(encoding="utf-8")) == cell
    regenerated = np.loadtxt(tmp_path / "robot_motion.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(regenerated, motion, rtol=0, atol=1e-8)
