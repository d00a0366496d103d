"""A weld: to the approach point, down the torch's z to the seam, along the seam on its own
times or at a speed, back up; the tool on each line and on the seam to 0.1 mm (Pinocchio's
forward kinematics called directly, at the samples and halfway between them)."""

from __future__ import annotations

import itertools

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from program_cells import START, cell, distance_to_segment, limits, tool_origins, with_midpoints

STEP = 0.004
SEAM_START = np.array([0.55, -0.1, 0.3])
SEAM_END = np.array([0.55, 0.1, 0.3])


def _welding_cell(arc: bool = False) -> tuple[pinframes.FrameTree, np.ndarray]:
    """The test cell with a seam of 0.2 m travelled in 10 s (a straight line, or a
    quarter circle), and a torch target pointing down into the work; its polyline."""
    tree = cell()
    if arc:
        angles = np.linspace(-np.pi / 4, np.pi / 4, 40)
        points = np.column_stack([0.45 + 0.13 * np.cos(angles), 0.13 * np.sin(angles) - 0.05,
                                  np.full(40, 0.3)])
    else:
        points = np.linspace(SEAM_START, SEAM_END, 2)
    seconds = np.linspace(0.0, 10.0, points.shape[0])
    travel_along_y = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    # the seam frame: x along the travel (the world's y), y across it (the world's -x)
    tree.add("seam_point", "world", pinframes.Pose(points, travel_along_y, times=seconds))
    tree.add("torch_target", "seam_point", pinframes.Pose.from_xyz_rpy(roll=np.pi))
    return tree, points


def _distance_to_polyline(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    return np.min([distance_to_segment(points, start, end)
                   for start, end in itertools.pairwise(polyline)], axis=0)


def _rows(motion: pinframes.Motion, name: str) -> slice:
    record = motion.move(name)
    return slice(round(record.start_s / STEP), round(record.end_s / STEP) + 1)


@pytest.mark.parametrize("arc", [False, True])
def test_tool_on_the_seam_and_the_approach_lines(arc):
    tree, polyline = _welding_cell(arc)
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.weld("seam_point", torch="torch_target", approach=0.05, retract=0.04, name="w")
    program.move_joints(list(START), name="home")
    motion = program.plan(step=STEP)
    assert motion.all_reached
    assert [(record.name, record.kind) for record in motion.moves] == [
        ("w: to approach", "joints"), ("w: approach", "approach"), ("w: seam", "seam"),
        ("w: retract", "retract"), ("home", "joints")]
    seam = motion.positions[_rows(motion, "w: seam")]
    assert _distance_to_polyline(tool_origins(with_midpoints(seam)), polyline).max() < 1e-4
    up = np.array([0.0, 0.0, 1.0])  # the torch target's -z
    approach = motion.positions[_rows(motion, "w: approach")]
    distances = distance_to_segment(tool_origins(with_midpoints(approach)),
                                    polyline[0] + 0.05 * up, polyline[0])
    assert distances.max() < 1e-4
    retract = motion.positions[_rows(motion, "w: retract")]
    distances = distance_to_segment(tool_origins(with_midpoints(retract)), polyline[-1],
                                    polyline[-1] + 0.04 * up)
    assert distances.max() < 1e-4
    # the torch points down the whole seam (its z the target's, spin free)
    from program_cells import tool_placements
    axes = np.array([placement.rotation[:, 2] for placement in tool_placements(seam)])
    assert np.degrees(np.arccos(np.clip(-axes[:, 2], -1, 1))).max() < 0.01
    # on its own times: the seam lasts its 10 s, and a little for the ramps
    assert 10.0 <= motion.move("w: seam").duration_s < 10.5
    # one trajectory, continuous: no joint jumps between samples
    assert np.abs(np.diff(motion.positions, axis=0)).max() < 0.05


def test_seam_at_a_given_speed():
    tree, polyline = _welding_cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.weld("seam_point", torch="torch_target", speed=0.05, name="w")
    motion = program.plan(step=STEP)
    record = motion.move("w: seam")
    assert record.requested_speed == pytest.approx(0.05)
    assert record.reached_speed == pytest.approx(0.05, rel=0.01)
    assert record.duration_s == pytest.approx(0.2 / 0.05, rel=0.05)
    seam = motion.positions[_rows(motion, "w: seam")]
    speeds = np.linalg.norm(np.diff(tool_origins(seam), axis=0), axis=1) / STEP
    assert speeds.max() == pytest.approx(0.05, rel=0.01)
    assert _distance_to_polyline(tool_origins(with_midpoints(seam)), polyline).max() < 1e-4


def test_a_weave_moves_the_tool_across_the_seam():
    tree, _ = _welding_cell()
    weave = pinframes.Weave(0.002, 1.0, "sine")
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.weld("seam_point", torch="torch_target", weave=weave, name="w")
    motion = program.plan(step=STEP)
    assert motion.all_reached
    seam = tool_origins(motion.positions[_rows(motion, "w: seam")])
    across = SEAM_START[0] - seam[:, 0]  # the seam's y is the world's -x
    assert across.max() == pytest.approx(0.002, abs=1e-4)
    assert across.min() == pytest.approx(-0.002, abs=1e-4)
    # where the tool is along the seam, the weave's own offset (sine, 1 Hz, from the start)
    seam_seconds = (seam[:, 1] - SEAM_START[1]) / 0.02
    np.testing.assert_allclose(across, 0.002 * np.sin(2 * np.pi * seam_seconds), atol=1e-4)


def test_a_whole_weld_within_the_limits_by_finite_differences():
    """Point to point, linear and seam moves in one motion: the written positions' finite
    differences within the velocity and acceleration limits, and at rest between moves."""
    from program_cells import ACCELERATION, ROBOT_URDF, limit_shares

    tree, _ = _welding_cell(arc=True)
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.weld("seam_point", torch="torch_target", speed=0.08, name="w")
    program.move_joints(list(START), name="home")
    motion = program.plan(step=STEP)
    velocity, acceleration = limit_shares(motion.positions, STEP)
    assert velocity <= 1.01 and acceleration <= 1.01
    model = pin.buildModelFromUrdf(str(ROBOT_URDF))  # every sample within the URDF limits
    assert (motion.positions >= model.lowerPositionLimit).all()
    assert (motion.positions <= model.upperPositionLimit).all()
    for record in motion.moves:
        row = round(record.end_s / STEP)
        np.testing.assert_allclose(motion.velocities[row], 0.0, atol=1e-9)
    # the positions' differences agree with the velocities the motion reports: a central
    # difference is the mean velocity over two steps, within max|acceleration| * step of it
    middle = (motion.positions[2:] - motion.positions[:-2]) / (2 * STEP)
    assert np.abs(middle - motion.velocities[1:-1]).max() <= 1.01 * ACCELERATION * STEP
