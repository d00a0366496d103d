"""``pinframes transform``: measured points and vectors into another frame, by hand."""

import io

import numpy as np


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
