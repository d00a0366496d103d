"""Velocities and Jacobians, against hand-derived values, finite differences and Pinocchio.

Pinocchio is called directly on models built here (``buildModelFromUrdf`` of the Panda of
example-robot-data with a free-flyer base for the moving mount), never on pinframes' own
compiled models.
"""

from __future__ import annotations

import warnings
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hardening.tree_model import build_tree
from hardening.tree_strategies import absolute_trees, trees
from pinframes import FrameTree, JointLimitWarning, Pose
from pinframes.errors import ExtrapolationError, FrameNotFoundError, JointError

FIXED = settings(max_examples=25, deadline=None, derandomize=True, database=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
LWA = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"


def panda_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "panda.urdf":
            return Path(file.locate())
    pytest.skip("example-robot-data is not installed")


# -- hand-derived ----------------------------------------------------------------------------
def test_a_point_on_a_turning_table_at_known_speed():
    """90 degrees in 10 s: 0.157 rad/s about z; a point 0.2 m out moves at 0.2 * 0.157 m/s."""
    rate = (np.pi / 2) / 10.0
    tree = FrameTree()
    tree.add("positioner", "world", Pose([1.5, 0.0, 0.8]))
    tree.add("table", "positioner",
             Pose(rotation=[[0, 0, 0, 1], [0, 0, np.sin(np.pi / 4), np.cos(np.pi / 4)]],
                  times=[0.0, 10.0]))
    tree.add("seam", "table", Pose([0.2, 0.0, 0.05]))
    times = [-1.0, 0.0, 2.5, 10.0, 12.0]
    velocity = tree.velocity("seam", "world", times=times)
    angles = np.array([0.0, 0.0, np.pi / 8, np.pi / 2, np.pi / 2])
    moving = np.array([0.0, 1.0, 1.0, 1.0, 0.0])  # held before 0 s and after 10 s
    expected = 0.2 * rate * np.stack([-np.sin(angles), np.cos(angles), 0 * angles], axis=1)
    np.testing.assert_allclose(velocity.linear, moving[:, None] * expected, atol=1e-15)
    np.testing.assert_allclose(velocity.angular, moving[:, None] * [0.0, 0.0, rate],
                               atol=1e-15)
    assert velocity.times.astype(np.int64).tolist() == [-10**9, 0, 25 * 10**8, 10**10,
                                                        12 * 10**9]
    # in the seam's own axes the point always moves along its y axis (Pinocchio's LOCAL)
    local = tree.velocity("seam", "world", times=times, expressed_in="seam")
    np.testing.assert_allclose(local.linear, moving[:, None] * [0.0, 0.2 * rate, 0.0],
                               atol=1e-15)
    # seen from the seam, the positioner turns the other way
    back = tree.velocity("positioner", "seam", times=[2.5])
    np.testing.assert_allclose(back.angular, [[0.0, 0.0, -rate]], atol=1e-15)
    # in the turning table's axes (a third frame) too, also while it is held
    in_table = tree.velocity("seam", "world", times=times, expressed_in="table")
    np.testing.assert_allclose(in_table.linear, moving[:, None] * [0.0, 0.2 * rate, 0.0],
                               atol=1e-15)


def test_a_static_pair_in_a_moving_frames_axes_without_times_is_at_rest():
    """Nothing moves between the two frames: one zero velocity, whatever axes it is written
    in (it was a ValueError when the third frame moved)."""
    tree = FrameTree()
    tree.add("a", "world", Pose([1.0, 0.0, 0.0]))
    tree.add("b", "world", Pose([0.0, 1.0, 0.0]))
    tree.add("turning", "world", Pose(rotation=[[0, 0, 0, 1], [0, 0, 1, 0]], times=[0.0, 1.0]))
    velocity = tree.velocity("a", "b", expressed_in="turning")
    assert velocity.times is None
    np.testing.assert_array_equal(velocity.linear, [[0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(velocity.angular, [[0.0, 0.0, 0.0]])


def test_keyframes_use_the_segment_that_starts_there():
    tree = FrameTree()
    tree.add("slider", "world", Pose([[0, 0, 0], [1, 0, 0], [1, 2, 0]], times=[0.0, 1.0, 2.0]))
    velocity = tree.velocity("slider", "world", times=[0.0, 0.5, 1.0, 2.0, 2.5])
    np.testing.assert_allclose(velocity.linear, [[1, 0, 0], [1, 0, 0], [0, 2, 0], [0, 2, 0],
                                                 [0, 0, 0]])
    default = tree.velocity("slider", "world")  # the keyframe times, as pose() uses
    assert default.times.astype(np.int64).tolist() == [0, 10**9, 2 * 10**9]


def test_mimic_joints_move_at_their_multiplier():
    urdf = """<robot name="m"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="prismatic"><parent link="a"/><child link="b"/>
        <axis xyz="1 0 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>
      <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/>
        <axis xyz="0 1 0"/><limit lower="-9" upper="9" effort="1" velocity="1"/>
        <mimic joint="j1" multiplier="-3" offset="0.5"/></joint></robot>"""
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    tree.set_joint_trajectory([0.0, 2.0], [[0.0], [1.0]], ["j1"])
    velocity = tree.velocity("c", "world", times=[1.0])
    np.testing.assert_allclose(velocity.linear, [[0.5, -1.5, 0.0]])
    jacobian = tree.jacobian("c", "world", times=[1.0])
    assert jacobian.joints == ("j1",)
    np.testing.assert_allclose(jacobian.matrix[0, :, 0], [1.0, -3.0, 0, 0, 0, 0])


def test_rotation_steps_are_pinocchio_log3(rng):
    from pinframes.values.interpolation import rotation_steps

    rotations = np.array([pin.exp3(rng.normal(size=3)) for _ in range(20)])
    rotations[5] = rotations[4] @ pin.exp3(np.array([0.0, 0.0, np.pi - 1e-6]))
    rotations[7] = rotations[6]  # no step
    expected = [pin.log3(rotations[k + 1] @ rotations[k].T) for k in range(19)]
    np.testing.assert_allclose(rotation_steps(rotations), expected, atol=1e-9)


# -- finite differences ----------------------------------------------------------------------
@FIXED
@given(spec=trees(robot_count=(0, 2)) | absolute_trees(robot_count=(0, 2)), data=st.data())
def test_velocity_is_the_derivative_of_the_numpy_model(spec, data):
    """Central differences of the independent numpy model, in the middle of segments."""
    tree = build_tree(spec)
    a = data.draw(st.sampled_from(tree.frames))
    b = data.draw(st.sampled_from(tree.frames))
    keyed = [item.instants() for item in spec.moving_items()]
    if not keyed:
        return
    union = np.unique(np.concatenate(keyed))
    gaps = np.diff(union)
    wide = gaps >= 10**7  # 10 ms: room for a precise difference
    if not wide.any():
        return
    instants = union[:-1][wide] + gaps[wide] // 2
    step = np.maximum(gaps[wide] // 200_000, 1)
    before = spec.poses_in_root(instants - step)
    after = spec.poses_in_root(instants + step)
    minus = np.linalg.inv(before[b]) @ before[a]
    plus = np.linalg.inv(after[b]) @ after[a]
    seconds = 2 * step[:, None] * 1e-9
    linear = (plus[:, :3, 3] - minus[:, :3, 3]) / seconds
    angular = np.array([pin.log3(p @ m.T) for p, m in zip(plus[:, :3, :3], minus[:, :3, :3],
                                                          strict=True)]) / seconds
    velocity = tree.velocity(a, b, times=spec.query_times(instants))
    scale = 1.0 + np.abs(linear).max() + np.abs(angular).max()
    np.testing.assert_allclose(velocity.linear, linear, rtol=1e-6, atol=1e-6 * scale)
    np.testing.assert_allclose(velocity.angular, angular, rtol=1e-6, atol=1e-6 * scale)


def test_velocity_is_the_derivative_of_pose_on_the_welding_cell():
    from pinframes import read_scene

    cell = read_scene(Path(__file__).resolve().parents[2] / "models" / "welding_cell"
                      / "scene.yaml")
    knots = cell.sample_times("torch_tcp", "workpiece").offsets
    middles = knots[:-1] + np.diff(knots) // 2
    step = 10**5  # 0.1 ms
    times = np.concatenate([middles - step, middles, middles + step]).astype("timedelta64[ns]")
    pose = cell.pose("torch_tcp", "workpiece", times=times)
    count = middles.shape[0]
    minus, plus = slice(0, count), slice(2 * count, 3 * count)
    linear = (pose.translation[plus] - pose.translation[minus]) / 2e-4
    velocity = cell.velocity("torch_tcp", "workpiece", times=times[count:2 * count])
    np.testing.assert_allclose(velocity.linear, linear, rtol=1e-6, atol=1e-9)
    angular = np.array([pin.log3(p @ m.T) for p, m in zip(pose.rotation[plus],
                                                          pose.rotation[minus], strict=True)])
    np.testing.assert_allclose(velocity.angular, angular / 2e-4, rtol=1e-6, atol=1e-9)


# -- Pinocchio, called directly --------------------------------------------------------------
@pytest.fixture(scope="module")
def panda_case():
    """The Panda on a mount moving with 6 keyframes, its arm driven by 9 samples."""
    rng = np.random.default_rng(5)
    urdf = panda_urdf()
    key_times = np.array([0.0, 1.0, 2.5, 3.0, 4.5, 6.0])
    mount_translation = rng.normal(scale=0.3, size=(6, 3))
    mount_rotation = np.array([pin.exp3(rng.normal(size=3)) for _ in range(6)])
    tree = FrameTree()
    tree.add("mount", "world", Pose(mount_translation, mount_rotation, times=key_times))
    tree.attach_urdf(urdf, "mount")
    tree.add("tool", "panda_hand", Pose([0.0, 0.0, 0.1034]))
    arm = [f"panda_joint{i}" for i in range(1, 8)]
    joint_times = np.linspace(0.0, 6.0, 9)
    positions = rng.uniform(-1.0, 1.0, size=(9, 7))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointLimitWarning)
        tree.set_joint_trajectory(joint_times, positions, arm)
    model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer())
    tool = model.addFrame(pin.Frame("tool", model.frames[model.getFrameId("panda_hand")]
                                    .parentJoint, model.frames[model.getFrameId("panda_hand")]
                                    .placement * pin.SE3(np.eye(3), np.array([0, 0, 0.1034])),
                                    pin.FrameType.OP_FRAME))
    # sample in the middle of every segment of the union of both timelines
    union = np.union1d(key_times, joint_times)
    times = union[:-1] + np.diff(union) / 2
    q, v = [], []
    for time in times:
        k = np.searchsorted(key_times, time) - 1
        span = key_times[k + 1] - key_times[k]
        f = (time - key_times[k]) / span
        rotation = mount_rotation[k] @ pin.exp3(f * pin.log3(mount_rotation[k].T
                                                             @ mount_rotation[k + 1]))
        translation = (1 - f) * mount_translation[k] + f * mount_translation[k + 1]
        body_linear = rotation.T @ (mount_translation[k + 1] - mount_translation[k]) / span
        body_angular = pin.log3(mount_rotation[k].T @ mount_rotation[k + 1]) / span
        j = np.searchsorted(joint_times, time) - 1
        g = (time - joint_times[j]) / (joint_times[j + 1] - joint_times[j])
        values = (1 - g) * positions[j] + g * positions[j + 1]
        rates = (positions[j + 1] - positions[j]) / (joint_times[j + 1] - joint_times[j])
        q_row = pin.neutral(model)
        q_row[:7] = pin.SE3ToXYZQUAT(pin.SE3(rotation, translation))
        v_row = np.zeros(model.nv)
        v_row[:3], v_row[3:6] = body_linear, body_angular
        for column, name in enumerate(arm):
            joint = model.joints[model.getJointId(name)]
            q_row[joint.idx_q] = values[column]
            v_row[joint.idx_v] = rates[column]
        q.append(q_row)
        v.append(v_row)
    return tree, model, tool, times, np.array(q), np.array(v), arm


def test_velocity_equals_pinocchio_get_frame_velocity(panda_case):
    tree, model, tool, times, q, v, _ = panda_case
    data = model.createData()
    world = tree.velocity("tool", "world", times=times)
    local = tree.velocity("tool", "world", times=times, expressed_in="tool")
    for i in range(times.shape[0]):
        pin.forwardKinematics(model, data, q[i], v[i])
        pin.updateFramePlacements(model, data)
        aligned = pin.getFrameVelocity(model, data, tool, LWA)
        np.testing.assert_allclose(world.linear[i], aligned.linear, atol=1e-10)
        np.testing.assert_allclose(world.angular[i], aligned.angular, atol=1e-10)
        body = pin.getFrameVelocity(model, data, tool, pin.ReferenceFrame.LOCAL)
        np.testing.assert_allclose(local.linear[i], body.linear, atol=1e-10)
        np.testing.assert_allclose(local.angular[i], body.angular, atol=1e-10)


def test_jacobian_equals_pinocchio_compute_frame_jacobian(panda_case):
    tree, model, tool, times, q, _v, arm = panda_case
    data = model.createData()
    jacobian = tree.jacobian("tool", "world", times=times)
    assert jacobian.matrix.shape == (times.shape[0], 6, len(jacobian.joints))
    assert jacobian.joints[:7] == tuple(arm)
    for i in range(times.shape[0]):
        expected = pin.computeFrameJacobian(model, data, q[i], tool, LWA)
        for column, name in enumerate(jacobian.joints):
            index = model.joints[model.getJointId(name)].idx_v
            np.testing.assert_allclose(jacobian.matrix[i, :, column], expected[:, index],
                                       atol=1e-10)


def test_jacobian_times_joint_rates_is_the_joint_part_of_the_velocity(panda_case):
    """With the mount held still (queried relative to it), joints cause all the motion."""
    tree, model, _tool, times, _q, v, arm = panda_case
    jacobian = tree.jacobian("tool", "mount", times=times, joints=arm)
    rates = v[:, [model.joints[model.getJointId(name)].idx_v for name in arm]]
    velocity = tree.velocity("tool", "mount", times=times)
    joined = np.concatenate([velocity.linear, velocity.angular], axis=1)
    np.testing.assert_allclose(np.einsum("tij,tj->ti", jacobian.matrix, rates), joined,
                               atol=1e-12)


def test_jacobian_between_two_robots_is_the_joint_space_derivative_of_pose():
    """Finite differences in joint space of the pose of one robot's tool in another's."""
    tree = FrameTree()
    tree.add("table", "world", Pose([1.0, 0.5, 0.0], [0, 0, 1, 0]))
    tree.attach_urdf(ROBOT, "world", prefix="a/")
    tree.attach_urdf(ROBOT, "table", prefix="b/")
    tree.add("tool", "a/flange", Pose([0.0, 0.05, 0.3]))
    names = [name for name, joint in tree.joints.items() if joint.is_actuated]
    values = np.random.default_rng(2).uniform(-1.0, 1.0, len(names))
    tree.set_joint_trajectory([0.0], values[None], names)
    jacobian = tree.jacobian("tool", "b/flange", times=[0.0])
    assert jacobian.joints == tuple(names)
    epsilon = 1e-6
    for column in range(len(names)):
        poses = []
        for sign in (1, -1):
            moved = values.copy()
            moved[column] += sign * epsilon
            tree.set_joint_trajectory([0.0], moved[None], names)
            poses.append(tree.pose("tool", "b/flange", times=[0.0]))
        linear = (poses[0].translation[0] - poses[1].translation[0]) / (2 * epsilon)
        angular = pin.log3(poses[0].rotation[0] @ poses[1].rotation[0].T) / (2 * epsilon)
        np.testing.assert_allclose(jacobian.matrix[0, :3, column], linear, atol=1e-8)
        np.testing.assert_allclose(jacobian.matrix[0, 3:, column], angular, atol=1e-8)


def test_static_paths_and_joints_off_the_path_have_zero_columns():
    tree = FrameTree()
    tree.attach_urdf(ROBOT, "world", prefix="a/")
    tree.add("fixture", "world", Pose([1.0, 0.0, 0.0]))
    still = tree.velocity("fixture", "world")
    assert still.times is None and still.linear.shape == (1, 3) and not still.linear.any()
    jacobian = tree.jacobian("fixture", "world", times=[0.0, 1.0])
    assert jacobian.matrix.shape == (2, 6, 6) and not jacobian.matrix.any()
    # a robot without trajectory still has its Jacobian (at joint values 0)
    with pytest.warns(UserWarning, match="no samples"):
        column = tree.jacobian("a/flange", "world", joints=["a/joint_1"]).matrix[0, :, 0]
        flange = tree.pose("a/flange", "world").translation
    np.testing.assert_allclose(column, [-flange[1], flange[0], 0, 0, 0, 1], atol=1e-15)


# -- bad input -------------------------------------------------------------------------------
def test_bad_arguments_name_the_argument_and_the_frame():
    tree = FrameTree()
    tree.attach_urdf(ROBOT, "world", prefix="a/")
    tree.add("slider", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0]))
    with pytest.raises(FrameNotFoundError, match="nowhere"):
        tree.velocity("nowhere", "world")
    with pytest.raises(FrameNotFoundError, match="nowhere"):
        tree.velocity("slider", "world", expressed_in="nowhere")
    with pytest.raises(JointError) as info:
        tree.jacobian("a/flange", "world", joints=["a/joint_9"])
    assert info.value.field == "joints" and info.value.frame == "a/flange"
    with pytest.raises(ExtrapolationError) as info:
        tree.velocity("slider", "world", times=[2.0], extrapolation="error")
    assert info.value.frame == "slider"
