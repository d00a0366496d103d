"""Robots as ROS packages are published: packages found by the name in their package.xml
(moveit_resources' ``panda_description`` folder holds ``moveit_resources_panda_description``,
a clone ``Universal_Robots_ROS2_Description`` holds ``ur_description``), an SRDF shipped as
xacro (``ur_moveit_config``), and a xacro file as a bag's ``--robot-description``.

References: the ``xacro`` command's own expansion (``urdf.ros_packages.xacro_command``), and
Pinocchio + coal called directly on it with the expanded SRDF's pairs removed.
"""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes import FileFormatError, GeometryWarning
from pinframes.cli import main
from pinframes.kinematics.collision.mesh_files import mesh_files_of
from pinframes.view import load_geometry
from urdf.ros_packages import DATA, UR_DESCRIPTION, UR_XACRO, xacro_command

PANDA = DATA / "moveit_resources" / "panda_description"
PANDA_URDF = PANDA / "urdf" / "panda.urdf"
UR_MOVEIT_CONFIG = DATA / "ur_moveit_config"
UR_SRDF = UR_MOVEIT_CONFIG / "srdf" / "ur.srdf.xacro"
UR5E = {"name": "ur", "ur_type": "ur5e"}


@pytest.fixture(scope="module")
def ur5e_texts(tmp_path_factory):
    """The UR5e URDF and its SRDF as the ``xacro`` command expands them."""
    scratch = tmp_path_factory.mktemp("xacro")
    packages = {"ur_description": str(UR_DESCRIPTION),
                "ur_moveit_config": str(UR_MOVEIT_CONFIG)}
    return (xacro_command(UR_XACRO, UR5E, packages, scratch),
            xacro_command(UR_SRDF, {"name": "ur"}, packages, scratch))


def smallest_distances(model, geometry, names, values) -> list[float]:
    """Per row of ``values`` (joints ``names``): the smallest distance over the collision
    pairs of ``geometry``, by ``pinocchio.computeDistances``."""
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    found = []
    for row in values:
        q = pin.neutral(model)
        for name, value in zip(names, row, strict=True):
            q[model.joints[model.getJointId(name)].idx_q] = value
        pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
        pin.computeDistances(geometry, geometry_data)
        found.append(min(result.min_distance for result in geometry_data.distanceResults))
    return found


def test_a_package_is_found_by_the_name_in_its_package_xml_in_a_crawled_folder(tmp_path):
    lone = tmp_path / "panda.urdf"  # no package above it: only the crawl of DATA finds it
    shutil.copy(PANDA_URDF, lone)
    tree = pinframes.read_urdf(lone, package_dirs=[DATA])
    meshes = [(frame, shape.mesh) for frame in tree.frames
              if (geometry := tree.frame_metadata(frame).get("geometry")) is not None
              for shape in geometry.collision]
    assert len(meshes) == 11  # link0 ... link7, the hand and its two fingers
    for frame, name in meshes:
        assert name.startswith("package://moveit_resources_panda_description/")
        found = mesh_files_of(tree.frame_metadata(frame)["geometry"]).find(name)
        assert found == PANDA / "meshes" / "collision" / name.rsplit("/", 1)[1]


def test_the_panda_page_and_clearance_find_their_meshes_and_equal_pinocchio(tmp_path, rng):
    lone = tmp_path / "panda.urdf"
    shutil.copy(PANDA_URDF, lone)
    tree = pinframes.read_urdf(lone, package_dirs=[DATA])
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)  # a mesh not found would warn
        drawn = {piece.link for piece in load_geometry(tree, collision=True)}
    assert drawn == {f"panda_link{n}" for n in range(8)} | {
        "panda_hand", "panda_leftfinger", "panda_rightfinger"}
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    lower = np.array([tree.joints[name].lower for name in names])
    upper = np.array([tree.joints[name].upper for name in names])
    values = rng.uniform(lower, upper, size=(4, len(names)))
    tree.set_joint_trajectory(np.arange(4.0), values, names)
    result = tree.clearance("panda_link0", "panda_hand")

    model = pin.buildModelFromUrdf(str(PANDA_URDF))
    named = tmp_path / "by_package_name"  # Pinocchio looks for packages by folder name
    named.mkdir()
    (named / "moveit_resources_panda_description").symlink_to(PANDA)
    geometry = pin.buildGeomFromUrdf(model, str(PANDA_URDF), pin.GeometryType.COLLISION,
                                     package_dirs=[str(named)])
    ids = [index for index, item in enumerate(geometry.geometryObjects)
           if model.frames[item.parentFrame].name in ("panda_link0", "panda_hand")]
    geometry.addCollisionPair(pin.CollisionPair(*ids))
    expected = smallest_distances(model, geometry, names, values)
    np.testing.assert_allclose(result.distance, expected, atol=1e-6)


def test_a_git_clone_named_after_its_repository_is_found_by_its_package_name(tmp_path):
    clone = tmp_path / "ws" / "src" / "Universal_Robots_ROS2_Description"
    shutil.copytree(UR_DESCRIPTION, clone)
    # $(find ur_description) among the file's ancestors, by the package.xml's name
    tree = pinframes.read_urdf(clone / "urdf" / "ur.urdf.xacro", xacro_args=UR5E)
    assert len(tree.joints) == 6
    # and from the workspace's folder, crawled down three levels
    lone = tmp_path / "ur.urdf.xacro"
    shutil.copy(UR_XACRO, lone)
    assert len(pinframes.read_urdf(lone, xacro_args=UR5E,
                                   package_dirs=[tmp_path / "ws"]).joints) == 6


