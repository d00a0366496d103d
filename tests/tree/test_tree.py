import numpy as np
import pytest

from hardening.file_cases import joint, urdf
from pinframes import FrameTree, Pose, Subsystem
from pinframes.errors import (
    ArgumentTypeError,
    FrameExistsError,
    FrameNotFoundError,
    JointError,
    ReferenceTimeError,
    TreeStructureError,
)

from geometry import rot_z


def small_tree() -> FrameTree:
    tree = FrameTree(root="world", name="cell")
    tree.add("robot", "world", Pose([1.0, 0.0, 0.0]))
    tree.add("flange", "robot", Pose([0.0, 0.0, 1.0]))
    tree.add("torch", "flange", Pose([0.0, 0.0, 0.4]))
    tree.add("table", "world", Pose([0.0, 2.0, 0.0]))
    return tree


def test_structure_queries():
    tree = small_tree()
    assert tree.frames == ["world", "robot", "flange", "torch", "table"]
    assert tree.root == "world" and tree.name == "cell"
    assert len(tree) == 5 and "torch" in tree and "nope" not in tree
    assert tree.parent("torch") == "flange" and tree.parent("world") is None
    assert tree.children("world") == ["robot", "table"]
    assert tree.path("torch", "table") == ["torch", "flange", "robot", "world", "table"]
    np.testing.assert_allclose(tree.local_pose("torch").translation, [0, 0, 0.4])


def test_add_errors_name_the_frame_and_leave_the_tree_unchanged():
    tree = small_tree()
    before = tree.frames
    with pytest.raises(FrameExistsError) as info:
        tree.add("torch", "world")
    assert info.value.frame == "torch"
    with pytest.raises(FrameNotFoundError) as info:
        tree.add("x", "missing")
    assert info.value.field == "parent" and isinstance(info.value, KeyError)
    with pytest.raises(ArgumentTypeError):
        tree.add("y", "world", pose=np.eye(4))
    with pytest.raises(TreeStructureError):
        tree.add("", "world")
    assert tree.frames == before


def test_remove_needs_recursive_for_children_and_never_removes_the_root():
    tree = small_tree()
    with pytest.raises(TreeStructureError, match="recursive"):
        tree.remove("robot")
    with pytest.raises(TreeStructureError):
        tree.remove("world")
    tree.remove("robot", recursive=True)
    assert tree.frames == ["world", "table"]
    tree.add("robot", "world")  # the name is free again
    np.testing.assert_allclose(tree.pose("robot").translation, [0, 0, 0])


def test_rename_keeps_order_pose_metadata_and_subsystems():
    tree = small_tree()
    tree.frame_metadata("flange")["note"] = "ISO 9409"
    tree.subsystems.append(Subsystem("robot_sys", "robot", ("robot", "flange", "torch")))
    before = tree.pose("torch", "world").translation
    tree.rename("flange", "tool0")
    assert tree.frames == ["world", "robot", "tool0", "torch", "table"]
    assert tree.parent("torch") == "tool0"
    assert tree.frame_metadata("tool0") == {"note": "ISO 9409"}
    assert tree.subsystems[0].members == ("robot", "tool0", "torch")
    np.testing.assert_allclose(tree.pose("torch", "world").translation, before)
    with pytest.raises(FrameExistsError):
        tree.rename("torch", "table")
    tree.rename("world", "floor")
    assert tree.root == "floor" and tree.parent("robot") == "floor"


def test_remove_drops_members_from_subsystems():
    tree = small_tree()
    tree.subsystems.append(Subsystem("robot_sys", "robot", ("robot", "flange", "torch")))
    tree.remove("torch")
    assert tree.subsystems[0].members == ("robot", "flange")
    tree.remove("robot", recursive=True)
    assert tree.subsystems == []


def test_remove_refuses_to_leave_a_mimic_joint_without_the_joint_it_follows():
    tree = FrameTree()
    tree.attach_urdf(urdf(joint("j1", "a", "b")
                          + joint("j2", "a", "c", inner='<mimic joint="j1" multiplier="2"/>'),
                          "a b c"), "world")
    with pytest.raises(JointError) as info:
        tree.remove("b")
    assert (info.value.frame, info.value.field) == ("c", "mimic")
    assert tree.frames == ["world", "a", "b", "c"] and list(tree.joints) == ["j1", "j2"]
    tree.set_joint_trajectory([0.0], [[0.25]])
    np.testing.assert_allclose(tree.pose("c", "a").rotation[0], rot_z(0.5), atol=1e-15)
    tree.remove("a", recursive=True)  # the mimic goes with the joint it follows
    assert tree.frames == ["world"] and tree.joints == {}


def test_moving_frames_must_agree_on_reference_times_when_the_tree_has_none():
    tree = FrameTree()
    tree.add("relative", "world", Pose(np.zeros((2, 3)), times=[0, 1]))
    absolute = Pose(np.zeros((2, 3)), times=["2024-01-01T00:00", "2024-01-01T00:01"])
    with pytest.raises(ReferenceTimeError) as info:
        tree.add("absolute", "world", absolute)
    assert info.value.frame == "absolute"
    assert "absolute" not in tree
    anchored = FrameTree(reference_time="2024-01-01")
    anchored.add("relative", "world", Pose(np.zeros((2, 3)), times=[0, 1]))
    anchored.add("absolute", "world", absolute)
    assert anchored.reference_time == np.datetime64("2024-01-01", "ns")


def test_set_local_pose_replaces_and_invalidates_cached_queries():
    tree = small_tree()
    np.testing.assert_allclose(tree.pose("torch", "world").translation, [1, 0, 1.4])
    tree.set_local_pose("robot", Pose([3.0, 0.0, 0.0]))
    np.testing.assert_allclose(tree.pose("torch", "world").translation, [3, 0, 1.4])
    tree.set_local_pose("robot", Pose([[0, 0, 0], [2, 0, 0]], times=[0, 2]))
    assert tree.is_moving("robot")
    np.testing.assert_allclose(tree.pose("torch", "world", times=1.0).translation, [[1, 0, 1.4]])


def test_unknown_frames_in_queries():
    tree = small_tree()
    with pytest.raises(FrameNotFoundError):
        tree.pose("ghost", "world")
    with pytest.raises(FrameNotFoundError):
        tree.pose("torch", "ghost")
    with pytest.raises(TreeStructureError):
        tree.pose("world")
