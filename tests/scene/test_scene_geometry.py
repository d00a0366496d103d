"""Scenes keep shapes: a frame's ``geometry`` entry read, written and read back."""

from __future__ import annotations

import textwrap

import numpy as np
import pytest

from meshes import write_cube_stl
from pinframes import (
    Box,
    Cylinder,
    FileFormatError,
    FrameTree,
    Mesh,
    Pose,
    Sphere,
    read_scene,
    write_scene,
)
from pinframes.values.geometry import GEOMETRY_METADATA_KEY

SCENE = """\
    pinframes_scene: 1
    frames:
      - name: fixture
        parent: world
        xyz: [1.0, 0.0, 0.0]
        geometry:
          - box: {size: [0.4, 0.2, 0.1]}
            xyz: [0.0, 0.0, 0.05]
          - mesh: {file: meshes/cube.stl, scale: 0.5}
            rpy: [0.0, 0.0, 0.3]
            kind: collision
          - cylinder: {radius: 0.05, length: 0.3}
            kind: visual
            rgba: [0.8, 0.2, 0.1, 1.0]
    tools:
      - name: probe
        parent: world
        xyz: [0.0, 0.0, 0.5]
        geometry:
          - sphere: {radius: 0.1}
    """


@pytest.fixture
def scene(tmp_path):
    (tmp_path / "meshes").mkdir()
    write_cube_stl(tmp_path / "meshes" / "cube.stl", 0.2)
    path = tmp_path / "cell.yaml"
    path.write_text(textwrap.dedent(SCENE))
    return path


def shapes(tree: FrameTree, frame: str):
    recorded = tree.frame_metadata(frame)[GEOMETRY_METADATA_KEY]
    return recorded.collision, recorded.visual


def test_a_scene_gives_frames_their_shapes(scene):
    tree = read_scene(scene)
    collision, visual = shapes(tree, "fixture")
    assert [shape.kind for shape in collision] == ["box", "mesh"]
    assert [shape.kind for shape in visual] == ["box", "cylinder"]
    assert collision[1].mesh == str(scene.parent / "meshes" / "cube.stl")
    assert collision[1].scale == (0.5, 0.5, 0.5) and collision[1].rpy == (0.0, 0.0, 0.3)
    assert visual[1].rgba == (0.8, 0.2, 0.1, 1.0)
    # the box's top at z = 0.1, the mesh cube (0.1 m after scale) within it: the probe's
    # ball (radius 0.1 at z = 0.5, x = 0) is sqrt(0.8**2 + 0.4**2) - 0.1 from the box's
    # nearest corner region: x from 0.8, z from 0.1
    expected = np.hypot(1.0 - 0.2, 0.5 - 0.1) - 0.1
    assert tree.clearance("fixture", "probe").distance[0] == pytest.approx(expected)


def test_written_scenes_keep_shapes_and_mesh_names(scene, tmp_path):
    tree = read_scene(scene)
    tree.add("pipe", "world", Pose([0.0, 2.0, 0.0]))
    tree.add_geometry("pipe", Mesh("package://cell_parts/meshes/pipe.stl", scale=[1, 1, 2]))
    written = tmp_path / "written.yaml"
    write_scene(tree, written)
    text = written.read_text()
    assert "file: meshes/cube.stl" in text and "package://cell_parts/meshes/pipe.stl" in text
    again = read_scene(written)
    for frame in ("fixture", "probe", "pipe"):
        assert shapes(again, frame) == shapes(tree, frame)


def test_written_robot_links_keep_their_urdf_shapes(tmp_path):
    (tmp_path / "meshes").mkdir()
    write_cube_stl(tmp_path / "meshes" / "block.stl", 0.3)
    urdf = tmp_path / "r.urdf"  # its mesh named relative to it
    urdf.write_text('<robot name="r"><link name="base"><collision><origin xyz="0 0 0.15"/>'
                    '<geometry><mesh filename="meshes/block.stl"/></geometry></collision>'
                    '</link></robot>')
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    tree.add("ball", "world", Pose([1.0, 0.0, 0.15]))
    tree.add_geometry("ball", Sphere(0.1))
    written = tmp_path / "out" / "cell.yaml"
    written.parent.mkdir()
    write_scene(tree, written)
    again = read_scene(written)
    assert again.clearance("base", "ball").distance[0] == pytest.approx(1.0 - 0.15 - 0.1)


def test_shapes_on_the_root_are_refused_by_the_writer(tmp_path):
    tree = FrameTree()
    tree.add_geometry("world", Box([1, 1, 1]))
    with pytest.raises(Exception, match="root"):
        write_scene(tree, tmp_path / "cell.yaml")
    assert not (tmp_path / "cell.yaml").exists()


@pytest.mark.parametrize(("entry", "field"), [
    ("{box: {size: [1, 2]}}", "frames[0].geometry[0].box.size"),
    ("{box: {size: [1, -2, 3]}}", "frames[0].geometry[0].box.size"),
    ("{sphere: {radius: .inf}}", "frames[0].geometry[0].sphere.radius"),
    ("{cylinder: {radius: 1}}", "frames[0].geometry[0].cylinder"),
    ("{sphere: {radius: 1}, box: {size: [1, 1, 1]}}", "frames[0].geometry[0]"),
    ("{sphere: {radius: 1}, kind: solid}", "frames[0].geometry[0].kind"),
    ("{sphere: {radius: 1}, xyz: [1, 2]}", "frames[0].geometry[0].xyz"),
    ("{sphere: {radius: 1}, rgba: [1, 0, 0, 2]}", "frames[0].geometry[0].rgba"),
    ("{mesh: {scale: 2}}", "frames[0].geometry[0].mesh"),
])
def test_bad_geometry_entries_name_file_frame_and_field(tmp_path, entry, field):
    path = tmp_path / "cell.yaml"
    path.write_text(f"pinframes_scene: 1\nframes:\n  - name: part\n    parent: world\n"
                    f"    geometry: [{entry}]\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(path)
    assert caught.value.file == str(path)
    assert caught.value.frame == "part" and caught.value.field == field, str(caught.value)


def test_shapes_are_values_with_sizes():
    assert Box([0.1, 0.2, 0.3]).size == (0.1, 0.2, 0.3)
    assert Cylinder(0.1, 0.5) == Cylinder(radius=0.1, length=0.5)
    assert Mesh("a.stl", 2).scale == (2.0, 2.0, 2.0)
