"""``solve_joints`` without a seed on the industrial arms that lost whole paths from their
rest values: ROS-Industrial's KUKA KR 5 arc and ABB GoFa CRB 15000-5/0.95 (tests/data).

Each path comes from a joint trajectory the arm can follow, far from the rest values (all
zero); every answer is checked with Pinocchio called directly on the URDF
(:mod:`ik_paths`).
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import (
    DATA,
    Arm,
    as_pose,
    frame_poses,
    largest_step,
    on_target,
    swinging,
    within_limits,
)
from pinframes import JointSolution
from pinframes.errors import TargetNotReachedError

SAMPLES = 101
RATE_HZ = 50.0

KR5 = Arm("KR5 arc", DATA / "kuka_kr5_arc" / "kr5_arc.urdf", "tool0", 6,
          (-0.6, -2.8, 2.0, -1.8, -0.9, 1.8), (0.4, 0.3, 0.3, 0.5, 0.4, 0.8))
"""Leaning back over its base (A2 -2.8 rad), elbow bent, wrist turned."""
CRB15000 = Arm("CRB 15000", DATA / "abb_crb15000" / "crb15000_5_95.urdf", "tool0", 6,
               (-1.7, -0.8, -2.1, -0.8, 2.5, 0.3), (0.4, 0.3, 0.3, 0.5, 0.4, 0.8))
"""Leaning back, elbow folded over (joint 3 -2.1 rad), wrist bent 2.5 rad."""
ARMS = [pytest.param(KR5, id="KR5"), pytest.param(CRB15000, id="CRB15000")]

CRB15000_OVER = replace(CRB15000, home=(2.7, 2.0, 0.1, 0.3, -0.6, 0.8))
"""Turned round and leaning far forward (joint 2 2.0 rad)."""
CRB15000_UNDER = replace(CRB15000, home=(1.9, -1.6, -1.3, -1.3, -2.7, -0.9))
"""Leaning back, wrist bent to -2.7 rad, near its limit."""
WIDE_RANGES = [pytest.param(CRB15000_OVER, id="over"), pytest.param(CRB15000_UNDER, id="under")]
WHOLE_TURNS = [
    pytest.param(replace(CRB15000, home=home), id=name) for name, home in [
        ("wrist-down", (1.465, -0.83, -0.871, -1.491, 0.483, -1.421)),
        ("folded-back", (-1.934, -2.456, -1.301, -2.56, 0.426, -2.274))]]
"""GoFa paths whose first sample the 64 spread starts reached only on branches that lose
the path, the Newton of the others stopping on a joint's limit at -pi or pi (72 of 101
reached on each)."""


def a_path(robot: Arm) -> tuple[np.ndarray, list, np.ndarray]:
    """The arm's trajectory (101 samples at 50 Hz), its tool's poses by Pinocchio, times."""
    times = np.arange(SAMPLES) / RATE_HZ
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    assert within_limits(robot.model(), trajectory)
    return trajectory, frame_poses(robot.model(), robot.tool, trajectory), times


def solved(robot: Arm, targets: list, times: np.ndarray, **options) -> JointSolution:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints have no samples: they warn so
        return robot.tree().solve_joints(robot.tool, as_pose(targets, times), **options)


@pytest.mark.parametrize("robot", [*ARMS, *WIDE_RANGES])
def test_without_a_seed_the_whole_path_is_reached(robot):
    """Issue 33: from the rest values alone the first two paths were lost (0 of 101); the
    starts spread over the ranges find a branch that follows every sample, in steps like
    the trajectory's own, inside the limits. On the GoFa, whose joints turn -180..180
    degrees, most starts stop on a limit: 16 starts lost the last two paths (66 and 34 of
    101 reached), 64 find them."""
    trajectory, targets, times = a_path(robot)
    solution = solved(robot, targets, times)
    model = robot.model()
    assert on_target(model, robot.tool, solution.positions, targets).all()
    assert solution.all_reached
    assert within_limits(model, solution.positions)
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory)


@pytest.mark.parametrize("robot", ARMS)
def test_samples_out_of_reach_cost_no_reachable_one(robot):
    """Five samples 3 m away from the path: no start reaches them all, so the solutions
    that follow the path furthest are tracked to the end; every other sample is reached."""
    _, targets, times = a_path(robot)
    away = range(40, 45)
    for index in away:
        targets[index] = pin.SE3(targets[index].rotation,
                                 targets[index].translation + np.array([3.0, 0.0, 0.0]))
    solution = solved(robot, targets, times)
    reached = on_target(robot.model(), robot.tool, solution.positions, targets)
    np.testing.assert_array_equal(np.flatnonzero(~reached), list(away))
    np.testing.assert_array_equal(reached, solution.reached)


@pytest.mark.parametrize("robot", ARMS)
def test_a_seed_at_the_rest_values_is_the_only_start(robot):
    """A given seed is honoured, not second-guessed: from the rest values the path is lost
    (the case the starts are for), and the loss is said: the solution's ``reached`` flags
    are Pinocchio's."""
    _, targets, times = a_path(robot)
    solution = solved(robot, targets, times, seed=np.zeros(6))
    reached = on_target(robot.model(), robot.tool, solution.positions, targets)
    assert not reached.all()
    np.testing.assert_array_equal(reached, solution.reached)


