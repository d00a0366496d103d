"""ROS-Industrial's KUKA meshes as they come (tests/data/kuka_experimental, Apache-2.0).

- The KR210 L150's visual meshes are COLLADA in inches (``<unit meter="0.0254">``): drawn and
  measured at the size of its collision meshes (STL in metres), not 39 times larger.
- The LBR iiwa 14's base mesh goes on after ``</COLLADA>`` (NUL bytes and the tail of an older
  file): the page and the clearance both read it, as the triangles of its first document.
- The KR210's collision meshes: clearance equal to Pinocchio + coal called directly on the
  same URDF.

The two COLLADA files are stored xz-compressed; each test unpacks what it needs.
"""

from __future__ import annotations

import lzma
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import coal
import numpy as np
import pinocchio as pin
import pytest
import trimesh

from pinframes import Box, FrameTree, GeometryWarning, Pose, Sphere
from pinframes.kinematics.collision.mesh_reader import read_mesh
from pinframes.view import load_geometry

DATA = Path(__file__).resolve().parents[1] / "data" / "kuka_experimental"
KR210 = DATA / "kuka_kr210_support" / "urdf" / "kr210l150.urdf"
KR210_BASE_DAE = "kuka_kr210_support/meshes/kr210l150/visual/base_link.dae"
IIWA_BASE_DAE = "kuka_lbr_iiwa_support/meshes/lbr_iiwa_14_r820/visual/base_link.dae"
ARM_JOINTS = [f"joint_a{i}" for i in range(1, 7)]


def unpacked(name: str, folder: Path) -> Path:
    """The stored ``name`` + ``.xz`` unpacked to ``folder / name``."""
    target = folder / name
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_bytes(lzma.decompress((DATA / (name + ".xz")).read_bytes()))
    return target


def kr210(tmp_path: Path) -> FrameTree:
    tree = FrameTree()
    tree.attach_urdf(KR210, "world", prefix="kr210/")
    unpacked(KR210_BASE_DAE, tmp_path)
    return tree


def in_link(pieces, link: str) -> np.ndarray:
    """The triangle corners of ``link``'s pieces in the link frame, (n, 3) metres."""
    corners = [piece.vertices[piece.faces.reshape(-1)] @ piece.pose_in_frame[:3, :3].T
               + piece.pose_in_frame[:3, 3] for piece in pieces if piece.link == link]
    return np.concatenate(corners)


def test_kr210_visual_base_is_drawn_at_the_size_of_its_collision_mesh(tmp_path):
    tree = kr210(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", GeometryWarning)  # the other links' visuals: not copied
        visual = in_link(load_geometry(tree, package_dirs=[tmp_path]), "base_link")
    collision = in_link(load_geometry(tree, collision=True), "base_link")
    # the collision mesh is a coarser hull of the drawn part: within a centimetre
    np.testing.assert_allclose(visual.min(axis=0), collision.min(axis=0), atol=0.01)
    np.testing.assert_allclose(visual.max(axis=0), collision.max(axis=0), atol=0.01)
    # without the unit (as trimesh reads the file) it is 1 / 0.0254 times larger
    raw = trimesh.load(str(tmp_path / KR210_BASE_DAE), force="scene").bounds
    extent = np.ptp(visual, axis=0)
    np.testing.assert_allclose(np.sort(raw[1] - raw[0]) * 0.0254, np.sort(extent), rtol=1e-6)


def test_kr210_visual_clearance_is_the_collision_clearance_not_a_contact(tmp_path):
    tree = kr210(tmp_path)
    tree.add("ball_at", "world", Pose([0.75, 0.1, 0.3]))
    tree.add_geometry("ball_at", Sphere(0.05))
    visual = tree.clearance("kr210/base_link", "ball_at", geometry="visual",
                            package_dirs=[tmp_path])
    collision = tree.clearance("kr210/base_link", "ball_at")
    assert collision.distance[0] > 0.1
    assert visual.distance[0] == pytest.approx(collision.distance[0], abs=0.02)


def test_iiwa_base_with_bytes_after_the_document_is_read_by_page_and_clearance(tmp_path):
    path = unpacked(IIWA_BASE_DAE, tmp_path)
    data = path.read_bytes()
    end = data.index(b"</COLLADA>") + len(b"</COLLADA>")
    assert len(data) - end > 70_000 and b"\0" in data[end:]  # what the stored file holds
    # the triangles of the first document, counted with ElementTree: fans of each polygon
    namespace = {"c": "http://www.collada.org/2005/11/COLLADASchema"}
    root = ET.fromstring(data[:end])
    counts = [int(n) for vcount in root.iterfind(".//c:polylist/c:vcount", namespace)
              for n in vcount.text.split()]
    mesh = read_mesh(path)
    assert mesh.triangle_count == sum(n - 2 for n in counts) > 18_000
    # assimp (coal's loader) reads the same file: the same box
    theirs = np.asarray(coal.MeshLoader().load(str(path), np.ones(3)).vertices())
    vertices, _ = mesh.merged()
    np.testing.assert_allclose(vertices.min(axis=0), theirs.min(axis=0), atol=1e-9)
    np.testing.assert_allclose(vertices.max(axis=0), theirs.max(axis=0), atol=1e-9)
    urdf = (f'<robot name="iiwa"><link name="base"><visual><geometry><mesh filename="{path}"/>'
            f'</geometry></visual><collision><geometry><mesh filename="{path}"/></geometry>'
            '</collision></link></robot>')
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)
        pieces = load_geometry(tree)
    assert sum(piece.faces.shape[0] for piece in pieces) == mesh.triangle_count
    tree.add("ball_at", "world", Pose([0.5, 0.1, 0.1]))
    tree.add_geometry("ball_at", Sphere(0.05))
    result = tree.clearance("base", "ball_at")
    # coal on assimp's reading of the whole file (which stops at the end tag too)
    theirs_model = coal.MeshLoader().load(str(path), np.ones(3))
    expected = coal.distance(theirs_model, coal.Transform3s(), coal.Sphere(0.05),
                             coal.Transform3s(np.eye(3), np.array([0.5, 0.1, 0.1])),
                             coal.DistanceRequest(), coal.DistanceResult())
    assert result.distance[0] == pytest.approx(expected, abs=1e-9)


