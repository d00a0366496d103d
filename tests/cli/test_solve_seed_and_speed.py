"""``pinframes solve --seed NAME=VALUE ...`` and the summary's fastest joint against its
URDF velocity limit. Solutions are checked with Pinocchio on the URDF; rates are plain
numpy differences of the CSV read back, limits read from the URDF with yourdfpy."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from pinframes import read_joint_trajectory
from robot_checks import placements, urdf_velocity_limits

ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
HOME = np.array([0.2, 0.4, -0.6, 0.1, 0.9, 0.3])  # rad
TURN_DEG = 40.0  # the table turns this much about its vertical axis in 2 s


def flange(configuration: np.ndarray) -> pin.SE3:
    return placements(ROBOT, "flange", configuration)[0]


def seed_arguments(values: np.ndarray) -> list[str]:
    """``--seed`` values for joints 1 to 6."""
    return ["--seed", *(f"robot/joint_{index + 1}={float(value)!r}"
                        for index, value in enumerate(values))]


@pytest.fixture
def cell(tmp_path: Path) -> Path:
    """The robot at the root; ``spot``, a fixed frame where the flange is at HOME; ``seam``,
    the same place on a table that turns 40 degrees in 2 s about a vertical axis 0.15 m
    away; ``quick_seam``, on a table that makes the same turn in 0.1 s."""
    tool = flange(HOME)
    quaternion = pin.Quaternion(tool.rotation).coeffs().tolist()  # x y z w
    centre = tool.translation + np.array([0.15, 0.0, 0.0])
    half = math.radians(TURN_DEG) / 2
    path = tmp_path / "cell.yaml"
    tables = "".join(textwrap.dedent(f"""\
          - name: {prefix}table
            parent: world
            xyz: {centre.tolist()}
            keyframes:
              - {{time: 0, quaternion: [0, 0, 0, 1]}}
              - {{time: {seconds}, quaternion: [0, 0, {math.sin(half)!r}, {math.cos(half)!r}]}}
          - name: {prefix}seam
            parent: {prefix}table
            xyz: {(tool.translation - centre).tolist()}
            quaternion: {quaternion}
        """) for prefix, seconds in (("", 2), ("quick_", 0.1)))
    path.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        name: cell
        robots:
          - {{name: welder, urdf: {ROBOT}, parent: world, prefix: robot/}}
        frames:
          - name: spot
            parent: world
            xyz: {tool.translation.tolist()}
            quaternion: {quaternion}
        """) + textwrap.indent(tables, "  "))
    return path


def test_the_seed_is_where_the_first_sample_starts(cell, run_cli, tmp_path):
    """With the torch axis free, the flange at HOME with joint 6 turned to 1.2 rad is already
    on ``spot``: started there, the solver stays there; started from the default (the rest
    values), it cannot end there."""
    seeded = HOME.copy()
    seeded[5] = 1.2
    on_spot = flange(seeded)
    assert np.allclose(on_spot.translation, flange(HOME).translation)
    out = tmp_path / "seeded.csv"
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                     "--free-axis", "z", "--times", "0", "1", *seed_arguments(seeded),
                     "-o", out)
    assert result.returncode == 0, result.stderr
    _, positions, _ = read_joint_trajectory(out)
    for row in positions:
        placement = flange(row)
        assert np.linalg.norm(placement.translation - on_spot.translation) <= 1e-6
        assert np.dot(placement.rotation[:, 2], on_spot.rotation[:, 2]) >= 1 - 1e-12
    np.testing.assert_allclose(positions, np.tile(seeded, (2, 1)), atol=1e-6)

    unseeded = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                       "--free-axis", "z", "--times", "0", "1")
    assert unseeded.returncode == 0, unseeded.stderr
    assert abs(float(unseeded.stdout.splitlines()[1].split(",")[6]) - 1.2) > 0.1


def test_a_partial_seed_names_some_joints(cell, run_cli, tmp_path):
    out = tmp_path / "joints.csv"
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                     "--free-axis", "z", "--times", "0", "--seed", "robot/joint_6=-2.5",
                     "robot/joint_3=-0.6", "-o", out)
    assert result.returncode == 0, result.stderr
    _, positions, _ = read_joint_trajectory(out)
    assert np.linalg.norm(flange(positions[0]).translation - flange(HOME).translation) <= 1e-6
    assert result.stderr.rstrip().endswith("; one sample, so no joint speeds")


