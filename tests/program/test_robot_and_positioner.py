"""A program for a robot and a positioner together (an SRDF group of both), moved to SRDF
group states and along a line to a mark on the positioner's table, which turns with it: the
MA2010 and D500 cell of tests/data, checked with Pinocchio's forward kinematics."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from program_cells import distance_to_segment, with_midpoints

CELL = Path(__file__).parents[1] / "data" / "ma2010_cell"
STEP = 0.004
OFFSET = np.array([0.05, 0.08, 0.1])  # m: the mark from the tool, in the table's axes


def _states() -> dict[str, dict[str, float]]:
    root = ET.parse(CELL / "cell.srdf").getroot()
    return {state.get("name"): {joint.get("name"): float(joint.get("value"))
                                for joint in state.iter("joint")}
            for state in root.iter("group_state")}


class _Cell:
    """The cell as Pinocchio reads it: placements of frames at the program's joint values."""

    def __init__(self, joint_names: tuple[str, ...]) -> None:
        self.model = pin.buildModelFromUrdf(str(CELL / "cell.urdf"))
        self.data = self.model.createData()
        self.columns = [joint_names.index(self.model.names[index])
                        for index in range(1, self.model.njoints)]

    def placements(self, frame: str, positions: np.ndarray) -> list[pin.SE3]:
        found = []
        for row in np.atleast_2d(positions):
            pin.framesForwardKinematics(self.model, self.data, row[self.columns])
            found.append(self.data.oMf[self.model.getFrameId(frame)].copy())
        return found


@pytest.fixture(scope="module")
def planned() -> tuple[pinframes.WeldProgram, pinframes.Motion, pin.SE3]:
    tree = pinframes.read_urdf(CELL / "cell.urdf", srdf=CELL / "cell.srdf")
    states = _states()
    names = [name for name in tree.joints if tree.joints[name].is_actuated]
    values = {**states["weld_ready"], **states["level"]}
    at_states = np.array([values[name] for name in names])
    pinocchio = _Cell(tuple(names))
    tool = pinocchio.placements("ma2010_tool0", at_states)[0]
    table = pinocchio.placements("d500_tool0", at_states)[0]
    tool_on_table = table.inverse() * tool
    mark = pin.SE3(tool_on_table.rotation, tool_on_table.translation + OFFSET)
    tree.add("mark", "d500_tool0", pinframes.Pose(mark.translation, mark.rotation))
    limits = {name: {"acceleration": 4.0} for name in tree.joints}
    program = pinframes.WeldProgram(tree, "ma2010_tool0", joints="cell", limits=limits)
    program.move_joints("weld_ready", name="ready")
    program.move_joints("level", name="level")
    program.move_linear("mark", speed=0.1, name="to the mark")
    return program, program.plan(step=STEP), mark


def test_group_states_are_reached(planned):
    program, motion, _ = planned
    assert len(program.joint_names) == 8  # six robot joints and two positioner joints
    states = _states()
    ready_end = round(motion.move("ready").end_s / STEP)
    for name, value in states["weld_ready"].items():
        assert motion.positions[ready_end, program.joint_names.index(name)] == \
            pytest.approx(value, abs=1e-9)
    level_end = round(motion.move("level").end_s / STEP)
    for name, value in {**states["weld_ready"], **states["level"]}.items():
        assert motion.positions[level_end, program.joint_names.index(name)] == \
            pytest.approx(value, abs=1e-9)


def test_the_line_to_a_mark_the_positioner_carries(planned):
    program, motion, mark = planned
    assert motion.all_reached
    record = motion.move("to the mark")
    rows = motion.positions[round(record.start_s / STEP):round(record.end_s / STEP) + 1]
    pinocchio = _Cell(program.joint_names)
    samples = with_midpoints(rows)
    tools = pinocchio.placements("ma2010_tool0", samples)
    tables = pinocchio.placements("d500_tool0", samples)
    on_table = np.array([(table.inverse() * tool).translation
                         for table, tool in zip(tables, tools, strict=True)])
    # on the straight line in the table's frame, from where it started to the mark
    assert distance_to_segment(on_table, on_table[0], mark.translation).max() < 1e-4
    np.testing.assert_allclose(on_table[len(rows) - 1], mark.translation, atol=1e-5)
    assert np.linalg.norm(on_table[0] - mark.translation) == pytest.approx(
        np.linalg.norm(OFFSET), abs=1e-6)
