"""Times outside a motion on the command line: one warning naming what is held (clamp, the
default), or an error (``--extrapolation error``); times within every motion say nothing.
The bundled cell moves from 0 s to 20 s."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell" / "scene.yaml"
POINTS = "<points>"  # a CSV of points without times, written per test


def warnings_of(result) -> list[str]:
    return [line for line in result.stderr.splitlines()
            if line.startswith("pinframes: warning:")]


@pytest.mark.parametrize("command", [
    ("pose", CELL, "torch_tcp", "-r", "workpiece"),
    ("transform", CELL, POINTS, "torch_tcp", "-r", "workpiece"),
    ("process", CELL, "--torch", "torch_tcp", "--seam", "seam_point", "--workpiece",
     "workpiece"),
    ("solve", CELL, "--frame", "torch_tcp", "--target", "torch_target"),
    ("clearance", CELL, "torch", "pipe"),
])
@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_times_after_the_motion_warn_once_or_fail(run_cli, tmp_path, command):
    points = tmp_path / "points.csv"
    points.write_text("x_m,y_m,z_m\n0,0,0\n0.1,0,0\n")
    command = [points if part == POINTS else part for part in command]
    result = run_cli(*command, "--times", "5", "20", "25", "30")
    assert result.returncode == 0, result.stderr
    (warning,) = warnings_of(result)
    assert "10 s after its last keyframe" in warning  # 30 s on a motion ending at 20 s
    assert "--extrapolation error" in warning
    refused = run_cli(*command, "--times", "5", "25", "--extrapolation", "error")
    assert refused.returncode == 1
    assert "pinframes: error:" in refused.stderr and "5 s after its last keyframe" in (
        refused.stderr)
    assert refused.stdout == ""
    within = run_cli(*command, "--times", "0", "20", "--extrapolation", "error")
    assert within.returncode == 0, within.stderr
    assert warnings_of(within) == []


def test_a_motion_held_after_its_end_by_default_times_warns(run_cli, tmp_path):
    """The seam frame stops at 15 s while the table turns on to 20 s: the default times
    (every sample on the path) run past the seam's last keyframe."""
    scene = tmp_path / "cell.yaml"
    scene.write_text("""\
pinframes_scene: 1
frames:
  - name: table
    parent: world
    keyframes: [{time: 0, rpy: [0, 0, 0]}, {time: 20, rpy: [0, 0, 1]}]
  - name: seam
    parent: table
    keyframes: [{time: 0, xyz: [0, 0, 0]}, {time: 15, xyz: [0.15, 0, 0]}]
  - {name: torch, parent: world, xyz: [0, 0, 0.2]}
""")
    result = run_cli("pose", scene, "seam", "-r", "world")
    assert result.returncode == 0, result.stderr
    (warning,) = warnings_of(result)
    assert "'seam'" in warning and "5 s after its last keyframe" in warning
    rows = np.loadtxt(result.stdout.splitlines()[1:], delimiter=",")
    assert rows[-1, 0] == 20.0  # still computed there, with the seam held at 0.15 m
    np.testing.assert_allclose(np.hypot(rows[-1, 1], rows[-1, 2]), 0.15, atol=1e-12)


def test_points_timed_after_the_motion_warn(run_cli, tmp_path):
    scan = tmp_path / "scan.csv"
    scan.write_text("time_s,x_m,y_m,z_m\n0,0,0,0\n22.5,0,0,0.01\n")
    result = run_cli("transform", CELL, scan, "torch_tcp", "-r", "workpiece")
    assert result.returncode == 0, result.stderr
    (warning,) = warnings_of(result)
    assert "2.5 s after its last keyframe" in warning
