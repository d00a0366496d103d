"""xacro robot files as ROS packages hold them (Universal Robots' ROS 2 description, the
ROS-Industrial Yaskawa packages): expanded as the ``xacro`` command expands them, and the
robots' link poses equal to Pinocchio's on that expansion."""

from __future__ import annotations

import shutil
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes import FileFormatError, UnsupportedFeatureError
from pinframes.formats.urdf import expand_xacro
from urdf.ros_packages import (
    D500_XACRO,
    MA2010_XACRO,
    MOTOMAN,
    UR_DESCRIPTION,
    UR_XACRO,
    packages_below,
    xacro_command,
)

CASES = [
    pytest.param(UR_XACRO, {"name": "ur5e", "ur_type": "ur5e"}, id="UR5e"),
    pytest.param(UR_XACRO, {"name": "arm", "ur_type": "ur10e", "tf_prefix": "left_"},
                 id="UR10e with tf_prefix"),
    pytest.param(MA2010_XACRO, {}, id="Yaskawa MA2010"),
    pytest.param(D500_XACRO, {}, id="Yaskawa MOTOPOS D500"),
]


def canonical(text: str) -> str:
    return ET.canonicalize(text, strip_text=True)


@pytest.fixture(scope="module")
def references(tmp_path_factory):
    """The ``xacro`` command's output per case, made once."""
    scratch = tmp_path_factory.mktemp("xacro")
    packages = {**packages_below(UR_DESCRIPTION.parent), **packages_below(MOTOMAN)}
    made: dict[tuple, str] = {}

    def reference(path, arguments):
        key = (path, tuple(sorted(arguments.items())))
        if key not in made:
            made[key] = xacro_command(path, arguments, packages, scratch)
        return made[key]

    return reference


@pytest.mark.parametrize(("path", "arguments"), CASES)
def test_expansion_equals_the_xacro_command(path, arguments, references):
    # $(find PKG) found among the file's ancestor folders: no package_dirs given
    assert canonical(expand_xacro(path, args=arguments)) == canonical(
        references(path, arguments))


@pytest.mark.parametrize(("path", "arguments"), CASES)
def test_link_poses_equal_pinocchio_on_the_expanded_urdf(path, arguments, references, rng):
    tree = pinframes.read_urdf(path, xacro_args=arguments)
    model = pin.buildModelFromXML(references(path, arguments))
    data = model.createData()
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    lower = np.array([tree.joints[name].lower for name in names])
    upper = np.array([tree.joints[name].upper for name in names])
    values = rng.uniform(lower, upper, size=(5, len(names)))
    tree.set_joint_trajectory(np.arange(5.0), values, names)
    links = [frame for frame in tree.frames if model.existFrame(frame)]
    assert len(links) == len(tree.frames)
    for sample, row in enumerate(values):
        q = pin.neutral(model)
        for name, value in zip(names, row, strict=True):
            q[model.joints[model.getJointId(name)].idx_q] = value
        pin.framesForwardKinematics(model, data, q)
        for link in links:
            expected = data.oMf[model.getFrameId(link)]
            pose = tree.pose(link, tree.root, times=[float(sample)])
            np.testing.assert_allclose(pose.translation[0], expected.translation, atol=1e-12)
            np.testing.assert_allclose(pose.rotation[0], expected.rotation, atol=1e-12)


def test_a_xacro_is_told_by_its_content_and_expanded_with_the_opt_in_whatever_its_name(
        tmp_path):
    renamed = tmp_path / "robot.urdf"
    shutil.copy(MA2010_XACRO, renamed)
    with pytest.raises(FileFormatError, match="xacro=True") as caught:
        pinframes.read(renamed, package_dirs=[MOTOMAN])
    assert caught.value.file == str(renamed) and caught.value.field == "xacro"
    tree = pinframes.read(renamed, package_dirs=[MOTOMAN], xacro=True)
    assert tree.name == "motoman_ma2010"
    assert len([joint for joint in tree.joints.values() if joint.is_actuated]) == 6


