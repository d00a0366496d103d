"""Timing along a joint path against TOPP-RA (``toppra``, called directly) and by hand."""

from __future__ import annotations

import logging

import numpy as np
import pytest
import toppra
import toppra.algorithm
import toppra.constraint
from ruckig import InputParameter, Result, Ruckig, Trajectory
from scipy.interpolate import CubicSpline

from pinframes.errors import JointError
from pinframes.kinematics.timing import MotionLimits, time_along_path

logging.getLogger("toppra").setLevel(logging.ERROR)


def toppra_duration(positions, parameters, velocity, acceleration) -> float:
    """TOPP-RA's duration on its own spline through the samples, the samples its grid."""
    path = toppra.SplineInterpolator(parameters, positions)
    constraints = [
        toppra.constraint.JointVelocityConstraint(np.stack([-velocity, velocity], axis=1)),
        toppra.constraint.JointAccelerationConstraint(np.stack([-acceleration, acceleration],
                                                               axis=1))]
    problem = toppra.algorithm.TOPPRA(constraints, path, gridpoints=parameters,
                                      parametrizer="ParametrizeConstAccel")
    return float(problem.compute_trajectory(0, 0).duration)


def random_path(rng: np.random.Generator, joints: int, samples: int):
    """A smooth joint path through a few random waypoints, sampled at uneven parameters."""
    steps = rng.uniform(0.5, 1.5, samples - 1)
    parameters = np.concatenate([[0.0], np.cumsum(steps)]) * 0.3 / steps.sum()
    waypoints = rng.uniform(-1.5, 1.5, (5, joints))
    positions = CubicSpline(np.linspace(0, 0.3, 5), waypoints, bc_type="clamped")(parameters)
    velocity = rng.uniform(0.5, 3, joints)
    acceleration = rng.uniform(1, 10, joints)
    return positions, parameters, velocity, acceleration


def check_motion(timing, positions, parameters, velocity, acceleration, *, speed=None,
                 tolerance=0.01, samples=20001):
    """Velocities and accelerations from finite differences of the sampled positions within
    the limits (to ``tolerance``), rest at both ends, the samples passed at their times."""
    seconds = np.linspace(0, timing.duration, samples)
    step = seconds[1] - seconds[0]
    sampled, velocities, accelerations = timing.sample(seconds)
    speeds = np.diff(sampled, axis=0) / step
    rates = np.diff(speeds, axis=0) / step
    assert np.all(np.abs(speeds) <= velocity * (1 + tolerance))
    assert np.all(np.abs(rates) <= acceleration * (1 + tolerance))
    assert np.all(np.abs(velocities) <= velocity * (1 + tolerance))
    assert np.all(np.abs(accelerations) <= acceleration * (1 + tolerance))
    # the velocities are the derivatives of the positions (their mean over a step)
    np.testing.assert_allclose(speeds, (velocities[1:] + velocities[:-1]) / 2,
                               atol=step * acceleration.max())
    np.testing.assert_allclose(velocities[[0, -1]], 0, atol=1e-12)
    np.testing.assert_allclose(sampled[[0, -1]], positions[[0, -1]], atol=1e-12)
    at_samples = timing.sample(timing.passing_times)[0]
    np.testing.assert_allclose(at_samples, positions, atol=1e-9)
    path_parameter, path_speed = timing.parameter(seconds)
    assert np.all(np.diff(path_parameter) >= 0)
    assert path_parameter[0] == parameters[0]
    assert path_parameter[-1] == pytest.approx(parameters[-1], abs=1e-12)
    np.testing.assert_allclose(np.diff(path_parameter) / step,
                               (path_speed[1:] + path_speed[:-1]) / 2,
                               atol=step * np.abs(np.diff(path_speed)).max() / step + 1e-9)
    if speed is not None:
        assert path_speed.max() <= speed * (1 + 1e-9)
    return seconds, sampled


@pytest.mark.parametrize(("joints", "samples"), [(1, 60), (2, 150), (6, 300), (7, 200)])
def test_durations_near_toppra_and_every_limit_kept(joints, samples):
    rng = np.random.default_rng(4343 + joints)
    differences = []
    for _ in range(3):
        positions, parameters, velocity, acceleration = random_path(rng, joints, samples)
        timing = time_along_path(positions, parameters, MotionLimits(velocity, acceleration))
        reference = toppra_duration(positions, parameters, velocity, acceleration)
        differences.append(timing.duration / reference - 1)
        check_motion(timing, positions, parameters, velocity, acceleration)
    assert max(np.abs(differences)) < 0.03, differences


@pytest.mark.parametrize(("samples", "error"), [(400, 3e-6), (40, 3e-3)])
def test_between_samples_the_joints_stay_on_the_path_they_sample(samples, error):
    # the path: scipy's spline through five waypoints; its samples are all the timing sees.
    # Between them the error of the cubic goes as the cube of the samples' spacing
    rng = np.random.default_rng(7)
    waypoints = rng.uniform(-1.5, 1.5, (5, 6))
    curve = CubicSpline(np.linspace(0, 0.3, 5), waypoints, bc_type="clamped")
    parameters = np.linspace(0, 0.3, samples)
    timing = time_along_path(curve(parameters), parameters,
                             MotionLimits(np.full(6, 2.0), np.full(6, 5.0)))
    seconds = np.linspace(0, timing.duration, 3001)
    path_parameter, _ = timing.parameter(seconds)
    sampled = timing.sample(seconds)[0]
    assert np.abs(sampled - curve(path_parameter)).max() < error


