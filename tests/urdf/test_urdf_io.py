"""Mounting, mimic joints, errors, trajectories and export of hand-written URDFs."""

import warnings

import numpy as np
import pinocchio as pin
import pytest
import yourdfpy

from pinframes import FrameTree, JointLimitWarning, Pose, read_urdf
from pinframes.errors import (
    FileFormatError,
    FrameExistsError,
    InvalidTimeError,
    JointError,
    ReadError,
    UnsupportedFeatureError,
)
from pinframes.formats.urdf import write_urdf

from geometry import rot_z

# A two-link arm: shoulder about z, a slider along x, and two mimic joints written before
# their primaries (Pinocchio's parser refuses this order): elbow_mimic follows shoulder,
# wrist_mimic follows elbow_mimic (a mimic of a mimic).
ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><visual><geometry><mesh filename="package://arm/base.dae"/></geometry></visual></link>
  <link name="upper"/><link name="slide"/><link name="fore"/><link name="hand"/><link name="tool"/>
  <joint name="elbow_mimic" type="revolute">
    <parent link="slide"/><child link="fore"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
    <mimic joint="shoulder" multiplier="2.0" offset="0.1"/>
    <dynamics damping="0.7"/>
  </joint>
  <joint name="wrist_mimic" type="revolute">
    <parent link="fore"/><child link="hand"/><origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
    <mimic joint="elbow_mimic" multiplier="-1.0"/>
  </joint>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 1" rpy="0 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="slider" type="prismatic">
    <parent link="upper"/><child link="slide"/><origin xyz="1 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.2" effort="10" velocity="1"/>
  </joint>
  <joint name="tool_fixed" type="fixed">
    <parent link="hand"/><child link="tool"/><origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/>
  </joint>