def test_packages_come_from_package_dirs_then_ros_package_path(tmp_path, monkeypatch):
    from xacro import substitution_args

    own_find = substitution_args._eval_find  # xacro's, restored after every expansion
    lone = tmp_path / "ma2010.xacro"
    shutil.copy(MA2010_XACRO, lone)  # no package folder above it
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    with pytest.raises(FileFormatError, match="motoman_ma2010_support") as caught:
        pinframes.read_urdf(lone)
    assert caught.value.file == str(lone)
    assert "package_dirs" in str(caught.value)
    assert len(pinframes.read_urdf(lone, package_dirs=[MOTOMAN]).joints) == 6
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(MOTOMAN))
    assert len(pinframes.read_urdf(lone).joints) == 6
    assert substitution_args._eval_find is own_find


def test_a_file_of_macros_only_says_so_and_not_that_joints_form_a_cycle():
    with pytest.raises(FileFormatError, match="xacro macros only") as caught:
        with pytest.warns(UserWarning, match="no name"):
            pinframes.read(MA2010_XACRO.with_name("ma2010_macro.xacro"))
    assert "cycle" not in str(caught.value)


def test_a_missing_argument_is_named_with_how_to_give_it():
    with pytest.raises(FileFormatError, match="--xacro-arg"):
        pinframes.read_urdf(UR_XACRO)


def test_arguments_for_a_file_that_is_no_xacro_are_refused(tmp_path):
    plain = tmp_path / "plain.urdf"
    plain.write_text('<robot name="r"><link name="a"/></robot>')
    with pytest.raises(FileFormatError, match="no xacro file") as caught:
        pinframes.read_urdf(plain, xacro_args={"name": "x"})
    assert caught.value.field == "xacro_args"


def test_without_the_xacro_package_the_error_names_it(monkeypatch):
    monkeypatch.setitem(sys.modules, "xacro", None)  # as if it were not installed
    with pytest.raises(UnsupportedFeatureError, match=r"xacro package.*pinframes\[ros\]"):
        pinframes.read_urdf(MA2010_XACRO)


def test_what_xacro_prints_becomes_one_warning_naming_the_file(tmp_path, capfd):
    (tmp_path / "offset.yaml").write_text("x: 0.5\n")
    robot = tmp_path / "robot.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     '<xacro:property name="p" value="${load_yaml(\'offset.yaml\')}"/>'
                     '<link name="a"/><link name="b"/><joint name="j" type="fixed">'
                     '<parent link="a"/><child link="b"/><origin xyz="${p[\'x\']} 0 0"/>'
                     '</joint></robot>')
    with pytest.warns(UserWarning, match=r"robot\.xacro: xacro: .*load_yaml\(\) directly"):
        tree = pinframes.read_urdf(robot)
    assert capfd.readouterr().err == ""  # nothing printed past pinframes
    np.testing.assert_allclose(tree.pose("b", "a").translation, [0.5, 0.0, 0.0])


def test_xacro_text_is_never_expanded():
    text = MA2010_XACRO.read_text()  # as a bag's /robot_description could hold it
    with pytest.raises(FileFormatError, match="xacro text") as caught:
        pinframes.FrameTree().attach_urdf(text, "world")
    assert caught.value.field == "xacro"


def test_a_urdf_that_keeps_the_namespace_needs_no_xacro(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "xacro", None)
    expanded = tmp_path / "expanded.urdf"  # as xacro writes them, the declaration kept
    expanded.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                        '<link name="a"/><link name="b"/><joint name="j" type="fixed">'
                        '<parent link="a"/><child link="b"/></joint></robot>')
    assert pinframes.read_urdf(expanded).frames == ["a", "b"]


def test_attach_urdf_and_package_dirs_are_remembered(tmp_path):
    tree = pinframes.FrameTree()
    tree.attach_urdf(MA2010_XACRO, "world", prefix="r/", package_dirs=[MOTOMAN])
    recorded = tree.frame_metadata("r/link_1_s")["geometry"]
    assert recorded.package_dirs == (str(MOTOMAN),)
    assert recorded.collision[0].mesh.startswith("package://motoman_ma2010_support/")
