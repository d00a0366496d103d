"""``JointSolution.velocities``, ``velocity_limits``, ``speed_ratio`` and the speed check of
``solve_joints(..., strict=True)``.

Solutions are first checked with Pinocchio called directly on the URDF; their rates are
then differenced with plain numpy, and the limits read from the URDF with yourdfpy.
"""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import as_pose
from pinframes import FrameTree, JointSpeedError, Pose
from pinframes.errors import JointError, PinframesError
from robot_checks import placements, urdf_mimic_multiplier, urdf_velocity_limits

ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
ARM = [f"robot/joint_{index}" for index in range(1, 7)]
HOME = np.array([0.2, 0.4, -0.6, 0.1, 0.9, 0.3])  # rad
TOLERANCE = 1e-6

MIMIC_ARM = """\
    <?xml version="1.0"?>
    <robot name="mimic_arm">
      <link name="base"/><link name="upper"/><link name="fore"/><link name="hand"/>
      <joint name="shoulder" type="{shoulder}">
        <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
        {shoulder_limit}
      </joint>
      <joint name="elbow" type="revolute">
        <parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
        <limit lower="-3" upper="3" velocity="3.0" effort="10"/>
      </joint>
      <joint name="wrist" type="revolute">
        <parent link="fore"/><child link="hand"/><origin xyz="0.4 0 0"/><axis xyz="0 0 1"/>
        <limit lower="-3" upper="3" velocity="1.0" effort="10"/>
        <mimic joint="elbow" multiplier="-2" offset="0.1"/>
      </joint>
    </robot>
    """
"""A planar arm whose wrist follows the elbow at twice its rate: the wrist's limit (1 rad/s)
lets the elbow move at 0.5 rad/s, tighter than the elbow's own 3 rad/s."""


def flange_poses(configurations: np.ndarray) -> list[pin.SE3]:
    return placements(ROBOT, "flange", configurations)


def pinocchio_errors(found: list[pin.SE3], targets: list[pin.SE3]) -> np.ndarray:
    """Largest of position (m) and orientation (rad) error per sample."""
    offsets = [t.actInv(p) for p, t in zip(found, targets, strict=True)]
    return np.array([max(np.linalg.norm(o.translation), np.linalg.norm(pin.log3(o.rotation)))
                     for o in offsets])


def arm_limits(urdf: Path, names: list[str]) -> np.ndarray:
    limits = urdf_velocity_limits(urdf)
    return np.array([limits[name] for name in names])


def robot_tree() -> FrameTree:
    tree = FrameTree("floor")
    tree.attach_urdf(ROBOT, "floor", prefix="robot/")
    return tree


def ramp(seconds: np.ndarray, duration: float) -> np.ndarray:
    """Joint values moving from HOME by (0.6, -0.3, 0.4, 0.8, -0.5, 1.0) rad over
    ``duration`` seconds."""
    return HOME + np.clip(seconds / duration, 0.0, 1.0)[:, None] * np.array(
        [0.6, -0.3, 0.4, 0.8, -0.5, 1.0])


def checked_solution(duration: float, seconds: np.ndarray, *, strict: bool = False):
    """The welding robot's flange tracking ``ramp(duration)``; the solution checked with
    Pinocchio before its rates are looked at."""
    targets = flange_poses(ramp(seconds, duration))
    solution = robot_tree().solve_joints(
        "robot/flange", as_pose(targets, seconds), times=seconds, strict=strict,
        seed=dict(zip(ARM, HOME, strict=True)))
    assert solution.all_reached
    assert pinocchio_errors(flange_poses(solution.positions), targets).max() <= 2 * TOLERANCE
    return solution


UNEVEN = np.cumsum(np.r_[0.0, np.tile([0.01, 0.03, 0.02], 40)])  # s: steps of 10, 30, 20 ms


