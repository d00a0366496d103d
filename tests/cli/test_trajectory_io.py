"""Joint trajectories from CSV and NPZ files, and the errors for malformed files."""

import numpy as np
import pytest

from pinframes import read_joint_trajectory
from pinframes.errors import FileFormatError, ReadError


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_csv_with_time_s_column(tmp_path):
    path = write(tmp_path, "m.csv", "time_s,j1,j2\n0,0.5,-1\n\n# a comment\n0.25,1e-3,2\n")
    times, positions, names = read_joint_trajectory(path)
    assert names == ["j1", "j2"]
    np.testing.assert_array_equal(times, [0.0, 0.25])
    np.testing.assert_array_equal(positions, [[0.5, -1.0], [0.001, 2.0]])


def test_csv_time_column_with_durations_and_timestamps(tmp_path):
    durations = write(tmp_path, "d.csv", "time,j\n0s,1\n500ms,2\nP0DT0H0M1.5S,3\n")
    times, _, _ = read_joint_trajectory(durations)
    np.testing.assert_array_equal(times.astype(np.int64), [0, 500_000_000, 1_500_000_000])
    stamps = write(tmp_path, "s.csv",
                   "time,j\n2024-03-01T08:00:00,1\n2024-03-01T08:00:02.5,2\n")
    times, _, _ = read_joint_trajectory(stamps)
    assert times.dtype == np.dtype("datetime64[ns]")
    assert times[1] - times[0] == np.timedelta64(2_500_000_000, "ns")
    assert times[0] == np.datetime64("2024-03-01T08:00:00")


def test_npz(tmp_path):
    path = tmp_path / "m.npz"
    np.savez(path, times=np.array([0.0, 1.0, 2.0]), positions=np.arange(6.0).reshape(3, 2),
             joint_names=np.array(["a", "b"]))
    times, positions, names = read_joint_trajectory(path)
    assert names == ["a", "b"]
    np.testing.assert_array_equal(times, [0.0, 1.0, 2.0])
    np.testing.assert_array_equal(positions, [[0, 1], [2, 3], [4, 5]])


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("", "empty file"),
        ("t,j1\n0,1\n", "first column must be the time"),
        ("time_s\n0\n", "no joint columns"),
        ("time_s,j1,j1\n0,1,2\n", "joint named twice"),
        ("time_s,j1\n", "no samples"),
        ("time_s,j1\n0,1\n1,2,3\n", "field 'line 3': 3 values, but the header has 2 columns"),
        ("time_s,j1\n0,1\n1,abc\n", "joint 'j1': field 'line 3': expected a number, got 'abc'"),
        ("time_s,j1\n0,1\nsoon,2\n", "field 'line 3': expected seconds in 'time_s', got 'soon'"),
        ("time_s,j1\n0,1\n0,2\n", "strictly increasing"),
        ("time_s,j1\n0,1\n1,nan\n", "not finite"),
        ("time,j1\n0,1\nyesterday,2\n", "cannot read a time"),
    ],
)
def test_malformed_csv_names_file_and_place(tmp_path, text, expected):
    path = write(tmp_path, "bad.csv", text)
    with pytest.raises(FileFormatError) as caught:
        read_joint_trajectory(path)
    assert str(caught.value).startswith(str(path))
    assert expected in str(caught.value)


def test_malformed_npz(tmp_path):
    def saved(**arrays):
        path = tmp_path / "bad.npz"
        np.savez(path, **arrays)
        return path

    good = {"times": np.array([0.0, 1.0]), "positions": np.zeros((2, 1)),
            "joint_names": np.array(["a"])}
    cases = [
        ({k: v for k, v in good.items() if k != "positions"}, "missing array(s) positions"),
        ({**good, "positions": np.zeros((3, 1))}, "field 'positions': expected numbers of shape"),
        ({**good, "joint_names": np.array([1, 2])}, "field 'joint_names'"),
        ({**good, "joint_names": np.array(["a"], dtype=object)}, "field 'joint_names'"),
        ({**good, "times": np.array([1.0, 0.0])}, "strictly increasing"),
    ]
    for arrays, expected in cases:
        with pytest.raises(FileFormatError, match=expected.replace("(", r"\(").replace(")", r"\)")):
            read_joint_trajectory(saved(**arrays))
    not_zip = write(tmp_path, "text.npz", "time_s,j\n0,1\n")
    with pytest.raises(FileFormatError, match="not a readable NPZ file"):
        read_joint_trajectory(not_zip)


def test_unknown_suffix_and_missing_file(tmp_path):
    with pytest.raises(FileFormatError, match=r"expected \.csv or \.npz"):
        read_joint_trajectory(write(tmp_path, "m.txt", "time_s,j\n0,1\n"))
    with pytest.raises(ReadError, match="no such file"):
        read_joint_trajectory(tmp_path / "absent.csv")
