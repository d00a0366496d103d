"""The clearance along a program, between samples too: a fast move through a plate thinner
than the tool's step between two samples is reported, the same move beside it is not, and
``strict=True`` refuses it naming the move."""

from __future__ import annotations

import numpy as np
import pytest

import pinframes
from program_cells import START, cell, limits, tool_placements

TIP_RADIUS = 0.001
PLATE = 0.0005  # thick, metres: less than the tool's 2-4 mm step between samples


def _plan(plate_offset: float, strict: bool = False, margin: float = 0.0
          ) -> pinframes.Motion:
    tree = cell()
    tree.add_geometry("tcp", pinframes.Sphere(TIP_RADIUS))
    start = tool_placements(START)[0]
    end = start.translation + np.array([0.0, 0.3, 0.0])
    middle = (start.translation + end) / 2
    # a plate across the line (its normal along the travel), or beside it
    tree.add("plate", "world", pinframes.Pose(middle + np.array([plate_offset, 0.0, 0.0])))
    tree.add_geometry("plate", pinframes.Box([0.04, PLATE, 0.04]))
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree, 30.0), start=START)
    program.move_linear(pinframes.Pose(end, start.rotation), speed=1.0, name="through")
    program.move_linear(pinframes.Pose(end + np.array([0.0, 0.0, 0.1]), start.rotation),
                        speed=0.5, name="up")  # away from the plate
    return program.plan(check=dict(a="tcp", b="plate", margin=margin), strict=strict)


def test_samples_straddle_the_plate():
    """The premise: no sample of the move is inside the plate, the steps jump over it."""
    motion = _plan(0.0)
    record = motion.move("through")
    origins = np.array([placement.translation for placement in tool_placements(
        motion.positions[round(record.start_s / 0.004):round(record.end_s / 0.004)])])
    middle = (origins[0, 1] + 0.15)
    gaps = np.abs(origins[:, 1] - middle)
    assert gaps.min() > TIP_RADIUS + PLATE / 2  # every sample clear of the plate
    assert np.diff(origins[:, 1]).max() > 2 * (TIP_RADIUS + PLATE / 2)


def test_a_move_through_the_plate_is_reported():
    motion = _plan(0.0)
    assert [record.move for record in motion.collisions] == ["through"]
    found = motion.collisions[0]
    assert (found.frame_a, found.frame_b) == ("tcp", "plate")
    assert found.distance <= 0.0
    record = motion.move("through")
    assert record.start_s < found.time_s < record.end_s


def test_a_move_beside_the_plate_is_not():
    assert _plan(0.05).collisions == ()
    # the margin counts: 0.05 m beside it (less the tip and half the plate's width) is
    # closer than 0.04 m
    near = _plan(0.05, margin=0.04)
    assert [record.move for record in near.collisions] == ["through"]
    assert near.collisions[0].distance == pytest.approx(0.05 - 0.02 - TIP_RADIUS, abs=2e-3)


def test_strict_refuses_the_collision_naming_the_move():
    with pytest.raises(pinframes.CollisionError, match="move 'through'"):
        _plan(0.0, strict=True)
