"""Point-to-point moves last what Ruckig (called directly) gives for the same limits, and
the planned samples keep every joint within its velocity and acceleration limits."""

from __future__ import annotations

import numpy as np
import pytest
import ruckig

import pinframes
from program_cells import ACCELERATION, ROBOT_URDF, START, cell, limit_shares, limits
from robot_checks import urdf_velocity_limits


def _ruckig_duration(start, goal, velocity, acceleration, jerk=None) -> float:
    count = len(start)
    generator = ruckig.Ruckig(count)
    request = ruckig.InputParameter(count)
    request.current_position, request.target_position = list(start), list(goal)
    request.max_velocity, request.max_acceleration = list(velocity), list(acceleration)
    request.max_jerk = list(jerk) if jerk is not None else [float("inf")] * count
    trajectory = ruckig.Trajectory(count)
    generator.calculate(request, trajectory)
    return float(trajectory.duration)


GOALS = [np.array([0.3, 0.4, -0.2, 0.1, 0.7, 0.2]), np.array([-1.2, 0.1, 0.3, 1.0, -0.5, 2.0]),
         np.array([0.0, 0.31, -0.3, 0.0, 0.8, 0.0])]


@pytest.mark.parametrize("goal", GOALS)
@pytest.mark.parametrize("jerk", [None, 40.0])
def test_duration_is_ruckigs(goal, jerk):
    tree = cell()
    given = limits(tree)
    if jerk is not None:
        for record in given.values():
            record["jerk"] = jerk
    program = pinframes.WeldProgram(tree, "tcp", limits=given, start=START)
    program.move_joints(dict(zip(program.joint_names, goal, strict=True)), name="ptp")
    motion = program.plan(step=0.001)
    velocity = [urdf_velocity_limits(ROBOT_URDF)[f"joint_{i}"] for i in range(1, 7)]
    expected = _ruckig_duration(START, goal, velocity, [ACCELERATION] * 6,
                                None if jerk is None else [jerk] * 6)
    record = motion.move("ptp")
    # the move is stretched onto whole steps: at most one step longer
    assert expected <= record.duration_s + 1e-9
    assert record.duration_s <= max(expected * 1.01, expected + 0.001 + 1e-9)
    np.testing.assert_allclose(motion.positions[-1], goal, atol=1e-9)
    np.testing.assert_allclose(motion.positions[0], START, atol=1e-12)


def test_samples_within_limits_by_finite_differences():
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    for number, goal in enumerate(GOALS):
        program.move_joints(list(goal), name=f"ptp {number}")
    program.wait(0.2)
    step = 0.004
    motion = program.plan(step=step)
    positions = motion.positions
    velocity, acceleration = limit_shares(positions, step)
    assert velocity <= 1.01 and acceleration <= 1.01
    # the fastest joint comes near its limit somewhere: the moves are not needlessly slow
    assert max(velocity, acceleration) > 0.9
    # rest to rest: at every move's end the joints stand still
    for record in motion.moves:
        row = round(record.end_s / step)
        np.testing.assert_allclose(motion.velocities[row], 0.0, atol=1e-9)
    # the reported rates agree with the positions
    np.testing.assert_allclose(motion.velocities[1:-1],
                               (positions[2:] - positions[:-2]) / (2 * step), atol=0.02)
    assert motion.cycle_time == pytest.approx(motion.moves[-1].end_s)
