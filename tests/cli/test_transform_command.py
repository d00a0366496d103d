"""``pinframes transform``: measured points and vectors into another frame, by hand."""

import io

import numpy as np
import pytest


def read_rows(text, header):
    lines = text.splitlines()
    assert lines[0] == header
    return np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)


def tip_circle(seconds, radius):
    """The turntable turns 90 degrees in 10 s about z at (1, 0, 0.5)."""
    angle = np.pi / 2 * np.clip(seconds, 0.0, 10.0) / 10.0
    return np.column_stack([1.0 + radius * np.cos(angle), radius * np.sin(angle),
                            np.full_like(angle, 0.5)])


def test_one_point_per_time_stamp(run_cli, turntable, tmp_path):
    data = tmp_path / "scan.csv"
    data.write_text("time_s,x_m,y_m,z_m\n0,0.1,0,0\n5,0.1,0,0\n10,0.3,0,0\n")
    result = run_cli("transform", turntable, data, "table", "-r", "world")
    assert result.returncode == 0, result.stderr
    rows = read_rows(result.stdout, "time_s,x_m,y_m,z_m")
    np.testing.assert_allclose(rows[:, 0], [0, 5, 10])
    expected = np.vstack([tip_circle(np.array([0.0, 5.0]), 0.1),
                          tip_circle(np.array([10.0]), 0.3)])
    np.testing.assert_allclose(rows[:, 1:], expected, atol=1e-12)


def test_every_point_at_every_time_and_vectors(run_cli, turntable, tmp_path):
    data = tmp_path / "profile.csv"
    data.write_text("vx_m_s,vy_m_s,vz_m_s\n1,0,0\n0,0,2\n")
    out = tmp_path / "out.csv"
    result = run_cli("transform", turntable, data, "table", "-r", "world", "--vectors",
                     "--times", "0", "10", "-o", out)
    assert result.returncode == 0, result.stderr
    rows = read_rows(out.read_text(), "time_s,point,vx_m_s,vy_m_s,vz_m_s")
    np.testing.assert_allclose(rows, [[0, 0, 1, 0, 0], [0, 1, 0, 0, 2], [10, 0, 0, 1, 0],
                                      [10, 1, 0, 0, 2]], atol=1e-12)


def test_static_path_keeps_the_points(run_cli, turntable, tmp_path):
    data = tmp_path / "points.csv"
    data.write_text("x,y,z\n0.1,0,0\n")
    result = run_cli("transform", turntable, data, "tip", "-r", "table")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_rows(result.stdout, "x,y,z"), [[0.3, 0, 0]], atol=1e-15)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_bad_data_files_name_file_and_field(run_cli, turntable, tmp_path):
    data = tmp_path / "bad.csv"
    for text, message in [("x,y\n1,2\n", "three data columns"),
                          ("x,y,z\n1,abc,2\n", "field 'y'"),
                          ("x,y,z\n1,2\n", "line 2"),
                          ("x,y,z\n1,2,3\n1,nan,2\n", "bad.csv: field 'y': line 3")]:
        data.write_text(text)
        result = run_cli("transform", turntable, data, "table", "-r", "world", "--times", "1")
        assert result.returncode == 1, text
        assert message in result.stderr, result.stderr
    result = run_cli("transform", turntable, tmp_path / "missing.csv", "table", "-r", "world")
    assert result.returncode == 1 and "missing.csv" in result.stderr


def test_points_in_millimetres_stay_millimetres(run_cli, turntable, tmp_path):
    # tip is 0.2 m out on the table: 100 mm along tip's x is 300 mm along the table's x
    data = tmp_path / "points.csv"
    data.write_text("x_mm,y_mm,z_mm\n100,0,0\n0,50,0\n")
    result = run_cli("transform", turntable, data, "tip", "-r", "table")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_rows(result.stdout, "x_mm,y_mm,z_mm"),
                               [[300, 0, 0], [200, 50, 0]], atol=1e-9)
    data.write_text("time_s,x_cm,y_cm,z_cm\n10,10,0,0\n")  # at 10 s the table has turned 90 deg
    result = run_cli("transform", turntable, data, "tip", "-r", "world")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_rows(result.stdout, "time_s,x_cm,y_cm,z_cm"),
                               [[10, 100, 30, 50]], atol=1e-9)
    data.write_text("x_in,y_in,z_in\n10,0,0\n")  # 0.254 m along tip's x, 0.2 m out itself
    result = run_cli("transform", turntable, data, "tip", "-r", "table")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_rows(result.stdout, "x_in,y_in,z_in"),
                               [[(0.254 + 0.2) / 0.0254, 0, 0]], atol=1e-9)


def test_vectors_keep_any_unit_they_share(run_cli, turntable, tmp_path):
    data = tmp_path / "speeds.csv"
    data.write_text("vx_mm_s,vy_mm_s,vz_mm_s\n3,0,0\n")
    result = run_cli("transform", turntable, data, "table", "-r", "world", "--vectors",
                     "--times", "10")
    assert result.returncode == 0, result.stderr
    np.testing.assert_allclose(read_rows(result.stdout, "time_s,point,vx_mm_s,vy_mm_s,vz_mm_s"),
                               [[10, 0, 0, 3, 0]], atol=1e-12)


@pytest.mark.parametrize(("header", "vectors", "message"), [
    ("x_mm,y_m,z_mm", False, "different units"),
    ("x,y_mm,z_mm", True, "different units"),
    ("x_yd,y_yd,z_yd", False, "'yd' is not a length unit"),
    ("vx_m_s,vy_m_s,vz_m_s", False, "--vectors"),
    ("x (mm),y (mm),z (mm)", False, "no unit pinframes knows"),
])
def test_unknown_or_mixed_units_are_refused(run_cli, turntable, tmp_path, header, vectors,
                                            message):
    data = tmp_path / "points.csv"
    data.write_text(f"{header}\n1,2,3\n")
    result = run_cli("transform", turntable, data, "tip", "-r", "table",
                     *(["--vectors"] if vectors else []))
    assert result.returncode == 1, result.stdout
    assert message in result.stderr and "points.csv" in result.stderr, result.stderr
