"""``pinframes convert IN OUT.mcap|OUT.bag|FOLDER [time options]``: trees out to ROS bags on
the command line, checked with rosbags' own reader."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import pinframes

pytest.importorskip("mcap_ros2")
from ros.bag_decoding import decode, matrix_from_quaternion

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell" / "scene.yaml"


def test_a_grid_of_times_becomes_the_stamps(run_cli, tmp_path):
    result = run_cli("convert", CELL, tmp_path / "grid.bag", "--start", "1", "--stop", "3",
                     "--step", "0.5")
    assert result.returncode == 0, result.stderr
    assert "wrote" in result.stderr
    records = decode(tmp_path / "grid.bag", "rosbags")
    stamps = sorted({row["stamp_ns"] for row in records["/tf"]})
    assert stamps == [10**9 + k * 5 * 10**8 for k in range(5)]  # no reference: from 0
    cell = pinframes.read_scene(CELL)
    rows = [row for row in records["/tf"] if row["child"] == "positioner"]
    pose = cell.pose("positioner", "positioner_base", times=[1.0, 1.5, 2.0, 2.5, 3.0])
    np.testing.assert_allclose([matrix_from_quaternion(row["quaternion"]) for row in rows],
                               pose.rotation, atol=1e-12)


def test_a_name_without_suffix_is_a_ros2_bag_folder_and_time_ref_sets_the_clock(
        run_cli, tmp_path):
    result = run_cli("convert", CELL, tmp_path / "run", "--times", "0", "20",
                     "--time-ref", "2024-03-01T08:00:00")
    assert result.returncode == 0, result.stderr
    assert sorted(path.name for path in (tmp_path / "run").iterdir()) == ["metadata.yaml",
                                                                          "run.mcap"]
    back = pinframes.read(tmp_path / "run")
    assert back.reference_time == np.datetime64("2024-03-01T08:00:00", "ns")
    cell = pinframes.read_scene(CELL)
    end = np.datetime64("2024-03-01T08:00:20", "ns")
    np.testing.assert_allclose(back.pose("torch_tcp", "world", times=[end]).matrix,
                               cell.pose("torch_tcp", "world", times=[20.0]).matrix,
                               atol=1e-9)


def test_time_options_for_files_that_hold_no_times_are_refused(run_cli, tmp_path):
    result = run_cli("convert", CELL, tmp_path / "cell.asdf", "--times", "1", "2")
    assert result.returncode != 0
    assert "--times is for ROS bag files" in result.stderr
    assert not (tmp_path / "cell.asdf").exists()
