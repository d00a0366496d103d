"""Clearances of the UR5's meshes (example-robot-data) against Pinocchio + coal called directly.

The reference builds its own model and geometry (``pin.buildModelFromUrdf``,
``pin.buildGeomFromUrdf``), adds the obstacles as coal objects of its own, and takes the
smallest of ``pin.computeDistances`` over every robot-obstacle pair at every sample.
"""

from __future__ import annotations

from pathlib import Path

import coal
import numpy as np
import pinocchio as pin
import pytest

from pinframes import FrameTree, Pose
from urdf.test_robots_against_pinocchio import ROBOTS

pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")

PIPE = Path(__file__).resolve().parents[2] / "models/welding_cell/geometry/meshes/pipe.stl"
OBSTACLES = {  # frame: (URDF geometry, coal object, pose in the world at time 0)
    "table": ('<box size="0.6 0.4 0.05"/>', lambda: coal.Box(0.6, 0.4, 0.05),
              Pose.from_xyz_rpy(0.45, 0.1, 0.35, 0.0, 0.2, 0.4)),
    "ball": ('<sphere radius="0.08"/>', lambda: coal.Sphere(0.08),
             Pose.from_xyz_rpy(-0.3, 0.35, 0.55, 0, 0, 0)),
    "pipe": (f'<mesh filename="{PIPE}"/>',
             lambda: coal.MeshLoader().load(str(PIPE), np.ones(3)),
             Pose.from_xyz_rpy(0.1, -0.45, 0.4, 1.2, 0.0, 0.3)),
}
MOUNT = Pose(translation=[[0.0, 0.0, 0.1], [0.05, -0.02, 0.12]],
             rotation=[[0, 0, 0, 1], [0, 0, np.sin(0.15), np.cos(0.15)]], times=[0.0, 4.0])


def ur5_urdf() -> Path:
    assert ROBOTS is not None
    return ROBOTS / "ur_description" / "urdf" / "ur5_robot.urdf"


def cell(rng, samples: int):
    """The UR5 on a moving mount among three obstacles (the ball moves), random joints."""
    tree = FrameTree()
    tree.add("mount", "world", MOUNT)
    tree.attach_urdf(ur5_urdf(), "mount", prefix="ur5/")
    for name, (geometry, _, pose) in OBSTACLES.items():
        if name == "ball":
            pose = Pose(translation=[pose.translation, pose.translation + np.array([0.3, -0.2, 0])],
                        rotation=[pose.quaternion] * 2, times=[0.0, 4.0])
        tree.add(name + "_at", "world", pose)
        tree.attach_urdf(f'<robot name="{name}"><link name="{name}"><collision><geometry>'
                         f'{geometry}</geometry></collision></link></robot>', name + "_at")
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    times = np.linspace(0.0, 4.0, samples)
    values = rng.uniform(-np.pi, np.pi, size=(samples, len(names)))
    values[:, 1] = rng.uniform(-2.4, -0.6, samples)  # shoulder lifting the arm
    tree.set_joint_trajectory(times, values, names)
    return tree, times, dict(zip(names, values.T, strict=True))