@pytest.mark.parametrize("robot", ARMS)
def test_a_seed_near_the_trajectory_keeps_its_branch(robot):
    trajectory, targets, times = a_path(robot)
    solution = solved(robot, targets, times, seed=trajectory[0] + 0.05)
    assert on_target(robot.model(), robot.tool, solution.positions, targets).all()
    np.testing.assert_allclose(solution.positions, trajectory, atol=1e-5)


def test_a_seed_on_the_flipped_wrist_keeps_that_branch():
    """The KR 5 arc's wrist is spherical: turning A4 and A6 by pi and negating A5 puts the
    tool on the same pose (checked by Pinocchio). Seeded there, the solver stays there."""
    trajectory, targets, times = a_path(KR5)
    flipped = trajectory[0] + np.array([0.0, 0.0, 0.0, np.pi, 0.0, np.pi])
    flipped[4] = -trajectory[0, 4]
    same = frame_poses(KR5.model(), KR5.tool, np.array([trajectory[0], flipped]))
    np.testing.assert_allclose(same[0].homogeneous, same[1].homogeneous, atol=1e-12)
    solution = solved(KR5, targets, times, seed=flipped + 0.05)
    np.testing.assert_allclose(solution.positions[0], flipped, atol=1e-5)
    assert on_target(KR5.model(), KR5.tool, solution.positions, targets).all()


@pytest.mark.parametrize("robot", ARMS)
def test_the_start_taken_is_the_same_on_every_call(robot):
    _, targets, times = a_path(robot)
    first, again = solved(robot, targets, times), solved(robot, targets, times)
    np.testing.assert_array_equal(first.positions, again.positions)


# -- many ROS-Industrial six-axis arms ---------------------------------------------------------
INDUSTRIAL = sorted((DATA / "ros_industrial_arms").glob("*/*.urdf"))
"""Fanuc, Yaskawa Motoman, ABB and KUKA arms as ROS-Industrial describes them (tests/data)."""


def far_paths(robot: Arm, count: int) -> list[np.ndarray]:
    """``count`` trajectories (101 samples at 50 Hz) swinging about configurations drawn
    uniformly inside the limits (within -pi..pi), each at least 1.5 rad (Euclidean) from
    the rest values; the same on every run."""
    model = robot.model()
    lower = np.maximum(model.lowerPositionLimit, -np.pi)
    upper = np.minimum(model.upperPositionLimit, np.pi)
    swing = np.minimum(robot.swing, (upper - lower) / 4)
    generator = np.random.default_rng(20261127)
    times = np.arange(SAMPLES) / RATE_HZ
    paths = []
    while len(paths) < count:
        home = generator.uniform(lower + swing, upper - swing)
        if np.linalg.norm(home) >= 1.5:
            paths.append(swinging(home, swing, times))
    return paths


def industrial(urdf) -> Arm:
    return Arm(f"{urdf.parent.name}/{urdf.stem}", urdf, "tool0", 6, (0.0,) * 6,
               (0.4, 0.3, 0.3, 0.5, 0.4, 0.8))


