"""A closed mesh is a solid for the clearance, an open mesh a surface (distances by hand).

coal measures a mesh as a surface of triangles; the clearance makes a closed mesh a solid:
a shape wholly inside it is in contact, at minus the distance between the surfaces.
"""

from __future__ import annotations

import numpy as np
import pytest

from meshes import CUBE_CORNERS, CUBE_TRIANGLES, write_cube_stl, write_stl
from pinframes import Box, FrameTree, Mesh, Pose, Sphere

# a ball of radius 0.05 moving along x through a meshed box of edge 0.4 centred on the origin
CENTRES = np.array([0.0, 0.05, 0.12, 0.2, 0.3, 0.5])


def fixture_with_ball(mesh_path, ball=None) -> FrameTree:
    """The meshed fixture at the origin and ``ball`` (default: a ball of radius 0.05)
    moving through ``CENTRES`` along x, one per second."""
    tree = FrameTree()
    tree.add("fixture", "world")
    tree.add_geometry("fixture", Mesh(mesh_path))
    tree.add("ball", "world", Pose(translation=np.stack([CENTRES, 0 * CENTRES, 0 * CENTRES],
                                                        axis=1),
                                   rotation=[[0, 0, 0, 1]] * len(CENTRES),
                                   times=np.arange(len(CENTRES), dtype=float)))
    tree.add_geometry("ball", Sphere(0.05) if ball is None else ball)
    return tree


def test_a_ball_inside_a_closed_meshed_box_is_in_contact(tmp_path):
    tree = fixture_with_ball(write_cube_stl(tmp_path / "box.stl", 0.4))
    result = tree.clearance("fixture", "ball")
    gap = 0.2 - CENTRES - 0.05  # from the ball to the face at x = 0.2, inside
    outside = CENTRES - 0.2 - 0.05  # from the face to the ball, outside
    inside = CENTRES + 0.05 < 0.2
    assert inside.tolist() == [True, True, True, False, False, False]
    assert result.in_contact.tolist() == [True, True, True, True, False, False]
    np.testing.assert_allclose(result.distance[inside], -gap[inside], atol=1e-7)
    assert result.distance[3] <= 1e-7  # the ball crosses the surface
    np.testing.assert_allclose(result.distance[4:], outside[4:], atol=1e-7)


def test_an_open_meshed_box_is_a_surface(tmp_path):
    """Without its top face the box is a sheet: a ball inside is clear of it."""
    tree = fixture_with_ball(write_cube_stl(tmp_path / "open.stl", 0.4, open_top=True))
    result = tree.clearance("fixture", "ball")
    # inside: the nearest remaining face is x = 0.2 (the bottom and sides are 0.2 away too)
    expected = np.where(CENTRES + 0.05 < 0.2, 0.2 - CENTRES - 0.05, CENTRES - 0.25)
    np.testing.assert_allclose(result.distance[[0, 1, 2, 5]], expected[[0, 1, 2, 5]], atol=1e-7)
    assert not result.in_contact[[0, 1, 2, 5]].any()


def test_a_box_and_a_mesh_inside_a_closed_mesh_are_in_contact(tmp_path):
    outer = write_cube_stl(tmp_path / "outer.stl", 0.4)
    inner = write_cube_stl(tmp_path / "inner.stl", 0.1)
    for shape, half in ((Box([0.1, 0.1, 0.1]), 0.05), (Mesh(inner), 0.05)):
        tree = fixture_with_ball(outer, ball=shape)
        result = tree.clearance("fixture", "ball")
        np.testing.assert_allclose(result.distance[:3], -(0.2 - CENTRES[:3] - half), atol=1e-7)
        # and the other way round: the big mesh around the small one
        swapped = tree.clearance("ball", "fixture")
        np.testing.assert_allclose(swapped.distance, result.distance, atol=1e-12)


def test_two_pieces_one_inside_one_outside_count_as_inside(tmp_path):
    """A mesh of two small cubes, one inside the big closed box, one 1 m away."""
    outer = write_cube_stl(tmp_path / "outer.stl", 0.4)
    small = CUBE_CORNERS * 0.05
    vertices = np.concatenate([small, small + np.array([1.0, 0.0, 0.0])])
    triangles = np.concatenate([CUBE_TRIANGLES, CUBE_TRIANGLES + 8])
    pair = write_stl(tmp_path / "pair.stl", vertices, triangles)
    tree = FrameTree()
    tree.add("fixture", "world")
    tree.add_geometry("fixture", Mesh(outer))
    tree.add("pair", "world")
    tree.add_geometry("pair", Mesh(pair))
    result = tree.clearance("fixture", "pair")
    assert result.distance[0] == pytest.approx(-(0.2 - 0.05), abs=1e-7)


def test_the_answer_does_not_depend_on_the_sphere_bounds_order(tmp_path):
    """A far ball checked first by its bound and a ball inside the box: the inside one wins."""
    tree = fixture_with_ball(write_cube_stl(tmp_path / "box.stl", 0.4))
    tree.add("far", "world", Pose([0.0, 0.0, 0.26]))
    tree.add_geometry("far", Sphere(0.05))
    result = tree.clearance("fixture", ["ball", "far"], times=[0.0])
    assert result.closest[0].tolist() == ["fixture", "ball"]
    assert result.distance[0] == pytest.approx(-0.15, abs=1e-7)


def test_a_mirrored_closed_mesh_is_still_a_solid(tmp_path):
    """scale -1 along x turns every triangle over: still closed, the ball inside in contact."""
    box = write_cube_stl(tmp_path / "box.stl", 0.4)
    tree = FrameTree()
    tree.add("fixture", "world")
    tree.add_geometry("fixture", Mesh(box, scale=[-1.0, 1.0, 1.0]))
    tree.add("ball", "world", Pose([0.05, 0.0, 0.0]))
    tree.add_geometry("ball", Sphere(0.05))
    assert tree.clearance("fixture", "ball").distance[0] == pytest.approx(-0.1, abs=1e-7)
