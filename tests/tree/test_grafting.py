"""FrameTree.graft and FrameTree.subtree: graft then subtree gives back the grafted tree (every
frame in every other at many times, to 1e-12); clashing names change neither tree."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

import pinframes
from pinframes import (
    ArgumentTypeError,
    FrameExistsError,
    FrameTree,
    Joint,
    Mimic,
    Pose,
    ReferenceTimeError,
    SpatialData,
    Subsystem,
)

from geometry import rot_x, rot_z

T_CELL = np.datetime64("2024-03-01T08:00:00", "ns")
T_HOST = np.datetime64("2024-03-01T07:59:50", "ns")
TIMES = T_CELL + (np.linspace(-3.0, 9.0, 41) * 1e9).astype("timedelta64[ns]")


def cell() -> FrameTree:
    """Static and moving frames, a robot with a mimic joint and a trajectory, data, subsystems."""
    tree = FrameTree("cell_base", name="cell", reference_time=T_CELL)
    tree.add("table", "cell_base", Pose([1.0, 0.0, 0.0], rot_z(0.3)))
    tree.add("slide", "table", Pose([[0, 0, 0], [0.5, 0, 0], [0.5, 0.2, 0]],
                                    np.stack([np.eye(3), rot_x(0.4), rot_z(1.0)]),
                                    times=[0.0, 2.0, 5.0]))
    tree.add("camera", "cell_base", Pose([[0, 0, 1], [0, 0.1, 1]], times=[
        "2024-03-01T07:59:59", "2024-03-01T08:00:04"]))
    tree.attach_joint("upper_arm", "slide", Joint("shoulder", "revolute", (0.0, 0.0, 1.0)),
                      Pose([0.0, 0.0, 0.2]))
    tree.attach_joint("forearm", "upper_arm", Joint("elbow", "revolute", (0.0, 1.0, 0.0),
                                                    mimic=Mimic("shoulder", 0.5, 0.1)),
                      Pose([0.3, 0.0, 0.0]))
    tree.add("tcp", "forearm", Pose([0.25, 0.0, 0.0], rot_x(np.pi / 2)))
    tree.set_joint_trajectory([0.0, 1.0, 4.0], [[0.0], [1.2], [-0.5]], ["shoulder"])
    tree.assign_data("part", SpatialData(np.eye(3), triangles=[[0, 1, 2]]), "table")
    tree.assign_data("scan", SpatialData(np.ones((2, 4, 3)), times=[0.5, 1.5]), "tcp")
    tree.subsystems = [Subsystem("robot", "slide", ("slide", "upper_arm", "forearm", "tcp"),
                                 "cell", None, ("gripper",), ("scan",)),
                       Subsystem("gripper", "forearm", ("forearm", "tcp"), "robot")]
    return tree


def host() -> FrameTree:
    tree = FrameTree("world", name="shop", reference_time=T_HOST)
    tree.add("bay", "world", Pose([[5.0, 0, 0], [5.0, 1.0, 0]], rot_z(0.7), times=[0.0, 20.0]))
    tree.add("cell_base", "bay", Pose([0.0, 0.0, 0.5], rot_x(0.2)))
    tree.add("crane", "world", Pose([0, 0, 3.0]))
    return tree


def snapshot(tree: FrameTree):
    return (tree.frames, [tree.parent(f) for f in tree.frames], list(tree.joints),
            tree.data_names, list(tree.subsystems), tree.name, tree.reference_time)


def assert_same_tree(copy: FrameTree, original: FrameTree) -> None:
    assert snapshot(copy) == snapshot(original)
    for frame in original.frames:
        for other in original.frames:
            np.testing.assert_allclose(copy.pose(frame, other, times=TIMES).matrix,
                                       original.pose(frame, other, times=TIMES).matrix,
                                       atol=1e-12, rtol=0, err_msg=f"{frame} in {other}")
    for name in original.data_names:
        assert copy.data_frame(name) == original.data_frame(name)
        np.testing.assert_allclose(copy.get_data(name, original.root).points,
                                   original.get_data(name, original.root).points, atol=1e-12)


def test_graft_then_subtree_gives_back_the_tree():
    shop, original = host(), cell()
    record = shop.graft(cell(), at="cell_base")
    assert record == Subsystem("cell", "cell_base", tuple(original.frames), "shop", T_CELL,
                               ("robot",), ("part", "scan"))
    assert_same_tree(shop.subtree("cell_base"), original)


def test_grafted_frames_sit_on_the_mount_frame():
    shop, original = host(), cell()
    shop.graft(cell(), at="cell_base")
    mount = shop.pose("cell_base", "world", times=TIMES).matrix
    for frame in original.frames[1:]:
        inside = original.pose(frame, "cell_base", times=TIMES).matrix
        np.testing.assert_allclose(shop.pose(frame, "world", times=TIMES).matrix,
                                   np.einsum("tij,tjk->tik", mount, inside), atol=1e-12)
    scan = original.get_data("scan", "cell_base").points  # at its own times 0.5 s, 1.5 s
    mount_at_scan = shop.pose("cell_base", "world", times=T_CELL + np.array(
        [500_000_000, 1_500_000_000], dtype="timedelta64[ns]"))
    expected = np.einsum("tij,tmj->tmi", mount_at_scan.rotation, scan) + \
        mount_at_scan.translation[:, None, :]
    np.testing.assert_allclose(shop.get_data("scan", "world").points, expected, atol=1e-12)


def test_graft_with_a_prefix_renames_frames_joints_data_and_subsystems():
    shop = host()
    shop.graft(cell(), at="crane", prefix="left/")
    shop.graft(cell(), at="bay", prefix="right/", name="cell_right")
    assert "left/tcp" in shop and "right/tcp" in shop and "cell_base" in shop
    assert shop.parent("left/table") == "crane"
    assert {"left/shoulder", "left/elbow", "right/shoulder"} <= set(shop.joints)
    assert shop.joints["left/elbow"].mimic.joint == "left/shoulder"
    assert sorted(shop.data_names) == ["left/part", "left/scan", "right/part", "right/scan"]
    names = {s.name: s for s in shop.subsystems}
    assert names["left/robot"].parent == "left/cell" and names["left/cell"].root == "crane"
    assert names["left/gripper"].parent == "left/robot"
    assert names["cell_right"].root == "bay"
    original = cell()
    for frame in ["tcp", "camera", "slide"]:
        np.testing.assert_allclose(shop.pose("left/" + frame, "crane", times=TIMES).matrix,
                                   original.pose(frame, "cell_base", times=TIMES).matrix,
                                   atol=1e-12)


@pytest.mark.parametrize("clash", ["frame", "joint", "data", "subsystem"])
def test_a_clashing_name_is_an_error_that_changes_neither_tree(clash):
    shop, grafted = host(), cell()
    if clash == "frame":
        shop.add("table", "crane")
    elif clash == "joint":
        shop.attach_joint("hoist", "crane", Joint("shoulder", "prismatic"))
    elif clash == "data":
        shop.assign_data("part", [[0.0, 0.0, 0.0]], "crane")
    else:
        shop.subsystems = [Subsystem("robot", "crane", ("crane",))]
    before, before_grafted = snapshot(shop), snapshot(grafted)
    with pytest.raises(FrameExistsError):
        shop.graft(grafted, at="cell_base")
    assert snapshot(shop) == before and snapshot(grafted) == before_grafted


def test_a_failure_midway_leaves_the_tree_as_it_was():
    shop = FrameTree("world")  # no reference time, a moving frame without one
    shop.add("cell_base", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0]))
    before = snapshot(shop)
    with pytest.raises(ReferenceTimeError):
        shop.graft(cell(), at="cell_base")
    assert snapshot(shop) == before and "shoulder" not in shop.joints


def test_subtree_of_an_inner_frame_keeps_what_lies_inside():
    original = cell()
    part = original.subtree("slide")
    assert part.root == "slide" and part.frames == ["slide", "upper_arm", "forearm", "tcp"]
    # the subsystem "robot" records exactly this part: it names the copy and is unwrapped
    assert part.name == "robot" and part.reference_time is None
    assert part.data_names == ["scan"]
    assert part.subsystems == [Subsystem("gripper", "forearm", ("forearm", "tcp"), "robot")]
    # the joint trajectory counted from the cell's reference time, and still does
    assert part.joint_track("shoulder").reference == T_CELL
    for frame in part.frames:
        np.testing.assert_allclose(part.pose(frame, "slide", times=TIMES).matrix,
                                   original.pose(frame, "slide", times=TIMES).matrix,
                                   atol=1e-12)


def test_subtree_of_a_plain_frame_keeps_the_tree_name_and_reference_time():
    original = cell()
    part = original.subtree("table")
    assert (part.name, part.reference_time, part.frames, part.data_names) == (
        "cell", T_CELL, ["table", "slide", "upper_arm", "forearm", "tcp"], ["part", "scan"])
    assert [s.name for s in part.subsystems] == ["robot", "gripper"]
    for frame in part.frames:
        np.testing.assert_allclose(part.pose(frame, "table", times=TIMES).matrix,
                                   original.pose(frame, "table", times=TIMES).matrix,
                                   atol=1e-12)


# -- tree metadata ---------------------------------------------------------------------------
def with_metadata(tree: FrameTree, metadata: dict) -> FrameTree:
    tree.metadata = metadata
    return tree


def test_graft_adds_the_grafted_metadata_under_the_prefix_and_keeps_its_own():
    shop = with_metadata(host(), {"site": "hall 3", "urdf": {"crane": {"name": "hoist"}}})
    grafted = with_metadata(cell(), {"urdf": {"arm": {"name": "ur5", "extra_xml": ["<m/>"]}},
                                     "calibrated": "2024-02-28"})
    shop.graft(grafted, at="crane", prefix="left/")
    assert shop.metadata == {"site": "hall 3", "urdf": {"crane": {"name": "hoist"}},
                             "left/urdf": {"arm": {"name": "ur5", "extra_xml": ["<m/>"]}},
                             "left/calibrated": "2024-02-28"}
    # deep copies: changing either tree afterwards leaves the other alone
    grafted.metadata["urdf"]["arm"]["extra_xml"].append("<n/>")
    shop.metadata["left/urdf"]["arm"]["name"] = "changed"
    assert shop.metadata["left/urdf"]["arm"]["extra_xml"] == ["<m/>"]
    assert grafted.metadata["urdf"]["arm"]["name"] == "ur5"


def test_graft_without_a_prefix_adds_the_keys_as_they_are():
    shop = with_metadata(host(), {"site": "hall 3"})
    shop.graft(with_metadata(cell(), {"urdf": {"arm": {"name": "ur5"}}}), at="cell_base")
    assert shop.metadata == {"site": "hall 3", "urdf": {"arm": {"name": "ur5"}}}


def test_a_clashing_metadata_key_is_an_error_that_changes_neither_tree():
    shop = with_metadata(host(), {"site": "hall 3", "left/note": "mine"})
    grafted = with_metadata(cell(), {"note": "theirs"})
    before, before_grafted = snapshot(shop), snapshot(grafted)
    with pytest.raises(FrameExistsError) as caught:
        shop.graft(grafted, at="crane", prefix="left/")
    assert caught.value.field == "metadata" and "'left/note'" in str(caught.value)
    assert snapshot(shop) == before and snapshot(grafted) == before_grafted
    assert shop.metadata == {"site": "hall 3", "left/note": "mine"}
    assert grafted.metadata == {"note": "theirs"}
    # another prefix takes it
    shop.graft(grafted, at="crane", prefix="right/")
    assert shop.metadata == {"site": "hall 3", "left/note": "mine", "right/note": "theirs"}


def test_a_failure_midway_leaves_the_metadata_as_it_was():
    shop = with_metadata(FrameTree("world"), {"site": "hall 3"})
    shop.add("cell_base", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0]))
    with pytest.raises(ReferenceTimeError):
        shop.graft(with_metadata(cell(), {"note": "theirs"}), at="cell_base")
    assert shop.metadata == {"site": "hall 3"}


def test_a_metadata_key_that_cannot_take_the_prefix_is_an_error_before_any_change():
    shop = host()
    before = snapshot(shop)
    with pytest.raises(ArgumentTypeError) as caught:
        shop.graft(with_metadata(cell(), {7: "seven"}), at="crane", prefix="left/")
    assert caught.value.field == "metadata" and "7" in str(caught.value)
    assert snapshot(shop) == before and shop.metadata == {}
    shop.graft(with_metadata(cell(), {7: "seven"}), at="cell_base")  # no prefix: kept as is
    assert shop.metadata == {7: "seven"}


ROBOT = """<robot name="arm">
  <material name="blue"><color rgba="0 0 1 1"/></material>
  <link name="base"/><link name="tip"/>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="tip"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


@pytest.mark.filterwarnings("ignore::pinframes.errors.JointWithoutSamplesWarning")
def test_a_grafted_robot_keeps_its_urdf_details_for_the_urdf_writer(tmp_path):
    (tmp_path / "arm.urdf").write_text(ROBOT)
    robot = pinframes.read(tmp_path / "arm.urdf")
    cell_tree = FrameTree("world")
    cell_tree.add("base", "world", Pose([1.0, 0.0, 0.0]))
    cell_tree.graft(robot)
    cell_tree.graft(robot, at="world", prefix="spare/")
    assert set(cell_tree.metadata) == {"urdf", "spare/urdf"}
    pinframes.write(cell_tree, tmp_path / "cell.urdf")
    written = ET.parse(tmp_path / "cell.urdf").getroot()
    assert [m.get("name") for m in written.findall("material")] == ["blue"]
    assert written.find("material/color").get("rgba") == "0 0 1 1"
