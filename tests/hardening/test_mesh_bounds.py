"""Mesh files that cost more than their triangle count said: COLLADA nodes that instance empty
nodes, one file of many triangles named from several links, STL/OBJ/PLY/OFF files loaded
whole before they were counted, a polygon of a million corners, a unit of 0 m."""

from __future__ import annotations

import os
import struct
import warnings
from importlib import metadata
from pathlib import Path

import coal
import numpy as np
import pytest

from hardening.capped import run_capped
from meshes import nested_instances_dae
from pinframes import FrameTree, GeometryError, GeometryWarning, Limits, Pose
from pinframes.view import load_geometry


def example_robot_meshes(suffix: str, count: int) -> list[Path]:
    """The first ``count`` mesh files of example-robot-data ending in ``suffix``."""
    found = sorted(Path(str(file.locate())) for file in metadata.files("example-robot-data") or []
                   if file.name.lower().endswith(suffix))
    return found[:count]


def mesh_robot(tree: FrameTree, path: Path, scales: list[float]) -> FrameTree:
    """One link per scale, each naming the mesh ``path`` as collision and visual geometry."""
    for index, scale in enumerate(scales):
        mesh = f'<mesh filename="{path}" scale="{scale} {scale} {scale}"/>'
        tree.attach_urdf(f'<robot name="r{index}"><link name="link{index}"><collision>'
                         f'<geometry>{mesh}</geometry></collision><visual><geometry>{mesh}'
                         '</geometry></visual></link></robot>', "world", prefix=f"r{index}/")
    # the ball moves (and stays put): pairs of frames fixed to each other are not checked
    tree.add("ball_at", "world", Pose([[0.5, 0.5, -1.0]] * 2, times=[0.0, 1.0]))
    tree.attach_urdf('<robot name="ball"><link name="ball"><collision><geometry><sphere '
                     'radius="0.1"/></geometry></collision></link></robot>', "ball_at")
    return tree


CLEARANCE = """
from pathlib import Path
from pinframes import FrameTree
from hardening.test_mesh_bounds import mesh_robot
scales = [float(scale) for scale in sys.argv[3].split(",")]
tree = mesh_robot(FrameTree(), Path(sys.argv[2]), scales)
print("DISTANCE", round(float(tree.clearance("r*", "ball").distance[0]), 9))
"""


def empty_node_bomb(levels: int) -> str:
    """One triangle at the root node beside ``levels`` levels of nodes that each instance
    the empty node below them twice (``2 ** levels`` visits of nothing)."""
    return nested_instances_dae(levels).replace(
        '<node id="n0"><instance_geometry url="#tri"/></node>', '<node id="n0"/>').replace(
        '<node id="root">', '<node id="root"><instance_geometry url="#tri"/>')


def test_empty_nodes_instanced_twice_per_level_are_not_walked(tmp_path):
    # 40 levels of empty nodes: 2**40 visits before (the clearance and the page hung)
    path = tmp_path / "empty.dae"
    path.write_text(empty_node_bomb(40))
    assert path.stat().st_size < 8_000
    outcome = run_capped(CLEARANCE + "from pinframes.view import load_geometry\n"
                         "print(len(load_geometry(tree, collision=True)))", str(path), "1")
    # the triangle (0,0,0), (1,0,0), (0,1,0) 1 m above the ball's centre: 0.9 m
    assert outcome == "DISTANCE 0.9\n2", outcome


def test_the_triangle_bound_counts_every_link_of_the_request(tmp_path):
    path = tmp_path / "nested.dae"
    path.write_text(nested_instances_dae(4))  # 16 triangles, all at z = 4 m
    scales = [1.0, 1.0 + 1e-9, 1.0 + 2e-9, 1.0 + 3e-9]
    tree = mesh_robot(FrameTree(), path, scales)
    with pytest.raises(GeometryError, match=r"bring the meshes of this request to 64 .*"
                       r"max_triangles=63") as caught:
        tree.clearance("r*", "ball", limits=Limits(max_triangles=63))
    assert caught.value.frame == "r3/link3" and caught.value.field == "collision[0].mesh"
    assert caught.value.file == str(path)
    # every link's triangle 4 m up, 5 m above the ball's centre
    distance = tree.clearance("r*", "ball", limits=Limits(max_triangles=64)).distance[0]
    assert distance == pytest.approx(5.0 - 0.1, abs=1e-6)
    with pytest.warns(GeometryWarning, match=r"link 'link3'.*max_triangles=63"):
        pieces = load_geometry(tree, limits=Limits(max_triangles=63))
    assert sorted({piece.frame for piece in pieces}) == ["r0/link0", "r1/link1", "r2/link2"]


