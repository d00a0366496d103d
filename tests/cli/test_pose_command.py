"""``pinframes pose``: numbers against the hand-derived turntable, formats, errors."""

import io
import json

import numpy as np
import pandas
import pytest


def tip_in_world(seconds):
    """Hand-derived: the tip turns on a circle of 0.2 m about (1, 0, 0.5), 90 deg in 10 s."""
    angle = np.pi / 2 * np.clip(seconds, 0.0, 10.0) / 10.0
    return np.column_stack([
        seconds, 1.0 + 0.2 * np.cos(angle), 0.2 * np.sin(angle), np.full_like(angle, 0.5),
        np.zeros_like(angle), np.zeros_like(angle), np.sin(angle / 2), np.cos(angle / 2)])


def read_csv(text, reference_time=None):
    lines = text.splitlines()
    time_column = "time_s" if reference_time is None else f"time_s_after_{reference_time}"
    assert lines[0] == f"{time_column},x_m,y_m,z_m,qx,qy,qz,qw"
    rows = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    frame = pandas.read_csv(io.StringIO(text))
    assert list(frame.columns) == lines[0].split(",")
    np.testing.assert_array_equal(frame.to_numpy(), rows)
    return rows


def test_grid_csv_to_stdout(run_cli, turntable):
    result = run_cli("pose", turntable, "tip", "--relative-to", "world", "--step", "2.5")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_csv(result.stdout),
                               tip_in_world(np.array([0, 2.5, 5, 7.5, 10.0])), atol=1e-12)


def test_times_and_start_stop(run_cli, turntable):
    result = run_cli("pose", turntable, "tip", "-r", "world", "--times", "1", "500ms", "12s")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_csv(result.stdout), tip_in_world(np.array([1, 0.5, 12.0])),
                               atol=1e-12)
    result = run_cli("pose", turntable, "tip", "-r", "world", "--start", "4", "--stop", "5.1",
                     "--step", "0.5")
    np.testing.assert_allclose(read_csv(result.stdout)[:, 0], [4.0, 4.5, 5.0])


def test_default_times_are_the_keyframes_and_inverse_direction(run_cli, turntable):
    result = run_cli("pose", turntable, "world", "-r", "tip")
    assert result.returncode == 0, result.stderr
    rows = read_csv(result.stdout)
    np.testing.assert_allclose(rows[:, 0], [0.0, 10.0])
    # world in tip: the inverse of tip in world, computed with plain numpy
    for row, expected in zip(rows, tip_in_world(np.array([0.0, 10.0])), strict=True):
        angle = 2 * np.arctan2(expected[6], expected[7])
        rotation = np.array([[np.cos(angle), -np.sin(angle), 0],
                             [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
        np.testing.assert_allclose(row[1:4], -rotation.T @ expected[1:4], atol=1e-12)
        np.testing.assert_allclose(row[4:], expected[4:] * [-1, -1, -1, 1], atol=1e-12)


def test_static_path_gives_one_row_without_time(run_cli, turntable):
    result = run_cli("pose", turntable, "tip", "-r", "table")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[1] == "nan,0.2,0.0,0.0,0.0,0.0,0.0,1.0"
    row = read_csv(result.stdout)[0]  # numpy and pandas read the NaN time
    assert np.isnan(row[0])


def test_json_and_npz_files(run_cli, turntable, tmp_path):
    out = tmp_path / "poses.json"
    result = run_cli("pose", turntable, "tip", "-r", "world", "--times", "5", "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    document = json.loads(out.read_text())
    assert document["frame"] == "tip" and document["relative_to"] == "world"
    record = document["poses"][0]
    np.testing.assert_allclose([record[key] for key in ("time_s", "x_m", "y_m", "z_m", "qx",
                                                        "qy", "qz", "qw")],
                               tip_in_world(np.array([5.0]))[0], atol=1e-12)
    npz = tmp_path / "poses.npz"
    assert run_cli("pose", turntable, "tip", "-r", "world", "--step", "1", "-o",
                   npz).returncode == 0
    with np.load(npz) as arrays:
        expected = tip_in_world(np.arange(11.0))
        np.testing.assert_allclose(arrays["time_s"], expected[:, 0])
        np.testing.assert_allclose(arrays["translation"], expected[:, 1:4], atol=1e-12)
        np.testing.assert_allclose(arrays["quaternion"], expected[:, 4:], atol=1e-12)
        assert str(arrays["frame"]) == "tip"


def test_reference_time_and_time_ref(run_cli, tmp_path):
    scene = tmp_path / "timed.yaml"
    scene.write_text("pinframes_scene: 1\nreference_time: 2024-03-01T08:00:00\nframes:\n"
                     "- name: cart\n  parent: world\n  keyframes:\n"
                     "  - {time: 0, xyz: [0, 0, 0]}\n  - {time: 10, xyz: [1, 0, 0]}\n")
    result = run_cli("pose", scene, "cart", "--times", "2024-03-01T08:00:05")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_csv(result.stdout, "2024-03-01T08:00:00")[0, :4],
                               [5.0, 0.5, 0.0, 0.0])
    assert "time_s counts from 2024-03-01T08:00:00" in result.stderr
    result = run_cli("pose", scene, "cart", "--times", "1", "--time-ref",
                     "2024-03-01T08:00:02")
    np.testing.assert_allclose(read_csv(result.stdout, "2024-03-01T08:00:02")[0, :4],
                               [1.0, 0.3, 0.0, 0.0])
    out = tmp_path / "cart.json"
    assert run_cli("pose", scene, "cart", "--times", "1", "-o", out).returncode == 0
    assert json.loads(out.read_text())["reference_time"] == "2024-03-01T08:00:00"


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["missing.yaml", "tip"], "missing.yaml: no such file"),
        ([".", "tip"], ".: is a folder, not a file"),
        (["{scene}", "nope", "-r", "world"],
         "turntable.yaml: frame 'nope': no frame of this name"),
        (["{scene}", "tip", "-r", "nowhere"], "frame 'nowhere'"),
        (["{scene}", "world"], "the root frame has no parent"),
        (["{scene}", "tip", "--times", "abc"], "field '--times': cannot read a time from 'abc'"),
        (["{scene}", "tip", "--step", "0"], "field '--step': must be a positive duration"),
        (["{scene}", "tip", "--step=-1s"], "must be a positive duration"),
        (["{scene}", "tip", "--start", "2"], "--start and --stop need --step"),
        (["{scene}", "tip", "--times", "1", "--step", "1"], "either --times or --start"),
        (["{scene}", "tip", "--start", "5", "--stop", "1", "--step", "1"], "--stop is before"),
        (["{scene}", "tip", "--format", "npz"], "NPZ output is binary"),
        (["{scene}", "tip", "-r", "world", "--step", "1ns"],
         "more than 50000000; take a larger --step"),
        (["{scene}", "tip", "-o", "/nonexistent-folder/p.csv"], "the folder does not exist"),
        (["{scene}", "tip", "--times", "1", "--time-ref", "2024-01-01T00:00:00"],
         "neither the tree nor its frames have a reference time"),
    ],
)
def test_user_errors_exit_1_with_one_line(run_cli, turntable, args, expected):
    result = run_cli("pose", *[arg.format(scene=turntable) for arg in args],
                     cwd=turntable.parent)
    assert result.returncode == 1
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("pinframes: error: ")
    assert expected in lines[0]


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_verbose_adds_traceback_and_usage_errors_exit_2(run_cli, turntable):
    result = run_cli("pose", turntable, "nope", "--verbose")
    assert result.returncode == 1
    assert "Traceback (most recent call last)" in result.stderr
    assert result.stderr.rstrip().splitlines()[-1].startswith("pinframes: error: ")
    result = run_cli("--verbose", "pose", turntable, "nope")
    assert "Traceback (most recent call last)" in result.stderr
    result = run_cli("pose", turntable, "nope")
    assert "Traceback" not in result.stderr
    result = run_cli("pose", turntable)
    assert result.returncode == 2
    assert "usage: pinframes pose" in result.stderr