def pinocchio_clearance(tree, times, values):
    """Per sample: the smallest distance, the next smallest, the pair of the smallest and its
    closest points (world), by Pinocchio."""
    urdf = ur5_urdf()
    model = pin.buildModelFromUrdf(str(urdf))
    share = urdf.parents[4]  # holds the package folder example-robot-data
    geometry = pin.buildGeomFromUrdf(model, str(urdf), pin.GeometryType.COLLISION,
                                     package_dirs=[str(share)])
    robot_objects = geometry.ngeoms
    for name, (_, make, _) in OBSTACLES.items():
        geometry.addGeometryObject(pin.GeometryObject(name, 0, pin.SE3.Identity(), make()))
    for i in range(robot_objects):
        for j in range(robot_objects, geometry.ngeoms):
            geometry.addCollisionPair(pin.CollisionPair(i, j))
    data, geometry_data = model.createData(), pin.GeometryData(geometry)
    mounts = tree.pose("mount", "world", times=times).matrix
    obstacles = {name: tree.pose(name, "world", times=times).matrix for name in OBSTACLES}
    found = []
    for k in range(len(times)):
        q = pin.neutral(model)
        for joint_id in range(1, model.njoints):
            q[model.joints[joint_id].idx_q] = values["ur5/" + model.names[joint_id]][k]
        base_from_world = np.linalg.inv(mounts[k])
        for index, name in enumerate(OBSTACLES):
            geometry.geometryObjects[robot_objects + index].placement = pin.SE3(
                base_from_world @ obstacles[name][k])
        pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
        pin.computeDistances(geometry, geometry_data)
        results = geometry_data.distanceResults
        order = sorted(range(len(results)), key=lambda p: results[p].min_distance)
        best, runner_up = order[0], results[order[1]].min_distance
        pair = geometry.collisionPairs[best]
        to_world = mounts[k][:3, :3], mounts[k][:3, 3]
        found.append((results[best].min_distance, runner_up,
                      model.frames[geometry.geometryObjects[pair.first].parentFrame].name,
                      geometry.geometryObjects[pair.second].name,
                      to_world[0] @ results[best].getNearestPoint1() + to_world[1],
                      to_world[0] @ results[best].getNearestPoint2() + to_world[1]))
    return found


def test_ur5_meshes_against_pinocchio_compute_distances(rng):
    tree, times, values = cell(rng, 30)
    result = tree.clearance("ur5/*", list(OBSTACLES), package_dirs=[])
    expected = pinocchio_clearance(tree, times, values)
    assert set(result.frames_a) == {f"ur5/{link}" for link in (
        "base_link", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
        "wrist_2_link", "wrist_3_link", "ee_link")}  # base and tool0 have no geometry
    np.testing.assert_allclose(result.distance, [e[0] for e in expected], atol=1e-6)
    assert result.distance.min() < 0.05 < result.distance.max()  # near and far samples
    for k, (distance, runner_up, link, obstacle, point_a, point_b) in enumerate(expected):
        if runner_up - distance > 1e-6:  # no tie: the same pair and the same points
            assert result.closest[k].tolist() == ["ur5/" + link, obstacle]
            np.testing.assert_allclose(result.point_a[k], point_a, atol=1e-6)
            np.testing.assert_allclose(result.point_b[k], point_b, atol=1e-6)


def test_to_pinocchio_geometry_sits_where_build_geom_from_urdf_puts_it(rng):
    tree, times, values = cell(rng, 5)
    compiled = tree.to_pinocchio()
    ours = compiled.geometry_model("collision")
    ours_data, model_data = pin.GeometryData(ours), compiled.model.createData()
    urdf = ur5_urdf()
    model = pin.buildModelFromUrdf(str(urdf))
    theirs = pin.buildGeomFromUrdf(model, str(urdf), pin.GeometryType.COLLISION,
                                   package_dirs=[str(urdf.parents[4])])
    theirs_data, data = pin.GeometryData(theirs), model.createData()
    assert sorted(obj.name for obj in ours.geometryObjects) == sorted(
        [f"ur5/{obj.name}" for obj in theirs.geometryObjects] + [f"{n}_0" for n in OBSTACLES])
    mounts = tree.pose("mount", "world", times=times).matrix
    for k, q in enumerate(compiled.configurations(times)):
        pin.updateGeometryPlacements(compiled.model, model_data, ours, ours_data, q)
        q_ur5 = pin.neutral(model)
        for joint_id in range(1, model.njoints):
            q_ur5[model.joints[joint_id].idx_q] = values["ur5/" + model.names[joint_id]][k]
        pin.updateGeometryPlacements(model, data, theirs, theirs_data, q_ur5)
        for index, obj in enumerate(theirs.geometryObjects):
            mine = ours.getGeometryId("ur5/" + obj.name)
            np.testing.assert_allclose(ours_data.oMg[mine].homogeneous,
                                       mounts[k] @ theirs_data.oMg[index].homogeneous,
                                       atol=1e-12)
            assert type(ours.geometryObjects[mine].geometry) is type(obj.geometry)
            assert ours.geometryObjects[mine].meshPath == obj.meshPath
