"""Meshes and shapes that would cost gigabytes or give phantom contacts (issue items 4, 10).

- A COLLADA file of a few kB whose nodes instance each other describes 2**levels triangles:
  counted before any is built, refused past ``Limits.max_triangles`` (the clearance: an
  error naming the frame; the page: the mesh left out with a warning).
- Shapes that are not finite, or so large or far that coal's squared distances overflow:
  clear errors naming the frame and field, never a contact that does not exist.
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

from meshes import nested_instances_dae, write_stl
from pinframes import FrameTree, GeometryError, GeometryWarning, Limits, Pose
from pinframes.view import load_geometry


def one_link(name: str, geometry: str, kind: str = "collision") -> str:
    return (f'<robot name="{name}"><link name="{name}"><{kind}><geometry>{geometry}</geometry>'
            f'</{kind}></link></robot>')


def with_ball(tree: FrameTree, at=(3.0, 0.0, 0.0)) -> FrameTree:
    tree.add("ball_at", "world", Pose(list(at)))
    tree.attach_urdf(one_link("ball", '<sphere radius="0.1"/>'), "ball_at")
    return tree


def nested_tree(tmp_path, levels: int) -> FrameTree:
    path = tmp_path / "nested.dae"
    path.write_text(nested_instances_dae(levels))
    assert path.stat().st_size < 5_000
    tree = FrameTree()
    mesh = f'<mesh filename="{path}"/>'
    tree.attach_urdf(f'<robot name="bomb"><link name="bomb"><collision><geometry>{mesh}'
                     f'</geometry></collision><visual><geometry>{mesh}</geometry></visual>'
                     '</link></robot>', "world")
    return with_ball(tree, (0.5, 0.5, -1.0))


def test_nested_instances_past_max_triangles_are_an_error_naming_the_frame(tmp_path):
    tree = nested_tree(tmp_path, 20)  # 1,048,576 triangles from 2.9 kB
    with pytest.raises(GeometryError, match=r"frame 'bomb'.*1,048,576 triangles after "
                       r"instancing, over the limit max_triangles=1,000,000"):
        tree.clearance("bomb", "ball")


def test_nested_instances_within_a_raised_limit_are_measured_in_place(tmp_path):
    tree = nested_tree(tmp_path, 10)  # 1,024 triangles, all 10 m up
    with pytest.raises(GeometryError, match="max_triangles=1,000"):
        tree.clearance("bomb", "ball", limits=Limits(max_triangles=1_000))
    result = tree.clearance("bomb", "ball", limits=Limits(max_triangles=1_024))
    # the triangle at z = 10 m above the ball at (0.5, 0.5, -1): 11 m less the radius
    assert result.distance[0] == pytest.approx(11.0 - 0.1, abs=1e-9)


def test_the_page_leaves_a_mesh_past_max_triangles_out_with_a_warning(tmp_path):
    tree = nested_tree(tmp_path, 12)
    with pytest.warns(GeometryWarning, match=r"nested.dae.*4,096 triangles.*max_triangles"):
        pieces = load_geometry(tree, limits=Limits(max_triangles=4_000))
    assert [piece.link for piece in pieces] == []  # the ball has collision geometry only
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)
        pieces = load_geometry(tree, limits=Limits(max_triangles=4_096))
    heights = np.concatenate([piece.vertices[:, 2] for piece in pieces])
    assert sum(len(piece.faces) for piece in pieces) == 4_096 and heights.max() == 12.0


def test_a_node_that_instances_itself_is_an_error(tmp_path):
    text = nested_instances_dae(2).replace('<instance_node url="#n0"/>',
                                           '<instance_node url="#n2"/>', 1)
    (tmp_path / "loop.dae").write_text(text)
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("loop", f'<mesh filename="{tmp_path / "loop.dae"}"/>'), "world")
    with pytest.raises(GeometryError, match="frame 'loop'"):
        tree.clearance("loop", "ball")


@pytest.mark.parametrize(("geometry", "field"), [
    ('<box size="1e308 1e308 1e308"/>', "dimensions"),
    ('<sphere radius="1e300"/>', "dimensions"),
    ('<cylinder radius="0.1" length="1e200"/>', "dimensions"),
])
def test_shapes_too_large_to_measure_are_errors_naming_frame_and_field(geometry, field):
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("huge", geometry), "world")
    with pytest.raises(GeometryError, match=rf"frame 'huge': field 'collision\[0\]\.{field}'"):
        tree.clearance("huge", "ball")


def test_a_shape_placed_beyond_reach_is_an_error_naming_frame_and_time():
    tree = FrameTree()
    tree.add("away", "world", Pose(translation=[[0.0, 0, 0], [1e300, 0, 0]], times=[0.0, 2.0]))
    tree.attach_urdf(one_link("far", '<sphere radius="0.1"/>'), "away")
    with_ball(tree)
    with pytest.raises(GeometryError, match=r"frame 'far'.* at 1 s: positions must be finite"):
        tree.clearance("far", "ball", times=[0.0, 1.0])
    assert tree.clearance("far", "ball", times=[0.0]).distance[0] == pytest.approx(2.8)


@pytest.mark.parametrize("scale", ["1e300 1 1", "1 1 1e155"])
def test_a_mesh_scaled_past_reach_is_an_error(tmp_path, scale):
    path = write_stl(tmp_path / "tri.stl", [[0, 0, 0], [1, 0, 0], [0, 1, 1]], [[0, 1, 2]])
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("scaled", f'<mesh filename="{path}" scale="{scale}"/>'), "world")
    with pytest.raises(GeometryError, match=r"frame 'scaled'.*finite and within"):
        tree.clearance("scaled", "ball")


def test_a_mesh_with_a_nan_corner_is_an_error(tmp_path):
    path = write_stl(tmp_path / "nan.stl", [[0, 0, 0], [1, 0, 0], [0, 1, np.nan]], [[0, 1, 2]])
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("broken", f'<mesh filename="{path}"/>'), "world")
    with pytest.raises(GeometryError, match=r"frame 'broken'"):
        tree.clearance("broken", "ball")


def test_triangles_of_no_area_are_left_out_not_measured_as_contact(tmp_path):
    """coal reads a ball 0.9 m beside a triangle of three points on a line as -0.1 m."""
    flat = [[0, 0, 0], [1, 0, 0], [2, 0, 0]]
    path = write_stl(tmp_path / "flat.stl", [*flat, [0, 0, -1], [1, 0, -1], [0, 0, -2]],
                     [[0, 1, 2], [3, 4, 5]])
    tree = with_ball(FrameTree(), (0.5, 1.0, 0.0))
    tree.attach_urdf(one_link("part", f'<mesh filename="{path}"/>'), "world")
    # the one real triangle lies in the plane y = 0, below z = -1: the ball is above its edge
    assert tree.clearance("part", "ball").distance[0] == pytest.approx(np.hypot(1.0, 1.0) - 0.1)
    only_flat = write_stl(tmp_path / "only_flat.stl", flat, [[0, 1, 2]])
    tree.attach_urdf(one_link("sheet", f'<mesh filename="{only_flat}"/>'), "world")
    with pytest.raises(GeometryError, match=r"frame 'sheet'.*no triangle of non-zero area"):
        tree.clearance("sheet", "ball")


@pytest.mark.parametrize("how", ["instances", "elements"])
def test_nodes_nested_thousands_deep_are_an_error_not_a_crash(tmp_path, how):
    text = nested_instances_dae(3000, fan=1)
    if how == "elements":  # <node> inside <node>, 3000 deep, around the triangle's node
        inner = '<node id="n0"><instance_geometry url="#tri"/></node>'
        nested = "<node>" * 3000 + inner + "</node>" * 3000
        text = re.sub(r"<library_nodes>.*</library_nodes>", "", text, flags=re.S)
        text = text.replace('<instance_node url="#n3000"/>', nested)
    (tmp_path / "deep.dae").write_text(text)
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("deep", f'<mesh filename="{tmp_path / "deep.dae"}"/>'), "world")
    with pytest.raises(GeometryError, match=r"frame 'deep'.*cannot be read"):
        tree.clearance("deep", "ball")


def test_a_mesh_file_over_max_decompressed_bytes_is_not_opened(tmp_path):
    path = write_stl(tmp_path / "tri.stl", [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    tree = with_ball(FrameTree())
    tree.attach_urdf(one_link("part", f'<mesh filename="{path}"/>'), "world")
    size = path.stat().st_size
    with pytest.raises(GeometryError, match=rf"frame 'part'.*max_decompressed_bytes={size - 1}"):
        tree.clearance("part", "ball", limits=Limits(max_decompressed_bytes=size - 1))
    measured = tree.clearance("part", "ball", limits=Limits(max_decompressed_bytes=size))
    assert measured.distance[0] == pytest.approx(2.0 - 0.1, abs=1e-9)  # from (1, 0, 0)
