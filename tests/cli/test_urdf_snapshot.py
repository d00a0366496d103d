"""A URDF is the tree at one time: written at t, loaded by Pinocchio with the joint values
written beside it, every frame sits where ``tree.pose`` puts it at t.

The joint-state file is read with the csv module and turned into Pinocchio's q here, by
Pinocchio's own joint indices; nothing of pinframes is used on the loading side.
"""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes import UnsupportedFeatureError
from pinframes.formats.urdf import joint_state_path

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell" / "scene.yaml"


def _joint_values(path: Path) -> dict[str, float]:
    with path.open(newline="") as handle:
        rows = [row for row in csv.reader(handle) if row and not row[0].startswith("#")]
    header, (values,) = rows[0], rows[1:]
    assert header[0] == "time_s"  # the one joint trajectory CSV: seconds (no reference time)
    return {name: float(value) for name, value in zip(header[1:], values[1:], strict=True)}


def _configuration(model: pin.Model, urdf: Path, values: dict[str, float]) -> np.ndarray:
    """q from joint values by joint name; mimic joints from the URDF's <mimic> elements."""
    for joint in ET.parse(urdf).getroot().iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            values[joint.get("name")] = (float(mimic.get("multiplier", 1.0))
                                         * values[mimic.get("joint")]
                                         + float(mimic.get("offset", 0.0)))
    q = pin.neutral(model)
    for name, value in values.items():
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 2:  # continuous joint: cos, sin
            q[joint.idx_q:joint.idx_q + 2] = np.cos(value), np.sin(value)
        else:
            q[joint.idx_q] = value
    return q


def _frames_in_pinocchio(urdf: Path, values: dict[str, float]) -> dict[str, np.ndarray]:
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    pin.framesForwardKinematics(model, data, _configuration(model, urdf, values))
    return {model.frames[i].name: data.oMf[i].homogeneous for i in range(model.nframes)
            if model.frames[i].type == pin.FrameType.BODY}


@pytest.mark.parametrize("time", [5.0, 5.3])
def test_urdf_at_a_time_with_its_joint_values_is_the_tree_at_that_time(tmp_path, time):
    tree = pinframes.read(CELL)
    assert tree.joints and any(tree.is_moving(f) for f in tree.frames[1:])
    out = tmp_path / "cell.urdf"
    pinframes.write(tree, out, time=time)
    values = _joint_values(joint_state_path(out))
    assert set(values) == {name for name, joint in tree.joints.items() if joint.is_actuated}
    placed = _frames_in_pinocchio(out, values)
    assert set(placed) == set(tree.frames)
    for frame in tree.frames:
        expected = tree.pose(frame, tree.root, times=[time]).matrix.reshape(-1, 4, 4)[0]
        np.testing.assert_allclose(placed[frame], expected, atol=1e-9, err_msg=frame)


def test_a_urdf_reads_back_with_the_joint_values_beside_it(tmp_path, run_cli):
    tree = pinframes.read(CELL)
    out = tmp_path / "cell.urdf"
    pinframes.write(tree, out, time=5.0)
    # Pinocchio with the values of cell.joints.csv put in by hand, vs pinframes reading both
    placed = _frames_in_pinocchio(out, _joint_values(joint_state_path(out)))
    read_back = pinframes.read_urdf(out)
    for frame in read_back.frames:
        pose = read_back.pose(frame, read_back.root)  # the one sample time: 5 s
        np.testing.assert_allclose(pose.matrix.reshape(-1, 4, 4)[0], placed[frame],
                                   atol=1e-9, err_msg=frame)
    np.testing.assert_allclose(read_back.joint_trajectory("robot/joint_1").times, [5e9])
    without = pinframes.read_urdf(out, joint_state=False)
    assert all(without.joint_trajectory(name) is None for name in without.joints)
    # the command line reads the pair too: the tip where it was at 5 s, not at joint values 0
    result = run_cli("pose", out, "torch_tcp", "-r", "robot_base", "-f", "json")
    assert result.returncode == 0, result.stderr
    tip = np.linalg.inv(placed["robot_base"]) @ placed["torch_tcp"]
    np.testing.assert_allclose(json.loads(result.stdout)["poses"][0]["x_m"], tip[0, 3],
                               atol=1e-9)


def test_frozen_joints_need_no_joint_values(tmp_path):
    tree = pinframes.read(CELL)
    out = tmp_path / "cell.urdf"
    pinframes.write(tree, out, time=5.0, freeze_joints=True)
    assert not joint_state_path(out).exists()
    placed = _frames_in_pinocchio(out, {})
    assert pin.buildModelFromUrdf(str(out)).nq == 0  # every joint fixed
    for frame in tree.frames:
        expected = tree.pose(frame, tree.root, times=[5.0]).matrix.reshape(-1, 4, 4)[0]
        np.testing.assert_allclose(placed[frame], expected, atol=1e-9, err_msg=frame)


def test_a_moving_tree_without_a_time_is_an_error_naming_what_moves(tmp_path, run_cli):
    tree = pinframes.read(CELL)
    out = tmp_path / "cell.urdf"
    with pytest.raises(UnsupportedFeatureError) as info:
        pinframes.write(tree, out)
    message = str(info.value)
    joint = repr(next(iter(tree.joints)))
    assert "'positioner'" in message and joint in message and "time=" in message
    assert info.value.field == "time"
    result = run_cli("convert", CELL, out)
    assert result.returncode == 1
    assert "--time" in result.stderr and "'positioner'" in result.stderr
    assert joint in result.stderr
    assert list(tmp_path.iterdir()) == []  # neither the URDF nor a joint-state file
