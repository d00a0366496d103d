"""The geometry recorded when a robot is attached, against yourdfpy reading the same URDFs."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
import yourdfpy

from pinframes import FrameTree, read_urdf
from pinframes.values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry
from urdf.test_robots_against_pinocchio import ROBOTS

URDFS = sorted(ROBOTS.rglob("*.urdf")) if ROBOTS is not None else []
BUNDLED = Path(__file__).resolve().parents[2] / "models"


def yourdfpy_robot(urdf: Path):
    try:
        return yourdfpy.URDF.load(str(urdf), build_scene_graph=False, load_meshes=False).robot
    except Exception:  # yourdfpy refuses a few files (ur3.urdf has no robot name)
        return None


def expected_shape(element, colours):
    """(kind, dimensions, mesh, scale, origin matrix, rgba) as yourdfpy reads the element."""
    geometry = element.geometry
    origin = np.eye(4) if element.origin is None else element.origin
    if geometry.box is not None:
        found = ("box", tuple(geometry.box.size), None, (1.0, 1.0, 1.0))
    elif geometry.cylinder is not None:
        found = ("cylinder", (geometry.cylinder.radius, geometry.cylinder.length), None,
                 (1.0, 1.0, 1.0))
    elif geometry.sphere is not None:
        found = ("sphere", (geometry.sphere.radius,), None, (1.0, 1.0, 1.0))
    else:
        scale = geometry.mesh.scale
        scale = (1.0, 1.0, 1.0) if scale is None else tuple(np.broadcast_to(scale, 3))
        found = ("mesh", (), geometry.mesh.filename, scale)
    material = getattr(element, "material", None)
    rgba = None
    if material is not None:
        rgba = colours.get(material.name) if material.color is None else material.color.rgba
    return (*found, origin, None if rgba is None else tuple(rgba))


@pytest.mark.skipif(not URDFS, reason="example-robot-data is not installed")
@pytest.mark.parametrize("urdf", URDFS, ids=lambda path: path.name)
def test_every_link_records_the_shapes_yourdfpy_reads(urdf):
    robot = yourdfpy_robot(urdf)
    if robot is None:
        pytest.skip("yourdfpy does not load this file")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tree = read_urdf(urdf)
    colours = {m.name: m.color.rgba for m in robot.materials if m.color is not None}
    for link in robot.links:
        recorded = tree.frame_metadata(link.name)[GEOMETRY_METADATA_KEY]
        assert isinstance(recorded, FrameGeometry)
        assert recorded.link == link.name and recorded.urdf == str(urdf.resolve())
        assert recorded.unreadable == ()
        for ours, theirs in ((recorded.collision, link.collisions),
                             (recorded.visual, link.visuals)):
            assert len(ours) == len(theirs)
            for shape, element in zip(ours, theirs, strict=True):
                kind, dimensions, mesh, scale, origin, rgba = expected_shape(element, colours)
                assert (shape.kind, shape.mesh) == (kind, mesh)
                np.testing.assert_allclose(shape.dimensions, dimensions, rtol=1e-15)
                np.testing.assert_allclose(shape.scale, scale, rtol=1e-15)
                np.testing.assert_allclose(shape.origin.matrix, origin, atol=1e-12)
                if ours is recorded.visual and rgba is not None:
                    np.testing.assert_allclose(shape.rgba, rgba, rtol=1e-15)


def test_named_and_inline_colours_and_every_kind_of_shape():
    tree = FrameTree()
    tree.attach_urdf("""<robot name="r">
      <material name="blue"><color rgba="0 0 1 1"/></material>
      <link name="a">
        <visual name="v"><origin xyz="1 2 3" rpy="0 0 1.5"/>
          <geometry><box size="0.1 0.2 0.3"/></geometry><material name="blue"/></visual>
        <visual><geometry><mesh filename="package://p/m.stl" scale="2 2 2"/></geometry>
          <material name="red"><color rgba="1 0 0 0.5"/></material></visual>
        <collision><geometry><cylinder radius="0.1" length="0.4"/></geometry></collision>
        <collision><geometry><sphere radius="0.25"/></geometry></collision>
      </link>
    </robot>""", "world", prefix="p/")
    geometry = tree.frame_metadata("p/a")[GEOMETRY_METADATA_KEY]
    assert geometry.urdf is None
    box, mesh = geometry.visual
    assert (box.kind, box.dimensions, box.name, box.rgba) == ("box", (0.1, 0.2, 0.3), "v",
                                                              (0.0, 0.0, 1.0, 1.0))
    np.testing.assert_allclose(box.origin.translation, [1, 2, 3])
    np.testing.assert_allclose(box.origin.rotation[:2, :2],
                               [[np.cos(1.5), -np.sin(1.5)], [np.sin(1.5), np.cos(1.5)]])
    assert (mesh.kind, mesh.mesh, mesh.scale, mesh.rgba) == ("mesh", "package://p/m.stl",
                                                             (2.0, 2.0, 2.0), (1, 0, 0, 0.5))
    assert [(s.kind, s.dimensions) for s in geometry.collision] == [
        ("cylinder", (0.1, 0.4)), ("sphere", (0.25,))]


def test_a_malformed_shape_is_recorded_and_the_robot_still_mounts():
    """Poses never need geometry: the problem waits for whoever uses that shape."""
    tree = FrameTree()
    tree.attach_urdf("""<robot name="r"><link name="a">
        <collision><geometry><box size="1 2"/></geometry></collision>
        <collision><geometry><sphere radius="0.1"/></geometry></collision>
        <visual><geometry/></visual>
      </link></robot>""", "world")
    geometry = tree.frame_metadata("a")[GEOMETRY_METADATA_KEY]
    assert [s.kind for s in geometry.collision] == ["sphere"]
    assert geometry.unreadable_shapes("collision") == (
        ("collision[0].geometry.box.size", "expected three finite numbers, got '1 2'"),)
    assert [field for field, _ in geometry.unreadable_shapes("visual")] == ["visual[0].geometry"]


def test_geometry_follows_renamed_copied_and_grafted_frames():
    tree = read_urdf(BUNDLED / "welding_robot" / "welding_robot.urdf")
    recorded = tree.frame_metadata("link_2")[GEOMETRY_METADATA_KEY]
    tree.rename("link_2", "upper_arm")
    assert tree.frame_metadata("upper_arm")[GEOMETRY_METADATA_KEY] == recorded
    cell = FrameTree()
    cell.graft(tree.copy(), at="world", prefix="robot/")
    assert cell.frame_metadata("robot/upper_arm")[GEOMETRY_METADATA_KEY] == recorded