def assert_followed_without_a_seed(robot: Arm, count: int) -> None:
    model = robot.model()
    times = np.arange(SAMPLES) / RATE_HZ
    for trajectory in far_paths(robot, count):
        targets = frame_poses(model, robot.tool, trajectory)
        solution = solved(robot, targets, times)
        assert on_target(model, robot.tool, solution.positions, targets).all(), trajectory[0]
        assert within_limits(model, solution.positions)


@pytest.mark.parametrize("urdf", INDUSTRIAL, ids=lambda urdf: urdf.stem)
def test_industrial_arms_follow_paths_far_from_rest_without_a_seed(urdf):
    """Issue 33 found 26 of 124 industrial six-axis arms missing paths they can follow
    when started from their rest values; here 25 of ROS-Industrial's, two paths each."""
    assert_followed_without_a_seed(industrial(urdf), 2)


@pytest.mark.slow
@pytest.mark.parametrize("urdf", INDUSTRIAL, ids=lambda urdf: urdf.stem)
def test_industrial_arms_follow_many_paths_without_a_seed(urdf):
    assert_followed_without_a_seed(industrial(urdf), 20)


def test_a_path_that_first_stands_longer_than_a_chunk_is_followed():
    """The starts are compared where the path moves: a target that stands for 4,200 samples
    (more than the 4,096 of a chunk) tells no branch from another, and comparing them there
    took one that lost 76 samples of the path after it."""
    _, moving, moving_times = a_path(CRB15000_OVER)
    hold = 4200
    targets = [moving[0]] * hold + moving
    times = np.concatenate([np.arange(hold) / RATE_HZ, hold / RATE_HZ + moving_times])
    solution = solved(CRB15000_OVER, targets, times)
    assert on_target(CRB15000_OVER.model(), CRB15000_OVER.tool, solution.positions,
                     targets).all()
    assert solution.all_reached
    np.testing.assert_array_equal(solution.positions[:hold], solution.positions[[0] * hold])


def test_a_standing_start_out_of_reach_is_reported_at_the_first_sample():
    """With ``strict=True`` the first sample not reached is the one reported, also when the
    samples that stand on it fill more than a chunk."""
    _, moving, moving_times = a_path(KR5)
    away = pin.SE3(moving[0].rotation, moving[0].translation + np.array([3.0, 0.0, 0.0]))
    hold = 4200
    times = np.concatenate([np.arange(hold) / RATE_HZ, hold / RATE_HZ + moving_times])
    with pytest.raises(TargetNotReachedError, match=r"sample 1 of 4301"):
        solved(KR5, [away] * hold + moving, times, strict=True)


def test_tilts_of_a_standing_start_are_those_of_its_first_sample():
    """Process windows report a tilt per sample, the standing ones included; the tilts
    are Pinocchio's tool in its target (about x, then y)."""
    _, moving, moving_times = a_path(KR5)
    hold = 4200
    targets = [moving[0]] * hold + moving
    times = np.concatenate([np.arange(hold) / RATE_HZ, hold / RATE_HZ + moving_times])
    solution = solved(KR5, targets, times, tilt=(0.2, 0.2))
    assert solution.all_reached and solution.tilt is not None
    assert solution.tilt.shape == (len(targets), 2)
    tools = frame_poses(KR5.model(), KR5.tool, solution.positions[[0, hold - 1, hold + 50]])
    for tool, index in zip(tools, [0, hold - 1, hold + 50], strict=True):
        in_target = targets[index].actInv(tool).rotation
        about_x = np.arctan2(-in_target[1, 2], in_target[2, 2])
        about_y = np.arcsin(np.clip(in_target[0, 2], -1.0, 1.0))
        np.testing.assert_allclose(solution.tilt[index], [about_x, about_y], atol=1e-9)


@pytest.mark.parametrize("robot", WHOLE_TURNS)
def test_joints_that_turn_a_whole_turn_do_not_stop_a_start_on_a_limit(robot):
    """Five of the GoFa's joints turn -pi..pi: a value past pi is the same pose as that
    value less a turn. Solved from a start far away, such a joint turns the short way and
    comes back into its range, where it stopped on the limit before: the branch that
    follows the path is among the first sample's solutions."""
    trajectory, targets, times = a_path(robot)
    solution = solved(robot, targets, times)
    model = robot.model()
    assert on_target(model, robot.tool, solution.positions, targets).all()
    assert within_limits(model, solution.positions)
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory)
