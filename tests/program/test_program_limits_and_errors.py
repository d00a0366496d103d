"""Where the limits come from (the URDF's velocities, ``limits=`` by tree or URDF joint
names), a joint without an acceleration limit, and the errors that name the move."""

from __future__ import annotations

import numpy as np
import pytest

import pinframes
from program_cells import START, cell, limits, tool_placements


def test_a_joint_without_an_acceleration_limit_is_named():
    tree = cell()
    given = limits(tree)
    del given["joint_4"]
    with pytest.raises(pinframes.JointError, match=r"robot/joint_4.*acceleration"):
        pinframes.WeldProgram(tree, "tcp", limits=given, start=START)
    with pytest.raises(pinframes.JointError, match="acceleration"):
        pinframes.WeldProgram(tree, "tcp", start=START)


def test_limits_by_tree_name_replace_the_urdf_velocity():
    tree = cell()
    given = limits(tree)
    given["robot/joint_1"] = {"velocity": 0.5, "acceleration": 2.0, "jerk": None}
    program = pinframes.WeldProgram(tree, "tcp", limits=given, start=START)
    assert program.limits.velocity[0] == 0.5
    assert program.limits.acceleration[0] == 2.0
    assert program.limits.velocity[1] == pytest.approx(3.3161256)  # the URDF's
    program.move_joints({"robot/joint_1": 1.0}, name="turn")
    motion = program.plan()
    assert np.abs(motion.velocities[:, 0]).max() == pytest.approx(0.5, rel=1e-3)
    assert motion.move("turn").duration_s == pytest.approx(1.0 / 0.5 + 0.5 / 2.0, abs=0.005)


def test_a_limit_that_is_no_positive_number_is_refused():
    tree = cell()
    given = limits(tree)
    given["joint_2"] = {"acceleration": -1.0}
    with pytest.raises(pinframes.JointError, match=r"joint_2.*positive"):
        pinframes.WeldProgram(tree, "tcp", limits=given, start=START)


def test_unknown_targets_name_the_move():
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.move_joints({"robot/joint_9": 0.1}, name="first")
    with pytest.raises(pinframes.JointError, match=r"joint_9.*move 'first'"):
        program.plan()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.move_joints("no_such_state", name="second")
    with pytest.raises(pinframes.NameNotFoundError, match="move 'second'"):
        program.plan()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    program.move_joints({"robot/joint_2": 3.0}, name="third")
    with pytest.raises(pinframes.JointError, match=r"move 'third'.*outside the limits"):
        program.plan()
    with pytest.raises(pinframes.FrameNotFoundError):
        program.weld("no_seam")


def test_strict_names_the_move_whose_target_is_out_of_reach():
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    start = tool_placements(START)[0]
    along_x = np.array([1.0, 0.0, 0.0])
    program.move_linear(pinframes.Pose(start.translation + 0.1 * along_x, start.rotation),
                        speed=0.2, name="fine")
    # the robot reaches about 0.24 m further along x
    program.move_linear(pinframes.Pose(start.translation + 0.3 * along_x, start.rotation),
                        speed=0.2, name="too far")
    with pytest.raises(pinframes.TargetNotReachedError, match="move 'too far'"):
        program.plan(strict=True)
    motion = program.plan()  # without strict: the samples out of reach are marked
    assert not motion.all_reached
    record = motion.move("too far")
    first_missed = motion.seconds[~motion.reached][0]
    assert record.start_s < first_missed <= record.end_s
    assert motion.reached[: round(motion.move("fine").end_s / 0.004) + 1].all()


def test_waits_hold_and_moves_chain():
    tree = cell()
    program = pinframes.WeldProgram(tree, "tcp", limits=limits(tree), start=START)
    assert program.wait(0.5, name="hold") is program
    motion = program.plan(step=0.01)
    assert len(motion) == 51 and motion.cycle_time == pytest.approx(0.5)
    np.testing.assert_array_equal(motion.positions, np.broadcast_to(START, (51, 6)))
    with pytest.raises(pinframes.NameNotFoundError, match="the moves are 'hold'"):
        motion.move("no such move")
    with pytest.raises(pinframes.InvalidDataError, match="already named 'hold'"):
        program.wait(1.0, name="hold")