@pytest.mark.slow
def test_half_a_million_instanced_triangles_from_four_links_are_refused_at_once(tmp_path):
    # 4.7 kB, 524,288 triangles, named from 4 links: 162 s and 1.7 GB before
    path = tmp_path / "nested.dae"
    path.write_text(nested_instances_dae(19))
    outcome = run_capped(CLEARANCE, str(path), "1,1.000000001,1.000000002,1.000000003")
    assert outcome.startswith("GeometryError "), outcome
    assert "frame 'r1/link1'" in outcome and "1,048,576" in outcome, outcome
    assert "max_triangles=1,000,000" in outcome and str(path) in outcome, outcome


READ = """
from pathlib import Path
from pinframes.kinematics.collision.mesh_reader import read_mesh
print("READ", read_mesh(Path(sys.argv[2])).triangle_count)
"""


def test_a_binary_stl_is_counted_from_its_header_before_loading(tmp_path):
    # 1,000,001 triangles (a sparse 50 MB file): assimp took 19 s and 1.2 GB before the bound
    path = tmp_path / "big.stl"
    count = 1_000_001
    with open(path, "wb") as handle:
        handle.write(b"binary".ljust(80, b" ") + struct.pack("<I", count))
        handle.truncate(84 + 50 * count)
    outcome = run_capped(READ, str(path))
    assert outcome.startswith("GeometryError " + str(path)), outcome
    assert "holds 1,000,001 triangles (counted before loading)" in outcome, outcome


def test_a_polygon_of_too_many_corners_is_refused(tmp_path):
    # one OBJ face of 400,000 corners (2.4 MB): assimp's triangulation ran past 90 s
    corners = 400_000
    path = tmp_path / "fan.obj"
    angles = np.linspace(0, 2 * np.pi, corners, endpoint=False)
    lines = [f"v {np.cos(a):.4f} {np.sin(a):.4f} 0" for a in angles]
    lines.append("f " + " ".join(str(n) for n in range(1, corners + 1)))
    path.write_text("\n".join(lines))
    outcome = run_capped(READ, str(path))
    assert outcome.startswith("GeometryError " + str(path)), outcome
    assert "a polygon of 400,000 corners, over the 10,000" in outcome, outcome


def written_meshes(folder: Path) -> list[Path]:
    """A box and a fan of quads and pentagons written by trimesh as ASCII and binary PLY,
    OFF, OBJ and ASCII STL."""
    import trimesh

    box = trimesh.creation.box((1.0, 2.0, 3.0))
    paths = []
    for name, options in (("box.ply", {"encoding": "binary"}), ("box_ascii.ply",
                          {"encoding": "ascii"}), ("box.off", {}), ("box.obj", {}),
                          ("box_ascii.stl", {"file_type": "stl_ascii"})):
        path = folder / name
        data = box.export(file_type=options.pop("file_type", path.suffix[1:]), **options)
        path.write_bytes(data if isinstance(data, bytes) else data.encode())
        paths.append(path)
    polygons = folder / "polygons.obj"
    polygons.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                        "f 1 2 3 4\nf 1 2 3 5 4 # a pentagon\nf 1/1 2/2 3/3\n")
    return [*paths, polygons]


def test_counts_before_loading_are_what_assimp_loads(tmp_path):
    from pinframes.kinematics.collision.mesh_counts import polygon_triangles

    for path in written_meshes(tmp_path):
        assert polygon_triangles(path) == coal.MeshLoader().load(str(path)).num_tris, path
    real = example_robot_meshes(".obj", 6) + example_robot_meshes(".stl", 6)
    assert len(real) == 12
    for path in real:
        # assimp drops the odd degenerate triangle of a real file: the count is a bound
        loaded = coal.MeshLoader().load(str(path)).num_tris
        assert loaded <= polygon_triangles(path) <= loaded * 1.01, path


@pytest.mark.parametrize("unit", ["0", "abc", "-1", "nan", "inf"])
def test_a_collada_unit_that_is_no_positive_number_is_refused(tmp_path, unit):
    path = tmp_path / "unit.dae"
    path.write_text(nested_instances_dae(1).replace('<unit meter="1"/>',
                                                    f'<unit meter="{unit}"/>'))
    tree = mesh_robot(FrameTree(), path, [1.0])
    with pytest.raises(GeometryError, match=rf"<unit meter> must be a positive number of "
                       rf"metres, got '{unit}'") as caught:
        tree.clearance("r*", "ball")
    assert caught.value.file == str(path) and caught.value.frame == "r0/link0"
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        assert load_geometry(tree) == []
    assert any("<unit meter>" in str(w.message) for w in seen)
    assert os.listdir(tmp_path) == ["unit.dae"]
