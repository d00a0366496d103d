"""Point-to-point moves against Ruckig's own ``calculate`` (same limits, rest to rest)."""

from __future__ import annotations

import numpy as np
import pytest
from ruckig import InputParameter, Result, Ruckig, Trajectory

from pinframes.errors import InvalidTimeError, JointError
from pinframes.kinematics.timing import MotionLimits, time_point_to_point

pytestmark = pytest.mark.filterwarnings("error")


def ruckig_duration(start, goal, velocity, acceleration, jerk=None) -> float:
    """Ruckig's duration of the synchronised rest-to-rest move (infinite jerk: second order)."""
    count = len(start)
    parameters = InputParameter(count)
    parameters.current_position = list(start)
    parameters.target_position = list(goal)
    parameters.max_velocity = list(velocity)
    parameters.max_acceleration = list(acceleration)
    parameters.max_jerk = [float("inf")] * count if jerk is None else list(jerk)
    trajectory = Trajectory(count)
    assert Ruckig(count).calculate(parameters, trajectory) == Result.Working
    return float(trajectory.duration)


def random_case(rng: np.random.Generator, count: int, with_jerk: bool):
    start = rng.uniform(-3, 3, count)
    goal = start + rng.uniform(-3, 3, count) * rng.choice([1e-3, 0.1, 1.0], count)
    velocity = rng.uniform(0.2, 4, count)
    acceleration = rng.uniform(0.5, 20, count)
    jerk = rng.uniform(5, 500, count) if with_jerk else None
    return start, goal, velocity, acceleration, jerk


