"""Error messages that help: near misses for unknown names, which side a query overshoots."""

import numpy as np
import pytest

from pinframes import ExtrapolationError, FrameNotFoundError, FrameTree, JointError, Pose

ARM = """<robot name="arm">
  <link name="base"/><link name="upper"/><link name="lower"/>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="joint2" type="revolute"><parent link="upper"/><child link="lower"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.fixture
def robot_tree():
    tree = FrameTree()
    tree.add("table", "world", Pose([1.0, 0.0, 0.0]))
    tree.attach_urdf(ARM, "table", prefix="panda/")
    return tree


def test_an_unprefixed_joint_name_suggests_the_prefixed_joint(robot_tree):
    with pytest.raises(JointError) as info:
        robot_tree.set_joint_trajectory([0.0, 1.0], [[0.0], [0.1]], joint_names=["joint1"])
    message = str(info.value)
    assert "did you mean joint 'panda/joint1'" in message
    assert "no joint named 'joint1'" in message
    assert "frame" not in message


def test_an_unknown_frame_suggests_close_names(robot_tree):
    with pytest.raises(FrameNotFoundError) as info:
        robot_tree.pose("panda/lowr", relative_to="world")
    assert "did you mean frame 'panda/lower'" in str(info.value)
    with pytest.raises(FrameNotFoundError) as info:
        robot_tree.add("tool", "upper", Pose())
    assert "'panda/upper'" in str(info.value)


def test_a_name_far_from_every_frame_gets_no_suggestion(robot_tree):
    with pytest.raises(FrameNotFoundError) as info:
        robot_tree.pose("qqqqqqqq", relative_to="world")
    assert "did you mean" not in str(info.value)


def test_set_joint_track_calls_a_joint_a_joint(robot_tree):
    with pytest.raises(FrameNotFoundError) as info:
        robot_tree.set_joint_track("joint2", None)
    assert "no joint named 'joint2'" in str(info.value)
    assert "did you mean joint 'panda/joint2'" in str(info.value)


@pytest.mark.parametrize(("times", "expected"), [
    ([-1.5, 1.0], "1.5 s before its first keyframe"),
    ([1.0, 4.25], "2.25 s after its last keyframe"),
    ([-0.5, 4.0], "0.5 s before its first keyframe and 2 s after its last keyframe"),
])
def test_extrapolation_error_says_which_side_and_by_how_much(times, expected):
    tree = FrameTree()
    tree.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 2.0]))
    with pytest.raises(ExtrapolationError) as info:
        tree.pose("a", "world", times=times, extrapolation="error")
    assert expected in str(info.value)
    assert info.value.frame == "a"
    held = tree.pose("a", "world", times=times)  # the default policy holds the ends
    np.testing.assert_allclose(held.translation[:, 0], np.clip(times, 0.0, 2.0) / 2.0)
