"""Link geometry placements against yourdfpy's scene graph and Pinocchio's GeometryModel.

The robots are mounted on a frame of a tree and driven with random joint values; each loaded
piece of geometry, placed by ``tree.pose(piece.frame) @ piece.pose_in_frame``, must sit where
yourdfpy's own forward kinematics put its scene nodes (the same triangles, per link) and
where Pinocchio's ``updateGeometryPlacements`` puts the matching GeometryObject.
"""

from __future__ import annotations

import warnings
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import yourdfpy

from pinframes import FrameTree, Pose
from pinframes.view import GeometryWarning, load_geometry

BUNDLED_ROBOT = Path(__file__).resolve().parents[2] / "models/welding_robot/welding_robot.urdf"
MOUNT = Pose.from_xyz_rpy(0.4, -0.2, 0.3, 0.1, -0.2, 0.7)


def panda_urdf() -> Path | None:
    try:
        files = metadata.files("example-robot-data") or []
    except metadata.PackageNotFoundError:
        return None
    return next((Path(f.locate()) for f in files if f.name == "panda.urdf"), None)


PANDA = panda_urdf()
needs_panda = pytest.mark.skipif(PANDA is None, reason="example-robot-data is not installed")


def mounted(urdf: Path, rng: np.random.Generator, samples: int = 4):
    """A tree with the robot on ``mount`` and random joint values at ``samples`` times."""
    tree = FrameTree(root="world")
    tree.add("mount", "world", MOUNT)
    tree.attach_urdf(urdf, "mount", prefix="r/")
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    low = np.array([max(tree.joints[n].lower or -3.0, -3.0) for n in names])
    high = np.array([min(tree.joints[n].upper or 3.0, 3.0) for n in names])
    values = low + (high - low) * rng.random((samples, len(names)))
    times = np.arange(samples, dtype=float)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # joint-limit warnings do not matter here
        tree.set_joint_trajectory(times, values, names)
    by_joint = dict(zip([n.removeprefix("r/") for n in names], values.T, strict=True))
    for name, joint in tree.joints.items():  # mimic joints are plain joints in Pinocchio
        if joint.mimic is not None:
            primary = by_joint[joint.mimic.joint.removeprefix("r/")]
            by_joint[name.removeprefix("r/")] = joint.mimic.multiplier * primary + \
                joint.mimic.offset
    return tree, times, by_joint


def placements(tree: FrameTree, pieces, times) -> list[np.ndarray]:
    """Each piece in the world at every time, shape (T, 4, 4), through pinframes' queries."""
    return [tree.pose(p.frame, relative_to="world", times=times).matrix @ p.pose_in_frame
            for p in pieces]


def pinocchio_placements(urdf: Path, kind, values: dict[str, np.ndarray], count: int,
                         package_dirs: list[str]):
    """Pinocchio's GeometryObjects: (link, shape, world placement per time)."""
    model = pin.buildModelFromUrdf(str(urdf))
    geometry = pin.buildGeomFromUrdf(model, str(urdf), kind, package_dirs=package_dirs)
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    mount = MOUNT.matrix
    found = {i: [] for i in range(geometry.ngeoms)}
    for k in range(count):
        q = pin.neutral(model)
        for joint_id in range(1, model.njoints):
            q[model.joints[joint_id].idx_q] = values[model.names[joint_id]][k]
        pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
        for i in range(geometry.ngeoms):
            found[i].append(mount @ geometry_data.oMg[i].homogeneous)
    return [(model.frames[obj.parentFrame].name, obj.geometry, np.array(found[i]))
            for i, obj in enumerate(geometry.geometryObjects)]


def test_bundled_robot_visuals_match_yourdfpy_and_pinocchio(rng):
    tree, times, values = mounted(BUNDLED_ROBOT, rng)
    pieces = load_geometry(tree)
    ours = placements(tree, pieces, times)
    theirs = pinocchio_placements(BUNDLED_ROBOT, pin.GeometryType.VISUAL, values, len(times),
                                  [])
    assert [p.link for p in pieces] == [link for link, _, _ in theirs]
    for piece, placed, (_, shape, expected) in zip(pieces, ours, theirs, strict=True):
        np.testing.assert_allclose(placed, expected, atol=1e-12)
        half = (piece.vertices.max(axis=0) - piece.vertices.min(axis=0)) / 2
        if type(shape).__name__ == "Box":
            np.testing.assert_allclose(half, shape.halfSide, atol=1e-12)
        else:  # cylinders along their z axis: radius and half length
            assert type(shape).__name__ == "Cylinder"
            np.testing.assert_allclose(half[:2], shape.radius, atol=1e-12)
            np.testing.assert_allclose(half[2], shape.halfLength, atol=1e-12)
    _against_yourdfpy(BUNDLED_ROBOT, tree, pieces, ours, values, len(times))