def finite_differences(positions: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocities and accelerations from positions sampled every ``step`` s."""
    velocity = np.diff(positions, axis=0) / step
    return velocity, np.diff(velocity, axis=0) / step


def assert_within_limits(move, velocity, acceleration, jerk=None, samples=4001):
    """The samples and their finite differences keep every limit (to 0.5 %), the rates are
    the derivatives of the positions, and the move starts and ends at rest."""
    seconds = np.linspace(0, move.duration, samples)
    step = seconds[1] - seconds[0]
    positions, velocities, accelerations = move.sample(seconds)
    assert np.all(np.abs(velocities) <= velocity * (1 + 1e-9) + 1e-12)
    assert np.all(np.abs(accelerations) <= acceleration * (1 + 1e-9) + 1e-12)
    speed, rate = finite_differences(positions, step)
    rounding = 1e-15 * (1 + np.abs(positions).max()) / step
    assert np.all(np.abs(speed) <= velocity * 1.005 + rounding)
    assert np.all(np.abs(rate) <= acceleration * 1.005 + rounding / step)
    # the mean of the sampled velocities over a step is the step's finite difference
    bound = step * acceleration if jerk is None else step**2 * jerk
    assert np.all(np.abs(speed - (velocities[1:] + velocities[:-1]) / 2) <= bound + rounding)
    np.testing.assert_allclose(positions[0], move.start, atol=1e-12)
    np.testing.assert_allclose(positions[-1], move.goal, atol=1e-9)
    np.testing.assert_allclose(velocities[[0, -1]], 0, atol=1e-9)
    if jerk is not None:  # an S-curve starts and ends without acceleration, too
        np.testing.assert_allclose(accelerations[[0, -1]], 0, atol=1e-9 * acceleration.max())
        jerks = np.diff(accelerations, axis=0) / step
        assert np.all(np.abs(jerks) <= jerk * 1.005 + 1e-9)


@pytest.mark.parametrize("with_jerk", [False, True])
@pytest.mark.parametrize("count", [1, 2, 6, 7])
def test_durations_equal_ruckig_on_random_moves(count, with_jerk):
    rng = np.random.default_rng(4300 + count + 100 * with_jerk)
    worst = 0.0
    for _ in range(40):
        start, goal, velocity, acceleration, jerk = random_case(rng, count, with_jerk)
        move = time_point_to_point(start, goal, MotionLimits(velocity, acceleration, jerk))
        expected = ruckig_duration(start, goal, velocity, acceleration, jerk)
        worst = max(worst, abs(move.duration - expected) / expected)
    assert worst < 1e-6


@pytest.mark.parametrize("with_jerk", [False, True])
def test_every_joint_keeps_its_limits_and_arrives_with_the_others(with_jerk):
    rng = np.random.default_rng(43)
    for _ in range(5):
        start, goal, velocity, acceleration, jerk = random_case(rng, 6, with_jerk)
        move = time_point_to_point(start, goal, MotionLimits(velocity, acceleration, jerk))
        assert_within_limits(move, velocity, acceleration, jerk)
        positions = move.sample(np.array([0.999 * move.duration]))[0][0]
        assert np.all(np.abs(positions - goal) > 0)  # nobody arrived early


@pytest.mark.parametrize("jerk", [None, [30.0, 30.0, 30.0]])
def test_a_still_joint_stays_still_and_all_still_is_no_move(jerk):
    limits = MotionLimits([1.0, 2.0, 3.0], [2.0, 2.0, 2.0], jerk)
    move = time_point_to_point([0.1, 0.2, 0.3], [0.1, 1.2, -0.7], limits)
    positions, velocities, accelerations = move.sample(np.linspace(0, move.duration, 50))
    assert np.all(positions[:, 0] == 0.1)
    assert np.all(velocities[:, 0] == 0) and np.all(accelerations[:, 0] == 0)
    assert move.duration == pytest.approx(
        ruckig_duration([0.1, 0.2, 0.3], [0.1, 1.2, -0.7], [1, 2, 3], [2, 2, 2], jerk), rel=1e-9)
    still = time_point_to_point([0.1, 0.2, 0.3], [0.1, 0.2, 0.3], limits)
    assert still.duration == 0.0
    positions, velocities, accelerations = still.sample(np.array([0.0, 1.0]))
    np.testing.assert_array_equal(positions, [[0.1, 0.2, 0.3]] * 2)
    assert not velocities.any() and not accelerations.any()


@pytest.mark.parametrize("jerk", [None, [1e4, 1.0]])
def test_very_short_moves_and_limits_of_different_magnitudes(jerk):
    velocity, acceleration = [1e-3, 50.0], [1e3, 1e-2]
    limits = MotionLimits(velocity, acceleration, jerk)
    for distance in (1e-9, 1e-5, 1e-2, 5.0):
        goal = [distance, -distance]
        move = time_point_to_point([0.0, 0.0], goal, limits)
        expected = ruckig_duration([0.0, 0.0], goal, velocity, acceleration, jerk)
        assert move.duration == pytest.approx(expected, rel=1e-6)
        assert_within_limits(move, np.array(velocity), np.array(acceleration),
                             None if jerk is None else np.array(jerk), samples=2001)


def test_the_s_curve_of_one_joint_by_hand():
    # v=1, a=1, j=2, d=1: t_j=0.5, the velocity limit is not reached, the acceleration is:
    # t_a = (sqrt(0.25 + 4) - 1.5) / 2, duration 4 t_j + 2 t_a
    move = time_point_to_point([0.0], [1.0], MotionLimits([1.0], [1.0], [2.0]))
    hold = (np.sqrt(4.25) - 1.5) / 2
    assert move.duration == pytest.approx(2.0 + 2 * hold, rel=1e-12)
    # the trapezoid of the same move: 1 s up to 1 m/s, 1 s down
    move = time_point_to_point([0.0], [1.0], MotionLimits([1.0], [1.0]))
    assert move.duration == pytest.approx(2.0, rel=1e-12)
    positions = move.sample(np.array([0.5, 1.0, 1.5]))[0][:, 0]
    np.testing.assert_allclose(positions, [0.125, 0.5, 0.875])


def test_bad_limits_and_positions_name_the_field_and_joint():
    with pytest.raises(JointError, match=r"acceleration\[1\]"):
        MotionLimits([1.0, 1.0], [1.0, 0.0])
    with pytest.raises(JointError, match=r"jerk\[0\]"):
        MotionLimits([1.0], [1.0], [float("nan")])
    with pytest.raises(JointError, match="acceleration"):
        MotionLimits([1.0, 1.0], [1.0])
    with pytest.raises(JointError, match=r"goal\[1\]"):
        time_point_to_point([0.0, 0.0], [1.0, float("inf")], MotionLimits([1.0, 1.0], [1.0, 1.0]))
    with pytest.raises(JointError, match="start"):
        time_point_to_point([0.0], [1.0, 1.0], MotionLimits([1.0, 1.0], [1.0, 1.0]))


def test_times_are_clipped_to_the_move_and_nan_is_an_error():
    move = time_point_to_point([0.0], [1.0], MotionLimits([1.0], [1.0]))
    positions, velocities, _ = move.sample(np.array([-1.0, 0.5, 3.0]))
    np.testing.assert_allclose(positions[:, 0], [0.0, 0.125, 1.0])
    assert velocities[0, 0] == 0 and velocities[2, 0] == 0
    assert move.sample(1.0)[0].shape == (1, 1)
    with pytest.raises(InvalidTimeError, match="NaN"):
        move.sample(np.array([0.0, np.nan]))