def test_velocity_columns_carry_units(run_cli, turntable):
    """Hand-derived: 90 deg in 10 s about z, the tip 0.2 m out moves at 0.2 * pi / 20 m/s."""
    result = run_cli("pose", turntable, "tip", "-r", "world", "--times", "2.5", "12",
                     "--velocity")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == ("time_s,x_m,y_m,z_m,qx,qy,qz,qw,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,"
                        "wz_rad_s")
    rows = np.loadtxt(io.StringIO(result.stdout), delimiter=",", skiprows=1, ndmin=2)
    np.testing.assert_allclose(rows[:, :8], tip_in_world(np.array([2.5, 12.0])), atol=1e-12)
    rate = np.pi / 20
    angle = np.pi / 8
    np.testing.assert_allclose(rows[0, 8:], [-0.2 * rate * np.sin(angle),
                                             0.2 * rate * np.cos(angle), 0, 0, 0, rate],
                               atol=1e-12)
    np.testing.assert_allclose(rows[1, 8:], 0.0, atol=1e-15)  # held after 10 s
    result = run_cli("pose", turntable, "tip", "-r", "world", "--times", "2.5", "-f", "json",
                     "--expressed-in", "tip")
    document = json.loads(result.stdout)
    assert document["units"]["v"] == "m/s" and document["units"]["velocity_axes"] == "tip"
    record = document["poses"][0]
    np.testing.assert_allclose([record["vx_m_s"], record["vy_m_s"], record["wz_rad_s"]],
                               [0.0, 0.2 * rate, rate], atol=1e-12)
    result = run_cli("pose", turntable, "tip", "-r", "world", "--expressed-in", "nowhere")
    assert result.returncode == 1 and "nowhere" in result.stderr


def test_velocity_in_npz_files(run_cli, turntable, tmp_path):
    out = tmp_path / "tip.npz"
    result = run_cli("pose", turntable, "tip", "-r", "world", "--times", "2.5", "--velocity",
                     "-o", out)
    assert result.returncode == 0, result.stderr
    with np.load(out) as data:
        rate = np.pi / 20
        np.testing.assert_allclose(data["angular_velocity_rad_s"], [[0, 0, rate]], atol=1e-15)
        np.testing.assert_allclose(np.linalg.norm(data["linear_velocity_m_s"]), 0.2 * rate,
                                   atol=1e-15)
        assert str(data["velocity_axes"]) == "world"