@needs_panda
def test_panda_visual_meshes_match_yourdfpy_scene_graph_and_pinocchio(rng):
    """package:// URIs resolved from the URDF's ancestors; every DAE node placed as yourdfpy
    places it, and each link's visual frame where Pinocchio puts its GeometryObject."""
    tree, times, values = mounted(PANDA, rng)
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)  # every mesh must be found
        pieces = load_geometry(tree)
    assert {p.link for p in pieces} == {f"panda_link{i}" for i in range(8)} | {
        "panda_hand", "panda_leftfinger", "panda_rightfinger"}
    assert all(p.source.endswith(".dae") for p in pieces)
    ours = placements(tree, pieces, times)
    _against_yourdfpy(PANDA, tree, pieces, ours, values, len(times))
    share = str(PANDA.parents[4])
    theirs = pinocchio_placements(PANDA, pin.GeometryType.VISUAL, values, len(times), [share])
    parsed = yourdfpy.URDF.load(str(PANDA), build_scene_graph=False, load_meshes=False)
    origins = {link.name: np.eye(4) if link.visuals[0].origin is None else
               link.visuals[0].origin for link in parsed.robot.links if link.visuals}
    for link, _, expected in theirs:
        frame = "r/" + link
        placed = tree.pose(frame, relative_to="world", times=times).matrix @ origins[link]
        np.testing.assert_allclose(placed, expected, atol=1e-9)


@needs_panda
def test_panda_collision_meshes_match_pinocchio_one_to_one(rng):
    tree, times, values = mounted(PANDA, rng)
    pieces = load_geometry(tree, collision=True)
    assert {p.source.rsplit("/", 1)[-1] for p in pieces} == {
        *(f"link{i}.stl" for i in range(8)), "hand.stl", "box"}  # the fingers are boxes
    ours = placements(tree, pieces, times)
    share = str(PANDA.parents[4])
    theirs = pinocchio_placements(PANDA, pin.GeometryType.COLLISION, values, len(times),
                                  [share])
    assert [p.link for p in pieces] == [link for link, _, _ in theirs]
    for piece, placed, (_, shape, expected) in zip(pieces, ours, theirs, strict=True):
        np.testing.assert_allclose(placed, expected, atol=1e-9)
        shape.computeLocalAABB()  # the same STL read by assimp: the same bounding box
        np.testing.assert_allclose(piece.vertices.min(axis=0), shape.aabb_local.min_,
                                   atol=1e-6)
        np.testing.assert_allclose(piece.vertices.max(axis=0), shape.aabb_local.max_,
                                   atol=1e-6)


def _against_yourdfpy(urdf: Path, tree, pieces, ours, values, count) -> None:
    """yourdfpy loads the same URDF on its own: per link and time, its scene's triangles
    (every node placed) must be ours: their number, bounding box and mean corner."""
    model = yourdfpy.URDF.load(str(urdf), load_meshes=True, build_scene_graph=True)
    nodes = model.scene.graph.nodes_geometry
    links = sorted({piece.link for piece in pieces})
    assert links == sorted({model.scene.graph.transforms.parents[node] for node in nodes})
    for k in range(count):
        model.update_cfg({name: float(v[k]) for name, v in values.items()
                          if name in model.actuated_joint_names})
        for link in links:
            theirs = [_corners(model.scene.graph.get(node)[0],
                               model.scene.geometry[model.scene.graph.get(node)[1]])
                      for node in nodes if model.scene.graph.transforms.parents[node] == link]
            expected = MOUNT.matrix[:3, :3] @ np.concatenate(theirs).T
            expected = expected.T + MOUNT.matrix[:3, 3]
            placed = np.concatenate([_corners(matrix[k], piece) for piece, matrix
                                     in zip(pieces, ours, strict=True) if piece.link == link])
            assert placed.shape == expected.shape
            for statistic in (np.min, np.max, np.mean):
                np.testing.assert_allclose(statistic(placed, axis=0),
                                           statistic(expected, axis=0), atol=1e-9)


def _corners(matrix: np.ndarray, mesh) -> np.ndarray:
    """Every triangle corner of ``mesh`` (a LinkGeometry or a trimesh) placed by
    ``matrix``, shape (3 m, 3)."""
    faces = getattr(mesh, "faces", None)
    corners = np.asarray(mesh.vertices)[np.asarray(faces).reshape(-1)]
    return corners @ matrix[:3, :3].T + matrix[:3, 3]
