"""pinframes.write_poses: CSV, JSON and NPZ files that numpy and pandas read back."""

import json

import numpy as np
import pandas
import pytest

from pinframes import FileFormatError, Pose, write_poses

QUARTER_TURN_Z = [0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)]


@pytest.fixture
def pose():
    return Pose([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]], [[0, 0, 0, 1], QUARTER_TURN_Z],
                times=[0.5, 2.0], reference_time="2024-03-01T08:00:00")


def test_csv_loads_with_numpy_and_pandas_and_carries_the_reference_time(pose, tmp_path):
    path = tmp_path / "tool.csv"
    write_poses(pose, path)
    rows = np.loadtxt(path, delimiter=",", skiprows=1)
    expected = [[0.5, 0, 0, 0, 0, 0, 0, 1], [2.0, 1, 2, 3, *QUARTER_TURN_Z]]
    np.testing.assert_allclose(rows, expected, atol=1e-15)
    frame = pandas.read_csv(path)
    assert list(frame.columns) == ["time_s_after_2024-03-01T08:00:00", "x_m", "y_m", "z_m",
                                   "qx", "qy", "qz", "qw"]
    np.testing.assert_allclose(frame.to_numpy(), expected, atol=1e-15)


def test_static_pose_csv_has_a_nan_time(tmp_path):
    path = tmp_path / "static.csv"
    write_poses(Pose([1.0, 2.0, 3.0]), path)
    row = np.loadtxt(path, delimiter=",", skiprows=1)
    assert np.isnan(row[0])
    np.testing.assert_array_equal(row[1:], [1, 2, 3, 0, 0, 0, 1])
    assert np.isnan(pandas.read_csv(path)["time_s"][0])


def test_json_and_npz(pose, tmp_path):
    write_poses(pose, tmp_path / "tool.json", frame="tool", relative_to="work")
    document = json.loads((tmp_path / "tool.json").read_text())
    assert (document["frame"], document["relative_to"]) == ("tool", "work")
    assert document["reference_time"] == "2024-03-01T08:00:00"
    assert document["poses"][1] == pytest.approx(
        {"time_s": 2.0, "x_m": 1.0, "y_m": 2.0, "z_m": 3.0, "qx": 0.0, "qy": 0.0,
         "qz": np.sqrt(0.5), "qw": np.sqrt(0.5)}, abs=1e-15)
    write_poses(pose, tmp_path / "out.bin", "npz")
    with np.load(tmp_path / "out.bin") as arrays:
        np.testing.assert_array_equal(arrays["time_s"], [0.5, 2.0])
        np.testing.assert_allclose(arrays["translation"], [[0, 0, 0], [1, 2, 3]])
        np.testing.assert_allclose(arrays["quaternion"][1], QUARTER_TURN_Z, atol=1e-15)
        assert str(arrays["reference_time"]) == "2024-03-01T08:00:00"


def test_unknown_suffix_without_format_is_refused(pose, tmp_path):
    with pytest.raises(FileFormatError, match="format='csv'"):
        write_poses(pose, tmp_path / "tool.txt")
    assert not (tmp_path / "tool.txt").exists()
