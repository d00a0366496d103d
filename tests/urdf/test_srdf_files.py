"""SRDF files beside their URDF: disabled collision pairs left out of the clearance (against
Pinocchio + coal with the same pairs removed by ``pinocchio.removeCollisionPairs``), joint
groups and group states for ``solve_joints``, and the SRDFs other tools write."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes import (
    FileFormatError,
    GeometryError,
    JointWithoutSamplesWarning,
    NameNotFoundError,
    SrdfWarning,
)
from urdf.ros_packages import CELL, MA2010_SRDF, MA2010_XACRO, MOTOMAN

CELL_URDF, CELL_SRDF = CELL / "cell.urdf", CELL / "cell.srdf"
MA2010_JOINTS = [f"joint_{n}" for n in ("1_s", "2_l", "3_u", "4_r", "5_b", "6_t")]


pytestmark = pytest.mark.filterwarnings(f"ignore::{JointWithoutSamplesWarning.__module__}."
                                        f"{JointWithoutSamplesWarning.__name__}")


def cell_tree(**options):
    return pinframes.read_urdf(CELL_URDF, srdf=CELL_SRDF, package_dirs=[MOTOMAN], **options)


def random_motion(tree, rng, samples):
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    lower = np.array([tree.joints[name].lower for name in names])
    upper = np.array([tree.joints[name].upper for name in names])
    values = rng.uniform(lower, upper, size=(samples, len(names)))
    tree.set_joint_trajectory(np.arange(float(samples)), values, names)
    return names, values


def pinocchio_clearance(names, values, remove_srdf_pairs):
    """The smallest distance per sample over every pair of links that can move against each
    other (on different Pinocchio joints), by Pinocchio and coal."""
    model = pin.buildModelFromUrdf(str(CELL_URDF))
    geometry = pin.buildGeomFromUrdf(model, str(CELL_URDF), pin.GeometryType.COLLISION,
                                     package_dirs=[str(MOTOMAN)])
    objects = geometry.geometryObjects
    for i in range(len(objects)):
        for j in range(i + 1, len(objects)):
            if objects[i].parentJoint != objects[j].parentJoint:
                geometry.addCollisionPair(pin.CollisionPair(i, j))
    if remove_srdf_pairs:
        pin.removeCollisionPairs(model, geometry, str(CELL_SRDF))
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    smallest = []
    for row in values:
        q = pin.neutral(model)
        for name, value in zip(names, row, strict=True):
            q[model.joints[model.getJointId(name)].idx_q] = value
        pin.computeDistances(model, data, geometry, geometry_data, q)
        smallest.append(min(result.min_distance for result in geometry_data.distanceResults))
    return np.array(smallest), len(geometry.collisionPairs)


@pytest.mark.parametrize("srdf_exclude", [True, False], ids=["SRDF pairs left out", "all"])
def test_cell_clearance_equals_pinocchio_and_coal_with_the_same_pairs(srdf_exclude, rng):
    tree = cell_tree()
    names, values = random_motion(tree, rng, 12)
    result = tree.clearance("*", "*", srdf_exclude=srdf_exclude)
    expected, pairs = pinocchio_clearance(names, values, srdf_exclude)
    # adjacent links' meshes overlap: coal's penetration depth of two meshes moves in the
    # 8th digit with the rounding of their placements, separate shapes agree to 1e-12
    np.testing.assert_allclose(result.distance, expected, atol=1e-7)
    assert len(result.excluded) == (14 if srdf_exclude else 0)
    # 13 shapes, one per link
    assert pairs == 13 * 12 // 2 - len(result.excluded) - len(result.fixed_together)


def test_disabled_pairs_follow_a_prefix_and_stay_apart_for_two_copies(rng):
    tree = pinframes.FrameTree()
    for prefix, x in (("a/", 0.0), ("b/", 3.0)):
        tree.attach_urdf(MA2010_XACRO, "world", pinframes.Pose.from_xyz_rpy(x, 0, 0, 0, 0, 0),
                         prefix=prefix, srdf=MA2010_SRDF, package_dirs=[MOTOMAN])
    result = tree.clearance("*", "*")
    excluded = {frozenset(pair) for pair in result.excluded}
    assert frozenset(("a/link_1_s", "a/link_2_l")) in excluded
    assert frozenset(("b/link_1_s", "b/link_2_l")) in excluded
    assert frozenset(("a/link_1_s", "b/link_2_l")) not in excluded
    assert len(excluded) == 2 * 12


def test_a_grafted_cell_keeps_its_groups_and_pairs():
    cell = pinframes.FrameTree()
    cell.add("stand", "world", pinframes.Pose.from_xyz_rpy(2.0, 0, 0, 0, 0, 0.3))
    cell.graft(cell_tree(), at="stand", prefix="p/")  # the root link becomes "stand"
    solution = cell.solve_joints("p/torch", "p/workpiece", joints="cell", times=[0.0])
    assert len(solution.joint_names) == 8  # robot and positioner, both below the root link
    assert len(cell.clearance("p/*", "p/*").excluded) == 14


def test_model_names_resolve_through_package_dirs_or_gazebo_model_path(monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    plain = pinframes.read_urdf(CELL_URDF)
    with pytest.raises(GeometryError, match="model://motoman_"):
        plain.clearance("torch", "ma2010_base_link")
    expected = plain.clearance("torch", "ma2010_base_link", package_dirs=[MOTOMAN]).distance
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(MOTOMAN))
    np.testing.assert_array_equal(plain.clearance("torch", "ma2010_base_link").distance,
                                  expected)
    monkeypatch.delenv("GAZEBO_MODEL_PATH")
    remembered = cell_tree()  # package_dirs given when read: not needed again
    np.testing.assert_array_equal(remembered.clearance("torch", "ma2010_base_link").distance,
                                  expected)
    model = pin.buildModelFromUrdf(str(CELL_URDF))
    reference = pin.buildGeomFromUrdf(model, str(CELL_URDF), pin.GeometryType.COLLISION,
                                      package_dirs=[str(MOTOMAN)])
    ours = remembered.to_pinocchio().geometry_model("collision")
    assert (sorted(Path(o.meshPath).resolve() for o in ours.geometryObjects if o.meshPath)
            == sorted(Path(o.meshPath).resolve() for o in reference.geometryObjects
                      if o.meshPath))


def test_the_page_finds_the_meshes_in_the_folders_given_when_read(monkeypatch):
    from pinframes.view import load_geometry

    monkeypatch.delenv("GAZEBO_MODEL_PATH", raising=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a mesh not found would be a GeometryWarning
        pieces = load_geometry(cell_tree(), collision=True)
    meshes = [piece for piece in pieces if piece.source.startswith("model://")]
    assert len(meshes) == 10  # MA2010: 7 links, D500: 3 links, one collision mesh each


def test_groups_expand_as_moveit_defines_them():
    tree = cell_tree()
    by_group = {group: tree.solve_joints("torch", "workpiece", joints=group).joint_names
                for group in ("ma2010", "d500", "cell", "wrist")}
    robot = tuple(f"ma2010_{name}" for name in MA2010_JOINTS)
    assert by_group["ma2010"] == robot  # a chain from base to tool
    assert by_group["d500"] == ("d500_joint_1", "d500_joint_2")
    assert by_group["cell"] == robot + by_group["d500"]  # subgroups
    # a joint, and links standing for the joints above them
    assert by_group["wrist"] == ("ma2010_joint_4_r", "ma2010_joint_5_b", "ma2010_joint_6_t")


def test_a_group_state_seeds_the_solver_as_its_values_do():
    values = {"ma2010_joint_1_s": 0.1, "ma2010_joint_2_l": 0.35, "ma2010_joint_3_u": -0.2,
              "ma2010_joint_4_r": 0.0, "ma2010_joint_5_b": -0.9, "ma2010_joint_6_t": 0.0}
    posed = cell_tree()  # the torch where the robot puts it 0.1 rad from the named state
    posed.set_joint_trajectory([0.0], [[value + 0.1 for value in values.values()]],
                               list(values))
    target = posed.pose("torch", "world")
    tree = cell_tree()
    by_name = tree.solve_joints("torch", target, joints="ma2010", seed="weld_ready")
    by_values = tree.solve_joints("torch", target, joints="ma2010", seed=values)
    np.testing.assert_array_equal(by_name.positions, by_values.positions)
    assert by_name.reached.all()
    np.testing.assert_allclose(by_name.positions[0], np.array(list(values.values())) + 0.1,
                               atol=1e-5)


def test_unknown_group_names_the_groups_there_are():
    with pytest.raises(NameNotFoundError, match="'cell', 'd500', 'ma2010', 'wrist'"):
        cell_tree().solve_joints("torch", "workpiece", joints="arm")
    with pytest.raises(NameNotFoundError, match="no robot of the tree was read with an SRDF"):
        pinframes.read_urdf(CELL_URDF).solve_joints("torch", "workpiece", seed="home")


def test_the_moveit_srdf_of_the_ma2010():
    tree = pinframes.read_urdf(MA2010_XACRO, srdf=MA2010_SRDF)
    solution = tree.solve_joints("tool0", "base_link", joints="manipulator", seed="home",
                                 times=[0.0])
    assert solution.joint_names == tuple(MA2010_JOINTS)
    assert len(tree.clearance("*", "*", package_dirs=[MOTOMAN]).excluded) == 12


def test_an_srdf_read_as_a_urdf_says_what_it_is():
    for read in (pinframes.read_urdf, pinframes.read):
        with pytest.raises(FileFormatError, match="this is an SRDF") as caught:
            read(MA2010_SRDF)
        assert caught.value.file == str(MA2010_SRDF)


def test_other_tools_elements_are_skipped_with_one_warning(tmp_path):
    srdf = tmp_path / "tesseract.srdf"
    srdf.write_text("""<robot name="cell">
      <contact_managers_plugin_config filename="model://cell/contact_plugins.yaml"/>
      <group name="d500">
        <chain base_link="d500_base_link" tip_link="d500_tool0"/>
        <group_state name="all_zero" group="ABB_1200">
          <joint name="d500_joint_1" value="0"/>
        </group_state>
      </group>
      <group_state name="tilted" group="d500"><joint name="d500_joint_1" value="0.5"/>
      </group_state>
      <group_state name="lost" group="no_such_group"/>
      <disable_collisions link1="ControlPanel" link2="Passive" reason="Adjacent"/>
      <disable_collisions link1="d500_link_1" link2="d500_link_2" reason="Adjacent"/>
    </robot>""")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tree = pinframes.read_urdf(CELL_URDF, srdf=srdf, package_dirs=[MOTOMAN])
    messages = [str(w.message) for w in caught if issubclass(w.category, SrdfWarning)]
    assert len(messages) == 1
    for skipped in ("contact_managers_plugin_config", "'all_zero' inside group 'd500'",
                    "'no_such_group'", "'ControlPanel'"):
        assert skipped in messages[0]
    solution = tree.solve_joints("workpiece", "d500_base_link", joints="d500", seed="tilted",
                                 times=[0.0])
    assert solution.joint_names == ("d500_joint_1", "d500_joint_2")
    excluded = tree.clearance("d500_*", "d500_*").excluded
    assert [set(pair) for pair in excluded] == [{"d500_link_1", "d500_link_2"}]


def test_a_chain_between_two_branches_goes_through_their_common_link(tmp_path):
    srdf = tmp_path / "across.srdf"
    srdf.write_text('<robot name="cell"><group name="across">'
                    '<chain base_link="ma2010_link_3_u" tip_link="d500_link_2"/></group></robot>')
    tree = pinframes.read_urdf(CELL_URDF, srdf=srdf)
    solution = tree.solve_joints("torch_tip", "workpiece", joints="across", times=[0.0])
    # up from link_3_u to the common root: joints 3, 2, 1; down to d500_link_2: its two
    assert solution.joint_names == ("ma2010_joint_1_s", "ma2010_joint_2_l", "ma2010_joint_3_u",
                                    "d500_joint_1", "d500_joint_2")


def test_default_disabled_links_and_pairs_enabled_again(tmp_path):
    srdf = tmp_path / "defaults.srdf"
    srdf.write_text('<robot name="cell"><disable_default_collisions link="torch"/>'
                    '<enable_collisions link1="ma2010_link_6_t" link2="torch"/></robot>')
    tree = pinframes.read_urdf(CELL_URDF, srdf=srdf, package_dirs=[MOTOMAN])
    excluded = {frozenset(pair) for pair in tree.clearance("*", "*").excluded}
    others = {"ma2010_pedestal", "ma2010_base_link", "d500_base_link", "workpiece",
              *(f"ma2010_link_{n}" for n in ("1_s", "2_l", "3_u", "4_r", "5_b")),
              "d500_link_1", "d500_link_2"}  # every link with geometry but the flange
    assert excluded == {frozenset(("torch", other)) for other in others}


@pytest.mark.parametrize(("element", "field"), [
    ('<disable_collisions link1="d500_link_1"/>', "disable_collisions.link2"),
    ('<group_state name="s" group="g"><joint name="d500_joint_1" value="up"/></group_state>',
     "group_state[s].joint.value"),
    ('<group name="g"><group name="h"/></group><group name="h"><group name="g"/></group>',
     "group[g]"),
])
def test_a_broken_srdf_is_refused_naming_the_field(tmp_path, element, field):
    srdf = tmp_path / "broken.srdf"
    srdf.write_text(f'<robot name="cell"><group name="g"><joint name="d500_joint_1"/></group>'
                    f'{element}</robot>' if "group_state" in element else
                    f'<robot name="cell">{element}</robot>')
    with pytest.raises(FileFormatError) as caught:
        pinframes.read_urdf(CELL_URDF, srdf=srdf)
    assert caught.value.file == str(srdf)
    assert caught.value.field == field