def test_velocities_are_the_rates_over_the_interval_ending_at_each_sample():
    solution = checked_solution(2.0, UNEVEN)
    expected = np.zeros_like(solution.positions)
    expected[1:] = np.diff(solution.positions, axis=0) / np.diff(UNEVEN)[:, None]
    assert solution.velocities.shape == (UNEVEN.size, 6)
    np.testing.assert_array_equal(solution.velocities[0], 0.0)
    np.testing.assert_allclose(solution.velocities, expected, rtol=1e-9, atol=1e-12)
    # and they are the ramp's own rates (0.6 rad over 2 s for joint 1, ...)
    moving = UNEVEN[1:] < 2.0 - 1e-9
    np.testing.assert_allclose(solution.velocities[1:][moving],
                               np.broadcast_to([0.3, -0.15, 0.2, 0.4, -0.25, 0.5],
                                               (int(moving.sum()), 6)), atol=1e-4)


def test_velocity_limits_are_the_urdfs_and_speed_ratio_the_largest_share():
    solution = checked_solution(2.0, UNEVEN)
    limits = arm_limits(ROBOT, [name.removeprefix("robot/") for name in ARM])
    np.testing.assert_array_equal(solution.velocity_limits, limits)
    assert solution.velocity_limit_joints == tuple(ARM)
    differences = np.diff(solution.positions, axis=0) / np.diff(UNEVEN)[:, None]
    expected = np.r_[0.0, (np.abs(differences) / limits).max(axis=1)]
    np.testing.assert_allclose(solution.speed_ratio, expected, rtol=1e-9, atol=1e-15)
    assert solution.speed_ratio.shape == (UNEVEN.size,)
    assert 0.0 < solution.speed_ratio.max() < 1.0


def test_strict_accepts_a_path_within_the_limits():
    solution = checked_solution(2.0, UNEVEN, strict=True)
    assert solution.speed_ratio.max() < 1.0


def test_strict_names_the_joint_the_time_and_the_ratio_of_a_path_too_fast():
    seconds = np.linspace(0.0, 0.4, 41)  # the ramp in 0.1 s: joint 1 at 6 rad/s, limit 3.49
    fast_solution = checked_solution(0.1, seconds)
    limits = arm_limits(ROBOT, [name.removeprefix("robot/") for name in ARM])
    ratios = np.abs(np.diff(fast_solution.positions, axis=0) / np.diff(seconds)[:, None]) / limits
    assert ratios.max() > 1.0  # the path is too fast for the robot
    first = int(np.flatnonzero(ratios.max(axis=1) > 1.0)[0])
    column = int(np.argmax(ratios[first]))
    with pytest.raises(JointSpeedError) as caught:
        checked_solution(0.1, seconds, strict=True)
    error = caught.value
    assert isinstance(error, JointError) and isinstance(error, PinframesError)
    assert error.joint == ARM[column] and error.frame == "robot/flange"
    assert error.field == "velocity"
    assert f"at {seconds[first + 1]:.9g} s" in str(error)
    ratio = float(re.search(r"is ([0-9.]+) times its velocity limit", str(error)).group(1))
    assert ratio == pytest.approx(ratios[first, column], rel=1e-2)
    assert f"{limits[column]:.3g} rad/s" in str(error)


def mimic_tree(tmp_path: Path, shoulder: str = "revolute",
               shoulder_limit: str = '<limit lower="-3" upper="3" velocity="2.0" effort="10"/>'
               ) -> tuple[FrameTree, Path]:
    urdf = tmp_path / "mimic_arm.urdf"
    urdf.write_text(textwrap.dedent(MIMIC_ARM).format(shoulder=shoulder,
                                                      shoulder_limit=shoulder_limit))
    tree = FrameTree("world")
    tree.attach_urdf(urdf, "world", prefix="arm/")
    tree.add("tip", "arm/hand", Pose([0.3, 0.0, 0.0]))
    return tree, urdf


