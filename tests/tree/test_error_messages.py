"""Error messages that help: near misses for unknown names, which side a query overshoots."""

import numpy as np
import pytest

from pinframes import (
    DataNotFoundError,
    ExtrapolationError,
    FileFormatError,
    FrameNotFoundError,
    FrameTree,
    JointError,
    JointNotFoundError,
    NameNotFoundError,
    Pose,
    SpatialData,
    read_joint_trajectory,
    read_scene,
)

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
    with pytest.raises(JointNotFoundError) as info:
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


def test_every_lookup_that_misses_is_one_kind_a_key_error(robot_tree):
    robot_tree.assign_data("seam", SpatialData([[0.0, 0.0, 0.0]]), "table")
    misses = {
        FrameNotFoundError: [lambda: robot_tree.pose("panda/lowr"),
                             lambda: robot_tree.joint_of("panda/lowr")],
        JointNotFoundError: [
            lambda: robot_tree.set_joint_trajectory([0.0], [[0.0]], ["panda/joint3"]),
            lambda: robot_tree.replace_joint_trajectory("panda/joint3", None),
            lambda: robot_tree.joint_trajectory("panda/joint3"),
            lambda: robot_tree.jacobian("panda/lower", "world", [0.0], ["panda/joint3"])],
        DataNotFoundError: [lambda: robot_tree.get_data("sean"),
                            lambda: robot_tree.data_frame("sean"),
                            lambda: robot_tree.delete_data("sean")],
    }
    for kind, calls in misses.items():
        for call in calls:
            with pytest.raises(kind) as info:
                call()
            assert isinstance(info.value, NameNotFoundError)
            assert isinstance(info.value, KeyError)
            assert "did you mean" in str(info.value)
    # unknown joints stay JointErrors (ValueErrors), as they were
    assert issubclass(JointNotFoundError, JointError) and issubclass(JointError, ValueError)
    assert robot_tree.joint_trajectory("panda/joint1") is None  # known, never driven


def test_trajectory_file_errors_name_the_joint_and_the_line(tmp_path):
    path = tmp_path / "run.csv"
    for text, line in [("time_s,j1,j2\n0,0,0\n# a comment\n1,0,nan\n", "line 4"),
                       ("time_s,j1,j2\n0,0,0\n1,0,abc\n", "line 3")]:
        path.write_text(text)
        with pytest.raises(FileFormatError) as info:
            read_joint_trajectory(path)
        assert info.value.joint == "j2" and info.value.frame is None
        assert info.value.field == line
        assert str(info.value).startswith(f"{path}: joint 'j2': field '{line}': ")
    path.write_text("time_s,j1\n0,0\n\n0,1\n")  # the second sample is on line 4
    with pytest.raises(FileFormatError, match="not after the one at line 2") as info:
        read_joint_trajectory(path)
    assert info.value.field == "line 4"
    npz = tmp_path / "run.npz"
    np.savez(npz, times=np.array([0.0, 1.0, 2.0]), positions=np.array([[0.0], [0.0], [np.inf]]),
             joint_names=np.array(["j1"]))
    with pytest.raises(FileFormatError) as info:
        read_joint_trajectory(npz)
    assert info.value.joint == "j1" and info.value.field == "sample 2"  # index, as numpy's


def test_a_scene_notes_a_referenced_file_once(tmp_path):
    (tmp_path / "arm.urdf").write_text(ARM.replace('<link name="lower"/>', ""))
    (tmp_path / "scene.yaml").write_text(
        "pinframes_scene: 1\nrobots:\n  - {name: arm, urdf: arm.urdf, parent: world}\n")
    with pytest.raises(FileFormatError) as info:
        read_scene(tmp_path / "scene.yaml")
    message = str(info.value)
    assert message.count("referenced by") == 1, message
    assert "joint 'joint2'" in message and "robots[0].urdf" in message
