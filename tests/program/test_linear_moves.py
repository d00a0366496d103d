"""Linear moves: the tool on the straight line to 0.1 mm at every sample and halfway
between samples (Pinocchio's forward kinematics called directly), at the requested speed
where the joints allow it, slower and within every limit where they do not."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from program_cells import (
    START,
    cell,
    distance_to_segment,
    limit_shares,
    limits,
    tool_origins,
    tool_placements,
    with_midpoints,
)

STEP = 0.004


def _program(speed: float) -> tuple[pinframes.Motion, np.ndarray, np.ndarray]:
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    start = tool_placements(START)[0]
    end = pin.SE3(pin.exp3(np.array([0.0, 0.3, 0.2])) @ start.rotation,
                  start.translation + np.array([0.05, 0.25, -0.1]))
    program.move_linear(pinframes.Pose(end.translation, end.rotation), speed=speed,
                        name="line")
    return program.plan(step=STEP), start.translation, end


@pytest.mark.parametrize("speed", [0.1, 5.0])
def test_tool_on_the_line_at_and_between_samples(speed):
    motion, start, end = _program(speed)
    assert motion.all_reached
    origins = tool_origins(with_midpoints(motion.positions))
    assert distance_to_segment(origins, start, end.translation).max() < 1e-4
    last = tool_placements(motion.positions[-1])[0]
    np.testing.assert_allclose(last.translation, end.translation, atol=1e-5)
    assert np.linalg.norm(pin.log3(last.rotation.T @ end.rotation)) < 1e-4
    # the orientation is slerped: at the middle of the path, half the turn
    along = np.linalg.norm(origins[: len(motion)] - start, axis=1) / np.linalg.norm(
        end.translation - start)
    middle = int(np.argmin(np.abs(along - 0.5)))
    turned = pin.log3(tool_placements(START)[0].rotation.T
                      @ tool_placements(motion.positions[middle])[0].rotation)
    total = pin.log3(tool_placements(START)[0].rotation.T @ end.rotation)
    np.testing.assert_allclose(turned, along[middle] * total, atol=2e-3)


def test_requested_speed_where_the_joints_allow_it():
    motion, start, end = _program(0.1)
    speeds = np.linalg.norm(np.diff(tool_origins(motion.positions), axis=0), axis=1) / STEP
    record = motion.move("line")
    assert record.requested_speed == pytest.approx(0.1)
    assert speeds.max() == pytest.approx(0.1, rel=0.01)
    assert record.reached_speed == pytest.approx(0.1, rel=0.01)
    # most of the way at that speed: the ramps are short
    assert (speeds > 0.099).mean() > 0.8
    length = np.linalg.norm(end.translation - start)
    assert record.duration_s == pytest.approx(length / 0.1, rel=0.05)


def test_too_fast_a_request_is_slowed_to_the_limits():
    motion, _, _ = _program(5.0)
    speeds = np.linalg.norm(np.diff(tool_origins(motion.positions), axis=0), axis=1) / STEP
    record = motion.move("line")
    assert record.reached_speed < 5.0
    assert speeds.max() == pytest.approx(record.reached_speed, rel=0.02)
    velocity, acceleration = limit_shares(motion.positions, STEP)
    assert velocity <= 1.01 and acceleration <= 1.01
    # some joint is at a limit: it is as fast as it may be
    assert max(velocity, acceleration) > 0.95