</robot>
"""


def expected_tool_in_base(shoulder, slider):
    """Hand-derived: rotations about z add up; lengths along the rotated x axes."""
    elbow = 2.0 * shoulder + 0.1
    wrist = -elbow
    base_upper = np.eye(4)
    base_upper[:3, :3] = rot_z(shoulder)
    base_upper[2, 3] = 1.0
    chain = base_upper
    for angle, length in [(0.0, 1.0 + slider), (elbow, 0.5), (wrist, 0.3), (np.pi / 2, 0.1)]:
        step = np.eye(4)
        step[:3, :3] = rot_z(angle)
        step[0, 3] = length
        chain = chain @ step
    return chain


def test_mimic_joints_before_their_primary_and_mimic_of_mimic():
    tree = read_urdf(ARM)
    assert tree.root == "base" and tree.name == "arm"
    assert [n for n, j in tree.joints.items() if j.is_actuated] == ["shoulder", "slider"]
    tree.set_joint_trajectory([0.0, 2.0], [[0.0, 0.0], [1.0, 0.2]])
    result = tree.pose("tool", "base", times=[0.0, 1.0, 2.0])
    for row, (shoulder, slider) in enumerate([(0.0, 0.0), (0.5, 0.1), (1.0, 0.2)]):
        np.testing.assert_allclose(result.matrix[row], expected_tool_in_base(shoulder, slider),
                                   atol=1e-12)


def test_export_keeps_joints_limits_mimic_and_link_contents_and_reloads(tmp_path):
    tree = FrameTree()
    tree.add("table", "world", Pose([[0, 0, 0], [2, 0, 0]], times=[0, 4]))
    tree.attach_urdf(ARM, "table", Pose.from_xyz_rpy(0, 0, 0.1, 0, 0, 0.3), prefix="a/")
    tree.add("torch", "a/tool", Pose([0, 0, 0.4]))
    path = tmp_path / "cell.urdf"
    with pytest.warns(UserWarning, match="no samples"):
        write_urdf(tree, path, time=2.0)
    text = path.read_text()
    assert "package://arm/base.dae" in text and 'damping="0.7"' in text
    # wrist = -1 * elbow and elbow = 2 * shoulder + 0.1: one mimic of the driven joint
    assert '<mimic joint="a/shoulder" multiplier="-2.0" offset="-0.1"' in text

    again = read_urdf(path)
    assert set(again.frames) == set(tree.frames)
    assert again.joints["a/shoulder"].upper == 1.5
    assert again.joints["a/elbow_mimic"].mimic.joint == "a/shoulder"
    assert again.joints["a/wrist_mimic"].mimic.joint == "a/shoulder"
    values = {"a/shoulder": 0.4, "a/slider": 0.15}
    again.set_joint_trajectory([0.0], [list(values.values())], list(values))
    tree.set_joint_trajectory([0.0], [list(values.values())], list(values))
    frozen = tree.pose("torch", "world", times=[2.0]).matrix[0]
    np.testing.assert_allclose(again.pose("torch", "world", times=[0.0]).matrix[0], frozen,
                               atol=1e-12)

    # Pinocchio (mimic joints as plain joints) and yourdfpy load it with equal FK.
    model = pin.buildModelFromUrdf(str(path))
    data = model.createData()
    q = pin.neutral(model)
    elbow = 2 * 0.4 + 0.1
    for name, value in {"a/shoulder": 0.4, "a/slider": 0.15, "a/elbow_mimic": elbow,
                        "a/wrist_mimic": -elbow}.items():
        q[model.joints[model.getJointId(name)].idx_q] = value
    pin.framesForwardKinematics(model, data, q)
    np.testing.assert_allclose(data.oMf[model.getFrameId("torch")].homogeneous, frozen,
                               atol=1e-12)
    # yourdfpy cannot follow a mimic of a mimic: compare the links before the wrist.
    robot = yourdfpy.URDF.load(str(path), load_meshes=False, build_scene_graph=True)
    robot.update_cfg({"a/shoulder": 0.4, "a/slider": 0.15})
    for link in ["a/slide", "a/fore"]:
        np.testing.assert_allclose(robot.get_transform(link, "world"),
                                   tree.pose(link, "world", times=[2.0]).matrix[0], atol=1e-12)


def test_two_copies_of_a_robot_in_one_tree_move_independently():
    tree = FrameTree()
    tree.attach_urdf(ARM, "world", prefix="left/")
    tree.attach_urdf(ARM, "world", Pose([0, 5, 0]), prefix="right/")
    tree.set_joint_trajectory([0.0], [[0.3, 0.0]], ["left/shoulder", "left/slider"])
    tree.set_joint_trajectory([0.0], [[-0.2, 0.1]], ["right/shoulder", "right/slider"])
    np.testing.assert_allclose(tree.pose("left/tool", "left/base", times=[0]).matrix[0],
                               expected_tool_in_base(0.3, 0.0), atol=1e-12)
    np.testing.assert_allclose(tree.pose("right/tool", "right/base", times=[0]).matrix[0],
                               expected_tool_in_base(-0.2, 0.1), atol=1e-12)
    with pytest.raises(FrameExistsError):
        tree.attach_urdf(ARM, "world", prefix="left/")


@pytest.mark.parametrize(
    ("urdf", "field"),
    [
        ("<robot name='x'><link name='a'/>", None),
        (ARM.replace('<link name="tool"/>', ""), "child.link"),
        (ARM.replace('<child link="upper"/>', '<child link="slide"/>'), "child.link"),
        (ARM.replace('joint="shoulder"', 'joint="nope"'), "mimic.joint"),
        (ARM.replace('type="prismatic"', 'type="spiral"'), "type"),
        (ARM.replace('xyz="0.3 0 0"', 'xyz="0.3 zero 0"'), "origin.xyz"),
        (ARM.replace('<link name="tool"/>', '<link name="tool"/><link name="extra"/>'), "link"),
    ],
)
def test_bad_urdfs_raise_named_errors_and_leave_the_tree_unchanged(urdf, field):
    tree = FrameTree()
    tree.add("table", "world")
    with pytest.raises(FileFormatError) as info:
        tree.attach_urdf(urdf, "table", strict=True)  # strict: a mimic of an unknown joint too
    assert info.value.file == "<urdf string>"
    assert info.value.field == field
    assert tree.frames == ["world", "table"] and tree.joints == {}


def test_missing_file_names_the_file(tmp_path):
    with pytest.raises(ReadError, match="no such file") as info:
        read_urdf(tmp_path / "missing.urdf")
    assert info.value.file.endswith("missing.urdf")


def test_trajectory_errors_and_limit_warnings():
    tree = read_urdf(ARM)
    with pytest.raises(JointError, match="shape"):
        tree.set_joint_trajectory([0, 1], [[0.0, 0.0]])
    with pytest.raises(JointError) as info:
        tree.set_joint_trajectory([0], [[0.0]], ["elbow"])
    assert "no joint named 'elbow'" in str(info.value)  # a joint, not a frame
    with pytest.raises(JointError, match="mimic"):
        tree.set_joint_trajectory([0], [[0.0]], ["elbow_mimic"])
    with pytest.raises(InvalidTimeError):
        tree.set_joint_trajectory([1, 0], [[0.0, 0.0], [0.1, 0.0]])
    with pytest.raises(JointError, match="non-finite"):
        tree.set_joint_trajectory([0], [[np.nan, 0.0]])
    with pytest.warns(JointLimitWarning, match="shoulder"):
        tree.set_joint_trajectory([0, 1], [[0.0, 0.0], [2.0, 0.1]])


def test_continuous_joints_interpolate_the_short_way_round():
    urdf = """<robot name="wheel"><link name="a"/><link name="b"/>
      <joint name="spin" type="continuous"><parent link="a"/><child link="b"/>
      <axis xyz="0 0 1"/></joint></robot>"""
    tree = read_urdf(urdf)
    tree.set_joint_trajectory([0.0, 1.0], [[3.0], [-3.0]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        middle = tree.pose("b", "a", times=[0.5]).rotation[0]
    # From 3 rad to -3 rad the short way passes through pi, not through 0.
    np.testing.assert_allclose(middle, rot_z(np.pi), atol=1e-12)


def test_floating_and_planar_joints_are_frames_at_their_origin_and_export_their_type(tmp_path):
    urdf = """<robot name="mobile"><link name="odom"/><link name="base"/><link name="box"/>
      <joint name="to_base" type="planar"><parent link="odom"/><child link="base"/>
      <origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint>
      <joint name="to_box" type="floating"><parent link="base"/><child link="box"/>
      <origin xyz="0 2 0"/></joint></robot>"""
    tree = read_urdf(urdf)
    np.testing.assert_allclose(tree.pose("box", "odom").translation, [1, 2, 0])
    tree.set_local_pose("base", Pose([[1, 0, 0], [3, 0, 0]], times=[0, 1]))
    np.testing.assert_allclose(tree.pose("box", "odom", times=[0.5]).translation, [[2, 2, 0]])
    path = tmp_path / "mobile.urdf"
    with pytest.raises(UnsupportedFeatureError, match=r"frames 'base' move.*pass time="):
        write_urdf(tree, path)  # a URDF holds one pose: no silent first keyframe
    write_urdf(tree, path, time=0.5)
    text = path.read_text()
    assert 'name="to_base" type="planar"' in text and 'name="to_box" type="floating"' in text
    assert '<origin xyz="2.0 0.0 0.0"' in text  # base at 0.5 s, halfway from x=1 to x=3