def test_a_straight_move_at_a_parameter_speed_is_a_trapezoid_as_ruckig_times_it():
    # one joint along q = 2 s: at most 0.5 parameter per s (1 rad/s), 4 rad/s^2 -> Ruckig's
    # trapezoid of the same joint move with v = 1, a = 4
    parameters = np.linspace(0.0, 1.5, 3001)
    positions = 2 * parameters[:, None]
    limits = MotionLimits([10.0], [4.0])
    timing = time_along_path(positions, parameters, limits, max_parameter_speed=0.5)
    inputs = InputParameter(1)
    inputs.current_position, inputs.target_position = [0.0], [3.0]
    inputs.max_velocity, inputs.max_acceleration, inputs.max_jerk = [1.0], [4.0], [np.inf]
    trajectory = Trajectory(1)
    assert Ruckig(1).calculate(inputs, trajectory) == Result.Working
    assert timing.duration == pytest.approx(trajectory.duration, rel=1e-3)
    check_motion(timing, positions, parameters, np.array([1.0]), np.array([4.0]), speed=0.5)
    # without the parameter speed the joint's own limits take over: 10 rad/s is reached
    fast = time_along_path(positions, parameters, limits)
    assert fast.duration == pytest.approx(3.0 / 10.0 + 10.0 / 4.0 if 3.0 * 4 >= 100
                                          else 2 * np.sqrt(3.0 / 4.0), rel=1e-3)


@pytest.mark.parametrize("samples", [2, 3])
def test_two_or_three_samples_and_a_joint_that_stays(samples):
    parameters = np.linspace(0.0, 0.2, samples)
    positions = np.stack([np.linspace(0.0, 1.0, samples), np.full(samples, 0.3)], axis=1)
    velocity, acceleration = np.array([1.0, 1.0]), np.array([2.0, 1e-3])
    timing = time_along_path(positions, parameters, MotionLimits(velocity, acceleration))
    # a straight joint line: joint 0 alone from rest to rest, v = 1 reached after 0.5 rad
    assert timing.duration == pytest.approx(1.0 + 1.0 / 2.0, rel=0.02)
    _, sampled = check_motion(timing, positions, parameters, velocity, acceleration)
    assert np.all(sampled[:, 1] == 0.3)


def test_limits_of_very_different_magnitudes():
    rng = np.random.default_rng(11)
    positions, parameters, _, _ = random_path(rng, 3, 300)
    velocity, acceleration = np.array([1e-2, 5.0, 50.0]), np.array([1e2, 1e-1, 5.0])
    timing = time_along_path(positions, parameters, MotionLimits(velocity, acceleration))
    reference = toppra_duration(positions, parameters, velocity, acceleration)
    assert timing.duration == pytest.approx(reference, rel=0.03)
    check_motion(timing, positions, parameters, velocity, acceleration)


def test_joints_that_stay_need_a_parameter_speed():
    parameters = np.linspace(0.0, 1.0, 11)
    positions = np.zeros((11, 2))
    with pytest.raises(JointError, match="max_parameter_speed"):
        time_along_path(positions, parameters, MotionLimits([1.0, 1.0], [1.0, 1.0]))
    timing = time_along_path(positions, parameters, MotionLimits([1.0, 1.0], [1.0, 1.0]),
                             max_parameter_speed=0.5)
    # nothing limits the path's acceleration: at 0.5 per s but on the first and last of the
    # 200 steps it is timed on (a path of fewer segments gets points between its samples)
    assert timing.duration == pytest.approx(1.0 / 0.5 + 2 * 0.005 / 0.5, rel=1e-9)


def test_bad_paths_name_the_field():
    limits = MotionLimits([1.0, 1.0], [1.0, 1.0])
    positions = np.zeros((3, 2))
    positions[:, 0] = [0.0, 1.0, 2.0]
    with pytest.raises(JointError, match=r"path_parameter\[2\]"):
        time_along_path(positions, [0.0, 1.0, 1.0], limits)
    with pytest.raises(JointError, match=r"positions\[1\]"):
        time_along_path([[0.0, 0.0], [np.nan, 0.0], [1.0, 0.0]], [0.0, 1.0, 2.0], limits)
    with pytest.raises(JointError, match="positions"):
        time_along_path(positions[:, :1], [0.0, 1.0, 2.0], limits)
    with pytest.raises(JointError, match="path_parameter"):
        time_along_path(positions, [0.0, 1.0], limits)
    with pytest.raises(JointError, match="max_parameter_speed"):
        time_along_path(positions, [0.0, 1.0, 2.0], limits, max_parameter_speed=0.0)