@pytest.mark.parametrize("name", ["robot/joint_9", "joint_2"])
def test_a_seed_for_an_unknown_joint_is_a_user_error_naming_it(cell, run_cli, tmp_path, name):
    out = tmp_path / "joints.csv"
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                     "--times", "0", "--seed", f"{name}=0.1", "-o", out)
    assert result.returncode == 1
    assert result.stderr.startswith("pinframes: error:")
    assert repr(name) in result.stderr and "--seed" in result.stderr
    assert "Traceback" not in result.stderr and not out.exists()


def test_a_seed_given_twice_is_a_user_error(cell, run_cli):
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                     "--times", "0", "--seed", "robot/joint_1=0.1", "robot/joint_1=0.2")
    assert result.returncode == 1
    assert "'robot/joint_1'" in result.stderr and "twice" in result.stderr


@pytest.mark.parametrize("text", ["robot/joint_1", "robot/joint_1=fast", "=0.5"])
def test_a_malformed_seed_is_a_usage_error(cell, run_cli, text):
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "spot",
                     "--seed", text)
    assert result.returncode == 2
    assert "NAME=VALUE" in result.stderr and repr(text) in result.stderr


def speed_ratios(out: Path) -> tuple[np.ndarray, np.ndarray, list[str], np.ndarray]:
    """From the CSV, by numpy differences: |rate| / limit per interval and joint, the rates,
    the joint names and the times at which the intervals end."""
    times, positions, names = read_joint_trajectory(out)
    limits = urdf_velocity_limits(ROBOT)
    rates = np.abs(np.diff(positions, axis=0) / np.diff(times)[:, None])
    return rates / np.array([limits[name] for name in names]), rates, names, times[1:]


def fastest(out: Path) -> tuple[str, float, float, float]:
    """The joint with the largest |rate| / limit, its speed, its limit and the time."""
    ratios, rates, names, ends = speed_ratios(out)
    row, column = np.unravel_index(np.argmax(ratios), ratios.shape)
    return names[column], rates[row, column], urdf_velocity_limits(ROBOT)[names[column]], ends[row]


def test_the_summary_names_the_fastest_joint_against_its_limit(cell, run_cli, tmp_path):
    out = tmp_path / "joints.csv"
    result = run_cli("solve", cell, "--frame", "robot/flange", "--target", "seam",
                     "--start", "0", "--stop", "2", "--step", "0.02", *seed_arguments(HOME),
                     "-o", out)
    assert result.returncode == 0, result.stderr
    assert "101 samples, 101 reached" in result.stderr
    name, speed, limit, when = fastest(out)
    assert (f"fastest joint robot/{name}: {speed:.3g} of {limit:.3g} rad/s "
            f"({speed / limit:.0%} of its limit) at {when:.6g} s") in result.stderr
    assert "faster than the robot can move" not in result.stderr


def test_the_summary_and_strict_say_when_the_robot_cannot_keep_up(cell, run_cli, tmp_path):
    """The 40 degree turn in 0.1 s."""
    out = tmp_path / "joints.csv"
    args = ["solve", cell, "--frame", "robot/flange", "--target", "quick_seam", "--start", "0",
            "--stop", "0.1", "--step", "0.01", *seed_arguments(HOME)]
    result = run_cli(*args, "-o", out)
    assert result.returncode == 0, result.stderr
    name, speed, limit, when = fastest(out)
    assert speed > limit
    assert (f"fastest joint robot/{name}: {speed:.3g} of {limit:.3g} rad/s "
            f"({speed / limit:.0%} of its limit) at {when:.6g} s: faster than the robot can "
            "move") in result.stderr

    strict = run_cli(*args, "--strict", "-o", tmp_path / "strict.csv")
    assert strict.returncode == 1
    ratios, _, names, ends = speed_ratios(out)  # the first time a joint is too fast
    row = int(np.flatnonzero(ratios.max(axis=1) > 1.0)[0])
    column = int(np.argmax(ratios[row]))
    assert f"joint 'robot/{names[column]}'" in strict.stderr
    assert f"{ratios[row, column]:.3g} times its velocity limit" in strict.stderr
    assert f"at {ends[row]:.9g} s" in strict.stderr
    assert not (tmp_path / "strict.csv").exists()
