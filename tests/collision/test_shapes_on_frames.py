"""FrameTree.add_geometry: boxes, cylinders, spheres and meshes on frames, against distances
worked out by hand and against Pinocchio + coal on ``to_pinocchio()``'s geometry."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from meshes import write_cube_stl
from pinframes import (
    ArgumentTypeError,
    Box,
    Cylinder,
    FrameNotFoundError,
    FrameTree,
    InvalidDataError,
    Mesh,
    Pose,
    Sphere,
    write_urdf,
)
from pinframes.view import load_geometry


def ball_along(path_xyz, radius: float = 0.05) -> FrameTree:
    """A tree with a ball on ``ball``, moving through ``path_xyz`` at times 0, 1, 2..."""
    tree = FrameTree()
    points = np.asarray(path_xyz, dtype=float)
    tree.add("ball", "world", Pose(translation=points, rotation=[[0, 0, 0, 1]] * len(points),
                                   times=np.arange(len(points), dtype=float)))
    tree.add_geometry("ball", Sphere(radius))
    return tree


def test_a_turned_box_against_a_ball():
    """Box 0.4 x 0.2 x 0.1 turned 90 degrees about z: 0.1 m to its face along x, 0.2 m
    along y, 0.05 m along z; the ball has radius 0.05."""
    tree = ball_along([[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5], [0.5, 0.5, 0]])
    tree.add("part", "world")
    tree.add_geometry("part", Box([0.4, 0.2, 0.1]),
                      origin=Pose.from_xyz_rpy(0, 0, 0, 0, 0, np.pi / 2))
    result = tree.clearance("part", "ball")
    corner = np.hypot(0.5 - 0.1, 0.5 - 0.2) - 0.05
    np.testing.assert_allclose(result.distance, [0.35, 0.25, 0.4, corner], atol=1e-9)
    np.testing.assert_allclose(result.point_a[0], [0.1, 0, 0], atol=1e-9)
    np.testing.assert_allclose(result.point_b[0], [0.45, 0, 0], atol=1e-9)


def test_a_cylinder_along_z_against_a_ball():
    """Radius 0.1, length 0.6 along z centred 0.2 m up: side, end and rim."""
    tree = ball_along([[0.3, 0, 0.2], [0, 0, 0.8], [0.3, 0, 0.8]])
    tree.add("pipe", "world", Pose([0.0, 0.0, 0.2]))
    tree.add_geometry("pipe", Cylinder(0.1, 0.6))
    result = tree.clearance("pipe", "ball")
    rim = np.hypot(0.3 - 0.1, 0.8 - 0.5) - 0.05
    np.testing.assert_allclose(result.distance, [0.15, 0.25, rim], atol=1e-9)


def test_spheres_overlap_by_the_sum_of_radii_less_the_gap():
    tree = ball_along([[0.5, 0, 0], [0.1, 0, 0]], radius=0.1)
    tree.add("other", "world")
    tree.add_geometry("other", Sphere(0.2), origin=Pose([0.1, 0.0, 0.0]))
    result = tree.clearance("other", "ball")
    np.testing.assert_allclose(result.distance, [0.4 - 0.3, -0.3], atol=1e-9)
    assert result.in_contact.tolist() == [False, True]


def test_shapes_join_a_robot_links_own_and_visual_ones_are_not_measured():
    tree = ball_along([[1.0, 0, 0]])
    tree.attach_urdf('<robot name="r"><link name="r"><collision><geometry><sphere radius="0.1"/>'
                     '</geometry></collision></link></robot>', "world")
    tree.add_geometry("r", Sphere(0.2), origin=Pose([0.5, 0, 0]), kind="collision")
    tree.add_geometry("r", Box([5, 5, 5]), kind="visual")  # drawn only
    assert tree.clearance("r", "ball").distance[0] == pytest.approx(1.0 - 0.7 - 0.05)
    drawn = load_geometry(tree)
    assert [piece.source for piece in drawn if piece.frame == "r"] == ["box"]
    assert sorted(piece.source for piece in load_geometry(tree, collision=True)
                  if piece.frame == "r") == ["sphere", "sphere"]


def test_a_mesh_with_a_scale_against_a_ball(tmp_path):
    cube = write_cube_stl(tmp_path / "cube.stl", 1.0)  # edge 1 m, scaled to 0.2 x 0.4 x 0.6
    tree = ball_along([[0.5, 0, 0], [0, 0.5, 0], [0, 0, 0.5]])
    tree.add("part", "world")
    tree.add_geometry("part", Mesh(cube, scale=[0.2, 0.4, 0.6]))
    result = tree.clearance("part", "ball")
    np.testing.assert_allclose(result.distance, [0.35, 0.25, 0.15], atol=1e-6)


def test_to_pinocchio_carries_the_shapes_and_coal_measures_the_same(tmp_path):
    tree = ball_along([[0.5, 0.2, 0.1]])
    tree.add("part", "world", Pose.from_xyz_rpy(0.0, 0.0, 0.1, 0.0, 0.2, 0.3))
    tree.add_geometry("part", Box([0.2, 0.3, 0.1]), origin=Pose([0.05, 0, 0]))
    compiled = tree.to_pinocchio()
    geometry = compiled.geometry_model("collision")
    assert sorted(obj.name for obj in geometry.geometryObjects) == ["ball_0", "part_0"]
    geometry.addAllCollisionPairs()
    data, geometry_data = compiled.model.createData(), pin.GeometryData(geometry)
    pin.updateGeometryPlacements(compiled.model, data, geometry, geometry_data,
                                 compiled.configurations()[0])
    pin.computeDistances(geometry, geometry_data)
    theirs = geometry_data.distanceResults[0].min_distance
    assert tree.clearance("part", "ball").distance[0] == pytest.approx(theirs, abs=1e-12)


@pytest.mark.parametrize("make", [lambda: Box([0.1, -0.2, 0.3]), lambda: Sphere(np.inf),
                                  lambda: Cylinder(0.1, np.nan), lambda: Box([1, 2]),
                                  lambda: Mesh("part.stl", scale=[1, np.inf, 1])])
def test_shapes_refuse_negative_and_non_finite_sizes(make):
    with pytest.raises(InvalidDataError):
        make()


def test_add_geometry_names_the_frame_and_field_of_what_is_wrong():
    tree = FrameTree()
    tree.add("part", "world")
    with pytest.raises(ArgumentTypeError, match="frame 'part': field 'shape'"):
        tree.add_geometry("part", "box")
    with pytest.raises(ArgumentTypeError, match="frame 'part': field 'kind'"):
        tree.add_geometry("part", Sphere(0.1), kind="solid")
    with pytest.raises(InvalidDataError, match=r"frame 'part': field 'origin'.*static"):
        tree.add_geometry("part", Sphere(0.1), origin=Pose(translation=[[0, 0, 0], [1, 0, 0]],
                                                           times=[0.0, 1.0]))
    with pytest.raises(FrameNotFoundError, match="frame 'nowhere'"):
        tree.add_geometry("nowhere", Sphere(0.1))
    assert "geometry" not in tree.frame_metadata("part")  # nothing recorded on failure


def test_write_urdf_keeps_added_shapes_for_pinocchio_to_read(tmp_path):
    """The written URDF, read by Pinocchio's own buildGeomFromUrdf: the same distance."""
    cube = write_cube_stl(tmp_path / "cube.stl", 1.0)
    tree = FrameTree()
    tree.add("part", "world", Pose.from_xyz_rpy(0.1, 0.0, 0.2, 0.0, 0.0, 0.4))
    tree.add_geometry("part", Box([0.2, 0.3, 0.1]), origin=Pose([0.05, 0, 0]))
    tree.add_geometry("part", Cylinder(0.05, 0.4), origin=Pose.from_xyz_rpy(0, 0, 0.3, 0.5, 0, 0),
                      kind="collision")
    tree.add("probe", "world", Pose([0.7, 0.3, 0.4]))
    tree.add_geometry("probe", Mesh(cube, scale=0.1), rgba=(0.2, 0.4, 0.6, 1.0))
    path = tmp_path / "cell.urdf"
    write_urdf(tree, path)
    model = pin.buildModelFromUrdf(str(path))
    geometry = pin.buildGeomFromUrdf(model, str(path), pin.GeometryType.COLLISION)
    assert geometry.ngeoms == 3
    part = [i for i, obj in enumerate(geometry.geometryObjects) if obj.name.startswith("part")]
    probe = [i for i, obj in enumerate(geometry.geometryObjects) if obj.name.startswith("probe")]
    for i in part:
        geometry.addCollisionPair(pin.CollisionPair(i, probe[0]))
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    pin.updateGeometryPlacements(model, data, geometry, geometry_data, pin.neutral(model))
    pin.computeDistances(geometry, geometry_data)
    theirs = min(result.min_distance for result in geometry_data.distanceResults)
    assert tree.clearance("part", "probe").distance[0] == pytest.approx(theirs, abs=1e-9)
    visual = pin.buildGeomFromUrdf(model, str(path), pin.GeometryType.VISUAL)
    colours = [obj.meshColor.tolist() for obj in visual.geometryObjects
               if obj.name.startswith("probe")]
    np.testing.assert_allclose(colours, [[0.2, 0.4, 0.6, 1.0]], atol=1e-7)  # float32 there
