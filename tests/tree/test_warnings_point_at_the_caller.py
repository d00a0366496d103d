"""Every warning pinframes gives points at the line that called pinframes (the warning's
file is this test file), not into pinframes' own modules, however deep it arises; and
libraries pinframes uses add no bare lines of their own to standard error."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from pinframes import (
    BrokenMimicWarning,
    FramesYamlWarning,
    FrameTree,
    Joint,
    JointLimitWarning,
    JointWithoutSamplesWarning,
    Pose,
    read_frames_yaml,
    read_urdf,
)

ARM = """<robot name="arm"><link name="base"/><link name="upper"/><link name="lower"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="upper"/><child link="lower"/>
    <axis xyz="0 1 0"/><mimic joint="j0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint></robot>"""


def warnings_of(call) -> list[warnings.WarningMessage]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        call()
    assert caught, "no warning"
    return caught


def assert_at_this_file(caught: list[warnings.WarningMessage], category: type[Warning]):
    mine = [warning for warning in caught if issubclass(warning.category, category)]
    assert mine, [str(warning.message) for warning in caught]
    for warning in mine:
        assert Path(warning.filename) == Path(__file__), (warning.filename, warning.message)


def robot_tree() -> FrameTree:
    tree = FrameTree()
    tree.add("mount", "world", Pose([0.0, 0.0, 0.5]))
    tree.attach_joint("arm", "mount", Joint("swing", "revolute", (0.0, 0.0, 1.0), -1.0, 1.0))
    tree.attach_joint("hand", "arm", Joint("slide", "prismatic", (1.0, 0.0, 0.0)))
    tree.add("mover", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0]))
    return tree


def test_joint_warnings_point_at_the_caller():
    tree = robot_tree()
    assert_at_this_file(warnings_of(
        lambda: tree.set_joint_trajectory([0.0, 1.0], [[0.0], [2.0]], ["swing"])),
        JointLimitWarning)
    for times in ([0.5], np.linspace(0.0, 1.0, 50)):  # the one-time and the batched paths
        fresh = robot_tree()
        assert_at_this_file(warnings_of(
            lambda fresh=fresh, times=times: fresh.pose("hand", relative_to="mover",
                                                       times=times)),
            JointWithoutSamplesWarning)


def test_file_warnings_point_at_the_caller(tmp_path):
    assert_at_this_file(warnings_of(lambda: read_urdf(ARM)), BrokenMimicWarning)
    tree = FrameTree()
    assert_at_this_file(warnings_of(lambda: tree.attach_urdf(ARM, "world")), BrokenMimicWarning)
    path = tmp_path / "frames.yaml"
    path.write_text("version: 1.0\nframes:\n  car: {relative_to: ghost, pose: {x: 1.0}}\n")
    assert_at_this_file(warnings_of(lambda: read_frames_yaml(path)), FramesYamlWarning)


def test_geometry_warnings_point_at_the_caller_and_the_library_stays_quiet(tmp_path, capfd):
    view = pytest.importorskip("pinframes.view")
    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ARM.replace("<mimic joint=\"j0\"/>", "").replace(
        '<link name="upper"/>',
        '<link name="upper"><visual><geometry><mesh filename="missing.stl"/></geometry>'
        "</visual></link>"))
    tree = read_urdf(urdf)
    capfd.readouterr()
    assert_at_this_file(warnings_of(lambda: view.load_geometry(tree)), view.GeometryWarning)
    assert "Can't find" not in capfd.readouterr().err  # yourdfpy's log line
    from_text = FrameTree()  # an XML string has no folder: its relative mesh is not found
    from_text.attach_urdf(urdf.read_text(), "world")
    assert_at_this_file(warnings_of(lambda: view.load_geometry(from_text)),
                        view.GeometryWarning)