def test_ament_prefix_path_share_folders_are_searched(tmp_path, monkeypatch):
    shutil.copytree(UR_DESCRIPTION, tmp_path / "install" / "share" / "ur_description")
    lone = tmp_path / "robot.urdf.xacro"
    shutil.copy(UR_XACRO, lone)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "install"))
    assert len(pinframes.read_urdf(lone, xacro_args=UR5E).joints) == 6


def test_the_clearance_of_a_ros2_moveit_config_equals_pinocchio_with_its_srdf(
        ur5e_texts, rng):
    urdf_text, srdf_text = ur5e_texts
    tree = pinframes.read_urdf(UR_XACRO, xacro_args=UR5E, srdf=UR_SRDF)
    assert tree.frame_metadata("shoulder_link")["srdf"].robot.groups[
        "ur_manipulator"] == ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                              "wrist_1_joint", "wrist_2_joint", "wrist_3_joint")
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    values = rng.uniform(-np.pi, np.pi, size=(12, len(names)))
    tree.set_joint_trajectory(np.arange(12.0), values, names)
    result = tree.clearance("*", "*")

    model = pin.buildModelFromXML(urdf_text)
    geometry = pin.buildGeomFromUrdfString(model, urdf_text, pin.GeometryType.COLLISION,
                                           package_dirs=[str(DATA)])
    geometry.addAllCollisionPairs()
    all_pairs = len(geometry.collisionPairs)
    pin.removeCollisionPairsFromXML(model, geometry, srdf_text, False)
    assert 0 < len(geometry.collisionPairs) < all_pairs
    expected = smallest_distances(model, geometry, names, values)
    np.testing.assert_allclose(result.distance, expected, atol=1e-6)
    # the SRDF matters: without it the adjacent links touch (0 m) at every sample
    assert max(expected) > 0.01
    assert np.all(tree.clearance("*", "*", srdf_exclude=False).distance <= 0.0)


def test_a_xacro_srdf_is_never_read_as_plain_xml(tmp_path):
    disguised = tmp_path / "ur.srdf"  # xacro content under a plain name
    disguised.write_text(UR_SRDF.read_text())
    with pytest.raises(FileFormatError, match="xacro=True") as caught:
        pinframes.read_urdf(UR_XACRO, xacro_args=UR5E, srdf=disguised)
    assert caught.value.file == str(disguised) and caught.value.field == "xacro"
    shutil.copy(UR_MOVEIT_CONFIG / "srdf" / "ur_macro.srdf.xacro", tmp_path)
    tree = pinframes.read_urdf(UR_XACRO, xacro_args=UR5E, srdf=disguised, xacro=True,
                               package_dirs=[DATA])
    assert tree.frame_metadata("tool0")["srdf"].robot.disabled_pairs


def test_an_srdf_argument_without_a_default_comes_from_xacro_args(tmp_path):
    srdf = tmp_path / "robot.srdf.xacro"  # as KUKA's ROS 2 MoveIt configs: no default
    srdf.write_text('<robot name="$(arg robot_name)" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    '<group name="arm">'
                    '<chain base_link="$(arg robot_name)_base" tip_link="tool0"/></group>'
                    '</robot>')
    urdf = tmp_path / "robot.urdf"
    urdf.write_text('<robot name="r"><link name="kr_base"/><link name="tool0"/>'
                    '<joint name="a1" type="revolute"><parent link="kr_base"/>'
                    '<child link="tool0"/><limit lower="-1" upper="1" effort="1" '
                    'velocity="1"/></joint></robot>')
    with pytest.raises(FileFormatError, match="robot_name"):
        pinframes.read_urdf(urdf, srdf=srdf)
    tree = pinframes.read_urdf(urdf, srdf=srdf, xacro_args={"robot_name": "kr"})
    assert tree.frame_metadata("tool0")["srdf"].robot.groups["arm"] == ("a1",)


def test_a_xacro_file_is_a_bags_robot_description_with_the_opt_in(tmp_path, capsys):
    pytest.importorskip("rosbags")
    from ros.bag_writing import Transform, tf_messages, write_bag

    start = 1_700_000_000 * 1_000_000_000
    bag = write_bag(tmp_path / "ur", "mcap",
                    tf_messages(2, [Transform("world", "base_link", start)], topic="/tf_static"))
    given = ["--robot-description", str(UR_XACRO), "--xacro-arg", "name:=ur",
             "--xacro-arg", "ur_type:=ur5e"]
    assert main(["info", str(bag), *given]) == 0, capsys.readouterr().err
    assert "wrist_3_link" in capsys.readouterr().out
    disguised = tmp_path / "ur.urdf"  # xacro content under a plain name: only with --xacro
    shutil.copytree(UR_DESCRIPTION, tmp_path / "ur_description")
    shutil.copy(UR_XACRO, tmp_path / "ur_description" / "urdf" / "ur.urdf")
    disguised = tmp_path / "ur_description" / "urdf" / "ur.urdf"
    given[1] = str(disguised)
    assert main(["info", str(bag), *given]) == 1
    assert "--xacro" in capsys.readouterr().err
    assert main(["info", str(bag), *given, "--xacro"]) == 0
    assert "wrist_3_link" in capsys.readouterr().out


def test_an_srdf_whose_pairs_name_none_of_the_robots_links_is_an_error(tmp_path):
    # the UR SRDF against a UR10e mounted with tf_prefix "left_": every pair names a link
    # the robot does not have, and a clearance would silently check them all
    arguments = {"name": "ur", "ur_type": "ur10e", "tf_prefix": "left_"}
    with pytest.raises(FileFormatError, match=r"none of its 11 disabled collision pairs.*"
                       r"tf_prefix") as caught:
        pinframes.read_urdf(UR_XACRO, xacro_args=arguments, srdf=UR_SRDF)
    assert caught.value.file == str(UR_SRDF) and caught.value.field == "disable_collisions"
