"""Finding and reading mesh files: package://, relative names, search folders, bad meshes."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import trimesh

from pinframes import FrameTree
from pinframes.view import GeometryWarning, load_geometry

PACKAGE_MESH = "package://cell_parts/meshes/bracket.stl"


def make_robot(folder: Path, package_mesh: str = PACKAGE_MESH,
               relative_mesh: str = "meshes/arm.stl") -> Path:
    """A two-link URDF: a package:// mesh and a box on ``base``, a relative mesh on ``arm``."""
    (folder / "meshes").mkdir(parents=True, exist_ok=True)
    trimesh.creation.box(extents=(0.1, 0.2, 0.3)).export(folder / "meshes" / "arm.stl")
    urdf = folder / "robot.urdf"
    urdf.write_text(f"""<robot name="r">
  <link name="base">
    <visual><geometry><mesh filename="{package_mesh}"/></geometry></visual>
    <visual><origin xyz="0 0 0.5"/><geometry><box size="0.4 0.4 0.1"/></geometry></visual>
  </link>
  <link name="arm">
    <visual><geometry><mesh filename="{relative_mesh}"/></geometry></visual>
  </link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>""")
    return urdf


def make_package(workspace: Path) -> Path:
    """``workspace/cell_parts/meshes/bracket.stl``: a 0.05 x 0.06 x 0.07 m box."""
    package = workspace / "cell_parts"
    (package / "meshes").mkdir(parents=True)
    trimesh.creation.box(extents=(0.05, 0.06, 0.07)).export(package / "meshes" / "bracket.stl")
    return package


def tree_with(urdf: Path) -> FrameTree:
    tree = FrameTree(root="world")
    tree.attach_urdf(urdf, "world", prefix="r/")
    return tree


def extents(piece) -> np.ndarray:
    return piece.vertices.max(axis=0) - piece.vertices.min(axis=0)


def loaded_quietly(tree: FrameTree, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)
        return load_geometry(tree, **options)


def test_package_found_in_a_search_folder_and_relative_mesh_beside_the_urdf(tmp_path):
    make_package(tmp_path / "workspace")
    tree = tree_with(make_robot(tmp_path / "robot"))
    pieces = loaded_quietly(tree, package_dirs=[tmp_path / "workspace"])
    assert [(p.frame, p.source) for p in pieces] == [
        ("r/base", PACKAGE_MESH), ("r/base", "box"), ("r/arm", "meshes/arm.stl")]
    np.testing.assert_allclose(extents(pieces[0]), [0.05, 0.06, 0.07], atol=1e-12)
    np.testing.assert_allclose(extents(pieces[1]), [0.4, 0.4, 0.1], atol=1e-12)
    np.testing.assert_allclose(pieces[1].pose_in_frame[:3, 3], [0, 0, 0.5])
    np.testing.assert_allclose(extents(pieces[2]), [0.1, 0.2, 0.3], atol=1e-12)


def test_a_search_folder_may_be_the_package_itself(tmp_path):
    package = make_package(tmp_path / "workspace")
    tree = tree_with(make_robot(tmp_path / "robot"))
    assert len(loaded_quietly(tree, package_dirs=[package])) == 3


def test_ros_package_path_is_searched(tmp_path, monkeypatch):
    make_package(tmp_path / "workspace")
    tree = tree_with(make_robot(tmp_path / "robot"))
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{tmp_path / 'nowhere'}:{tmp_path / 'workspace'}")
    assert len(loaded_quietly(tree)) == 3


def test_package_not_found_is_a_warning_naming_link_file_and_search_options(tmp_path):
    tree = tree_with(make_robot(tmp_path / "robot"))
    with pytest.warns(GeometryWarning) as caught:
        pieces = load_geometry(tree)
    assert len(caught) == 1
    message = str(caught[0].message)
    for part in ("robot.urdf", "link 'base'", PACKAGE_MESH, "not found", "package_dirs",
                 "--package-dir", "ROS_PACKAGE_PATH"):
        assert part in message
    assert [(p.frame, p.source) for p in pieces] == [("r/base", "box"),
                                                     ("r/arm", "meshes/arm.stl")]


def test_missing_relative_mesh_is_a_warning(tmp_path):
    make_package(tmp_path / "workspace")
    tree = tree_with(make_robot(tmp_path / "robot", relative_mesh="meshes/gone.stl"))
    with pytest.warns(GeometryWarning, match=r"link 'arm': mesh 'meshes/gone.stl' not found"):
        pieces = load_geometry(tree, package_dirs=[tmp_path / "workspace"])
    assert [p.frame for p in pieces] == ["r/base", "r/base"]


def test_unreadable_dae_is_a_warning_and_the_rest_is_loaded(tmp_path):
    robot = tmp_path / "robot"
    tree = tree_with(make_robot(robot, package_mesh="meshes/broken.dae"))
    (robot / "meshes" / "broken.dae").write_text("<COLLADA><library_geometries>")
    with pytest.warns(GeometryWarning, match=r"link 'base': mesh 'meshes/broken.dae' cannot "
                      r"be read"):
        pieces = load_geometry(tree)
    assert [p.source for p in pieces] == ["box", "meshes/arm.stl"]


def test_empty_stl_is_a_warning(tmp_path):
    robot = tmp_path / "robot"
    tree = tree_with(make_robot(robot, package_mesh="meshes/empty.stl"))
    (robot / "meshes" / "empty.stl").write_bytes(b"solid nothing\nendsolid nothing\n")
    with pytest.warns(GeometryWarning, match=r"link 'base'.*(has no triangles|cannot be read)"):
        pieces = load_geometry(tree)
    assert [p.source for p in pieces] == ["box", "meshes/arm.stl"]


def test_robot_from_an_xml_string_draws_its_shapes_and_finds_meshes_in_search_folders(
        tmp_path):
    """An XML string has no folder: a relative mesh is not found (a warning says where it was
    looked for), a package:// mesh is found in a search folder, primitives need nothing."""
    make_package(tmp_path / "workspace")
    tree = FrameTree(root="world")
    tree.attach_urdf(make_robot(tmp_path).read_text(), "world", prefix="r/")
    with pytest.warns(GeometryWarning, match=r"<urdf string>: link 'arm': mesh "
                                             r"'meshes/arm\.stl' not found"):
        pieces = load_geometry(tree, package_dirs=[tmp_path / "workspace"])
    assert [(p.frame, p.source) for p in pieces] == [("r/base", PACKAGE_MESH), ("r/base", "box")]
    with pytest.warns(UserWarning, match="no samples"):
        arm = tree.pose("r/arm", relative_to="world")
    assert arm.translation.tolist() == [0.0, 0.0, 0.0]