def pinocchio_distances(values: np.ndarray, obstacles: dict[str, tuple]) -> np.ndarray:
    """Per sample, the smallest distance between the KR210's collision meshes and the
    obstacles, from Pinocchio's own model and geometry (buildGeomFromUrdf)."""
    model = pin.buildModelFromUrdf(str(KR210))
    geometry = pin.buildGeomFromUrdf(model, str(KR210), pin.GeometryType.COLLISION,
                                     package_dirs=[str(DATA)])
    robot = geometry.ngeoms
    for name, (shape, placement) in obstacles.items():
        geometry.addGeometryObject(pin.GeometryObject(name, 0, pin.SE3(placement), shape))
    for i in range(robot):
        for j in range(robot, geometry.ngeoms):
            geometry.addCollisionPair(pin.CollisionPair(i, j))
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    found = []
    for row in values:
        q = pin.neutral(model)
        for name, value in zip(ARM_JOINTS, row, strict=True):
            q[model.joints[model.getJointId(name)].idx_q] = value
        pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
        pin.computeDistances(geometry, geometry_data)
        found.append(min(result.min_distance for result in geometry_data.distanceResults))
    return np.array(found)


def test_kr210_collision_meshes_against_pinocchio_compute_distances(rng):
    obstacles = {"table": (Box([0.8, 0.6, 0.1]), coal.Box(0.8, 0.6, 0.1),
                           Pose.from_xyz_rpy(1.9, 0.4, 0.9, 0.0, 0.3, 0.5)),
                 "ball": (Sphere(0.15), coal.Sphere(0.15),
                          Pose.from_xyz_rpy(-0.4, 1.6, 1.4, 0.0, 0.0, 0.0))}
    tree = FrameTree()
    tree.attach_urdf(KR210, "world", prefix="kr210/")
    for name, (shape, _, pose) in obstacles.items():
        tree.add(name, "world", pose)
        tree.add_geometry(name, shape)
    times = np.arange(12.0)
    joints = [tree.joints[f"kr210/{name}"] for name in ARM_JOINTS]
    low = np.maximum([joint.lower for joint in joints], -1.2)
    high = np.minimum([joint.upper for joint in joints], 1.2)
    values = low + (high - low) * rng.random((times.size, 6))
    tree.set_joint_trajectory(times, values, [f"kr210/{name}" for name in ARM_JOINTS])
    result = tree.clearance("kr210/*", list(obstacles))
    expected = pinocchio_distances(values, {name: (made, pose.matrix) for name, (_, made, pose)
                                            in obstacles.items()})
    np.testing.assert_allclose(result.distance, expected, atol=1e-9)
    assert np.all(expected > -1.0) and np.ptp(expected) > 0.05  # the arm moves


def test_the_kr210_collision_stl_files_are_what_assimp_reads():
    for path in sorted((DATA / "kuka_kr210_support/meshes/kr210l150/collision").glob("*.stl")):
        ours, triangles = read_mesh(path).merged()
        theirs = coal.MeshLoader().load(str(path), np.ones(3))
        assert triangles.shape[0] == theirs.num_tris
        np.testing.assert_array_equal(ours, np.asarray(theirs.vertices()))