def mimic_tip_poses(urdf: Path, values: np.ndarray) -> list[pin.SE3]:
    """The tip (0.3 m along the hand) by Pinocchio, the wrist set to follow the elbow by
    hand (``-2 * elbow + 0.1``, as the URDF's mimic says); Pinocchio reads the mimic joint as
    a joint of its own, a continuous shoulder as (cos, sin)."""
    shoulder, elbow = values[:, 0], values[:, 1]
    continuous = 'type="continuous"' in urdf.read_text()
    turn = [np.cos(shoulder), np.sin(shoulder)] if continuous else [shoulder]
    hands = placements(urdf, "hand", np.column_stack([*turn, elbow, -2.0 * elbow + 0.1]))
    return [hand * pin.SE3(np.eye(3), np.array([0.3, 0.0, 0.0])) for hand in hands]


def solve_mimic_arm(tmp_path: Path, elbow_rate: float, *, strict: bool = False, **arm):
    seconds = np.linspace(0.0, 1.0, 21)
    values = np.column_stack([0.3 * seconds, 0.2 + elbow_rate * seconds])
    tree, urdf = mimic_tree(tmp_path, **arm)
    targets = mimic_tip_poses(urdf, values)
    solution = tree.solve_joints("tip", as_pose(targets, seconds), seed=[0.0, 0.2],
                                 strict=strict)
    assert solution.all_reached
    assert pinocchio_errors(mimic_tip_poses(urdf, solution.positions), targets).max() <= (
        2 * TOLERANCE)
    return solution, urdf, seconds


def test_a_mimic_joint_that_moves_limits_its_primary_by_its_own_limit(tmp_path):
    solution, urdf, seconds = solve_mimic_arm(tmp_path, 0.4)
    shoulder, elbow, wrist = arm_limits(urdf, ["shoulder", "elbow", "wrist"])
    multiplier = urdf_mimic_multiplier(urdf, "wrist")
    expected = np.array([shoulder, min(elbow, wrist / abs(multiplier))])  # 2.0, 0.5 rad/s
    np.testing.assert_array_equal(solution.velocity_limits, expected)
    assert solution.velocity_limit_joints == ("arm/shoulder", "arm/wrist")
    rates = np.diff(solution.positions, axis=0) / np.diff(seconds)[:, None]
    # the wrist moves at 2 x 0.4 = 0.8 of its 1 rad/s
    np.testing.assert_allclose(solution.speed_ratio[1:],
                               np.max(np.abs(rates) / expected, axis=1), rtol=1e-9)
    np.testing.assert_allclose(solution.speed_ratio[1:], 0.8, rtol=1e-4)


def test_strict_names_the_mimic_joint_whose_limit_is_passed(tmp_path):
    solve_mimic_arm(tmp_path, 0.4, strict=True)  # within every limit
    with pytest.raises(JointSpeedError) as caught:
        solve_mimic_arm(tmp_path, 0.7, strict=True)  # wrist at 1.4 rad/s, limit 1
    error = caught.value
    assert error.joint == "arm/wrist"
    assert "1.4 rad/s" in str(error) and "1.4 times" in str(error)
    assert "arm/elbow" in str(error) and "at 0.05 s" in str(error)


def test_a_joint_without_a_velocity_limit_has_an_infinite_one(tmp_path):
    solution, urdf, _ = solve_mimic_arm(tmp_path, 0.4, shoulder="continuous",
                                        shoulder_limit="")
    assert "shoulder" not in urdf_velocity_limits(urdf)
    assert solution.velocity_limits[0] == np.inf
    assert solution.velocity_limit_joints[0] == "arm/shoulder"
    np.testing.assert_allclose(solution.speed_ratio[1:], 0.8, rtol=1e-4)  # the wrist's


def test_one_sample_has_zero_velocity(tmp_path):
    tree, urdf = mimic_tree(tmp_path)
    target = mimic_tip_poses(urdf, np.array([[0.3, 0.5]]))[0]
    solution = tree.solve_joints("tip", Pose(target.translation, target.rotation),
                                 relative_to="world", seed=[0.2, 0.4])
    assert len(solution) == 1 and solution.all_reached
    np.testing.assert_array_equal(solution.velocities, np.zeros((1, 2)))
    np.testing.assert_array_equal(solution.speed_ratio, [0.0])
