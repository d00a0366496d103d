"""Queries at one time (Pinocchio's own kinematics on Python-float samples) against plain numpy
compositions of hand-interpolated poses, Pinocchio called directly, and the batched path."""

from __future__ import annotations

import pickle
import sys
import threading
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
from pinframes import FrameTree, JointWithoutSamplesWarning, Pose
from pinframes.errors import ExtrapolationError
from pinframes.kinematics._one_time import FEW_TIMES, MAX_DEGREES_OF_FREEDOM
from pinframes.kinematics._plan import prepare_path
from pinframes.values.interpolation import Keyframes, Segments, segment_position
from pinframes.values.joint_trajectory import JointTrajectory

from geometry import homogeneous, rot_z

FIXED = settings(max_examples=40, deadline=None, derandomize=True, database=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
SECOND = 10**9


def panda_urdf() -> Path:
    for file in metadata.files("example-robot-data") or []:
        if file.name == "panda.urdf":
            return Path(file.locate())
    pytest.skip("example-robot-data is not installed")


def batched_at(tree: FrameTree, frame: str, relative_to: str, t, **options) -> np.ndarray:
    """The pose at ``t`` taken from a query at more times than the one-time path takes."""
    others = list(np.linspace(-3.0, 13.0, FEW_TIMES + 3))
    result = tree.pose(frame, relative_to, times=[t, *others], **options)
    return result.matrix[0]


# -- the scalar samplers ---------------------------------------------------------------------
def test_segment_position_is_segments_for_one_time(rng):
    for count in (1, 2, 7):
        keyframe_times = np.cumsum(rng.integers(1, 10**9, size=count))
        times = np.concatenate([keyframe_times, keyframe_times - 1, keyframe_times + 1,
                                rng.integers(keyframe_times[0] - 10**9,
                                             keyframe_times[-1] + 10**9, size=50)])
        segments = Segments(keyframe_times, times)
        index, fraction = segments.index, segments.fraction
        for position, time in enumerate(times.tolist()):
            one = segment_position(keyframe_times, time)
            assert one == (index[position], fraction[position])
            assert isinstance(one[0], int) and isinstance(one[1], float)


def hand_slerp(q0: np.ndarray, q1: np.ndarray, fraction: float) -> np.ndarray:
    """The short-arc SLERP of two unit quaternions, written out here."""
    if np.dot(q0, q1) < 0:
        q1 = -q1
    angle = np.arccos(min(abs(float(np.dot(q0, q1))), 1.0))
    if angle < 1e-9:
        q = (1 - fraction) * q0 + fraction * q1
    else:
        q = (np.sin((1 - fraction) * angle) * q0 + np.sin(fraction * angle) * q1) / np.sin(angle)
    return q / np.linalg.norm(q)


def matrix_of(quaternion) -> np.ndarray:
    x, y, z, w = quaternion
    return pin.Quaternion(w, x, y, z).toRotationMatrix()


def test_keyframes_pose_at_is_linear_translation_and_short_arc_slerp(rng):
    quaternions = rng.normal(size=(8, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    quaternions[3] = -quaternions[2]  # antipodal: the same rotation, no motion between
    quaternions[5] = quaternions[4] + 1e-10  # nearly identical
    quaternions[5] /= np.linalg.norm(quaternions[5])
    rotations = np.array([matrix_of(q) for q in quaternions])
    translations = rng.normal(size=(8, 3))
    times = np.cumsum(rng.integers(1, 10**9, size=8))
    keyframes = Keyframes(times, rotations, translations)
    samples = np.concatenate([rng.integers(times[0] - 10**9, times[-1] + 10**9, size=60),
                              times])
    batched_rotation, batched_translation = keyframes.transform_at(samples)
    for position, time in enumerate(samples.tolist()):
        translation, quaternion = keyframes.pose_at(time)
        assert all(isinstance(v, float) for v in (*translation, *quaternion))
        k = int(np.clip(np.searchsorted(times, time, side="right") - 1, 0, 6))
        f = float(np.clip((time - times[k]) / (times[k + 1] - times[k]), 0.0, 1.0))
        np.testing.assert_allclose(translation,
                                   (1 - f) * translations[k] + f * translations[k + 1],
                                   atol=1e-12)
        expected = matrix_of(hand_slerp(quaternions[k], quaternions[k + 1], f))
        np.testing.assert_allclose(matrix_of(quaternion), expected, atol=1e-12)
        assert abs(np.linalg.norm(quaternion) - 1.0) < 1e-12
        np.testing.assert_allclose(matrix_of(quaternion), batched_rotation[..., position],
                                   atol=1e-12)
        np.testing.assert_allclose(translation, batched_translation[:, position], atol=1e-12)


def test_a_single_keyframe_is_held(rng):
    rotation = pin.exp3(rng.normal(size=3))
    keyframes = Keyframes(np.array([5]), rotation[None], np.array([[1.0, 2.0, 3.0]]))
    translation, quaternion = keyframes.pose_at(-10**12)
    assert translation == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(matrix_of(quaternion), rotation, atol=1e-12)


def test_joint_trajectory_value_at_is_linear_and_held_outside(rng):
    times = np.cumsum(rng.integers(1, 10**9, size=6))
    values = rng.normal(size=6)
    trajectory = JointTrajectory(times, None, values)
    for time in rng.integers(times[0] - 10**9, times[-1] + 10**9, size=40).tolist():
        value = trajectory.value_at(time)
        assert isinstance(value, float)
        assert value == pytest.approx(np.interp(time, times, values), abs=1e-12)
    assert JointTrajectory(times[:1], None, values[:1]).value_at(0) == values[0]


# -- random trees against an independent numpy model -----------------------------------------
@FIXED
@given(spec=trees(robot_count=(0, 2)) | absolute_trees(robot_count=(0, 2)), data=st.data())
def test_random_trees_at_one_time_match_numpy_and_the_batched_path(spec, data):
    tree = build_tree(spec)
    frames = tree.frames
    instants = spec.instants()
    world = spec.poses_in_root(instants)
    for _ in range(4):
        frame = data.draw(st.sampled_from(frames))
        reference = data.draw(st.sampled_from(frames))
        row = data.draw(st.integers(0, len(instants) - 1))
        at = spec.query_times(instants[row:row + 1])[0]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", JointWithoutSamplesWarning)
            one = tree.pose(frame, reference, times=at)
            many = tree.pose(frame, reference, times=spec.query_times(
                np.concatenate([instants[row:row + 1], np.resize(instants, FEW_TIMES + 2)])))
        expected = np.linalg.solve(world[reference][row], world[frame][row])
        if one.is_time_dependent:
            assert one.matrix.shape == (1, 4, 4)
            assert one.reference_time == many.reference_time
            assert one.times[0] == many.times[0]
            np.testing.assert_allclose(one.matrix[0], expected, atol=1e-12)
            np.testing.assert_allclose(one.matrix[0], many.matrix[0], atol=1e-12)
        else:  # a static path: one pose
            np.testing.assert_allclose(one.matrix, expected, atol=1e-12)


# -- a moving path: directions, branches, clamping, reference times ----------------------------
def moving_tree(rng):
    """world <- a (static) <- m (moving, 50 keyframes) <- tool (static); world <- b <- c."""
    tree = FrameTree()
    a = homogeneous(pin.exp3(rng.normal(size=3)), rng.normal(size=3))
    tool = homogeneous(pin.exp3(rng.normal(size=3)), rng.normal(size=3))
    c = homogeneous(pin.exp3(rng.normal(size=3)), rng.normal(size=3))
    keyframe_times = np.linspace(0.0, 10.0, 50)
    # steps below 1 rad (log3, which the check uses, is exact far from half a turn)...
    rotations = [pin.exp3(rng.normal(size=3))]
    for index in range(1, 50):
        step = pin.exp3(rng.normal(size=3) * 0.5) if index != 21 else rot_z(np.pi)
        rotations.append(rotations[-1] @ step)  # ... and a half turn from 20 to 21
    rotations = np.array(rotations)
    translations = rng.normal(size=(50, 3))
    tree.add("a", "world", Pose.from_matrix(a))
    tree.add("m", "a", Pose(translations, rotations, times=keyframe_times))
    tree.add("tool", "m", Pose.from_matrix(tool))
    quarter = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]  # a quarter turn about z
    tree.add("b", "world", Pose(rng.normal(size=(2, 3)), [[0, 0, 0, 1], quarter],
                                times=[2.0, 4.0]))
    tree.add("c", "b", Pose.from_matrix(c))
    return tree, a, tool, c, (keyframe_times, translations, rotations)


def hand_pose(keyframe_times, translations, rotations, t) -> np.ndarray:
    """Linear translation and SLERP as R0 exp(f log(R0^T R1)) (Pinocchio's exp3/log3)."""
    k = int(np.clip(np.searchsorted(keyframe_times, t, side="right") - 1, 0,
                    len(keyframe_times) - 2))
    f = float(np.clip((t - keyframe_times[k]) / (keyframe_times[k + 1] - keyframe_times[k]),
                      0.0, 1.0))
    rotation = rotations[k] @ pin.exp3(f * pin.log3(rotations[k].T @ rotations[k + 1]))
    return homogeneous(rotation, (1 - f) * translations[k] + f * translations[k + 1])


@pytest.mark.parametrize("t", [4.321, 0.0, 10.0, -2.0, 12.5, 4.2])
def test_a_moving_path_at_one_time_both_directions(rng, t):
    tree, a, tool, _, keyframes = moving_tree(rng)
    expected = a @ hand_pose(*keyframes, t) @ tool
    if t != 4.2:  # 4.2 s is inside the half-turn segment, where log3 picks a direction
        np.testing.assert_allclose(tree.pose("tool", "world", times=t).matrix[0], expected,
                                   atol=1e-12)
        # the reference frame below the moving frame: the inverse direction
        np.testing.assert_allclose(tree.pose("world", "tool", times=t).matrix[0],
                                   np.linalg.inv(expected), atol=1e-12)
    for frame, reference in [("tool", "world"), ("world", "tool"), ("a", "tool"),
                             ("tool", "c"), ("c", "tool")]:
        np.testing.assert_allclose(tree.pose(frame, reference, times=t).matrix[0],
                                   batched_at(tree, frame, reference, t), atol=1e-12)


def test_a_half_turn_between_keyframes_turns_a_quarter_at_the_midpoint():
    tree = FrameTree()
    tree.add("m", "world", Pose(rotation=[np.eye(3), rot_z(np.pi)], times=[0.0, 1.0]))
    middle = tree.pose("m", "world", times=0.5).rotation[0]
    assert np.allclose(middle, rot_z(np.pi / 2), atol=1e-12) or np.allclose(
        middle, rot_z(-np.pi / 2), atol=1e-12)
    np.testing.assert_allclose(middle, batched_at(tree, "m", "world", 0.5)[:3, :3],
                               atol=1e-12)


def test_a_pair_across_two_moving_branches(rng):
    tree, a, tool, c, keyframes = moving_tree(rng)
    b_translations = tree.local_pose("b").translation
    b_rotations = np.array([np.eye(3), rot_z(np.pi / 2)])
    for t in (3.5, 1.0):  # 1 s is before b's first keyframe: b is held there
        b_pose = hand_pose(np.array([2.0, 4.0]), b_translations, b_rotations, t)
        expected = np.linalg.solve(b_pose @ c, a @ hand_pose(*keyframes, t) @ tool)
        result = tree.pose("tool", "c", times=t).matrix[0]
        np.testing.assert_allclose(result, expected, atol=1e-12)
        np.testing.assert_allclose(result, batched_at(tree, "tool", "c", t), atol=1e-12)


def test_outside_the_keyframes_one_time_clamps_or_raises(rng):
    tree, a, tool, _, (_, translations, rotations) = moving_tree(rng)
    last = a @ homogeneous(rotations[-1], translations[-1]) @ tool
    np.testing.assert_allclose(tree.pose("tool", "world", times=99.0).matrix[0], last,
                               atol=1e-12)
    with pytest.raises(ExtrapolationError) as info:
        tree.pose("tool", "world", times=99.0, extrapolation="error")
    assert (info.value.frame, info.value.field) == ("m", "times")
    inside = tree.pose("tool", "world", times=5.0, extrapolation="error")
    np.testing.assert_allclose(inside.matrix[0], batched_at(tree, "tool", "world", 5.0),
                               atol=1e-12)


def test_absolute_times_and_reference_times_at_one_time(rng):
    start = np.datetime64("2024-01-01T00:00:00", "ns")
    tree = FrameTree(reference_time=start)
    translations = rng.normal(size=(3, 3))
    rotations = np.array([pin.exp3(rng.normal(size=3) * 0.5) for _ in range(3)])
    # m counts from 2 s after the tree's reference, n from the tree's reference
    tree.add("m", "world", Pose(translations, rotations, times=[0.0, 1.0, 2.0],
                                reference_time=start + np.timedelta64(2, "s")))
    tree.add("n", "m", Pose(rng.normal(size=(2, 3)), [[0, 0, 0, 1], [0, 0.6, 0, 0.8]],
                            times=[0.0, 5.0]))
    at = start + np.timedelta64(3_250, "ms")
    one = tree.pose("m", "world", times=at)
    expected = hand_pose(np.array([0.0, 1.0, 2.0]), translations, rotations, 1.25)
    np.testing.assert_allclose(one.matrix[0], expected, atol=1e-12)
    many = tree.pose("m", "world", times=[at] + [start] * (FEW_TIMES + 2))
    assert one.reference_time == many.reference_time
    assert one.times[0] == many.times[0]
    for times, time_ref in [(at, None), ([1.25], start + np.timedelta64(2, "s")), (0.4, None)]:
        one = tree.pose("n", "world", times=times, time_ref=time_ref)
        many = tree.pose("n", "world", times=np.resize(np.asarray(times), FEW_TIMES + 3),
                         time_ref=time_ref)
        assert (one.reference_time, one.times[0]) == (many.reference_time, many.times[0])
        np.testing.assert_allclose(one.matrix[0], many.matrix[0], atol=1e-12)


# -- robots -----------------------------------------------------------------------------------
def panda_on_mount(rng):
    tree = FrameTree()
    mount_times = np.linspace(0.0, 10.0, 20)
    mount_rotations = np.array([pin.exp3(rng.normal(size=3) * 0.5) for _ in range(20)])
    mount_translations = rng.normal(size=(20, 3))
    tree.add("mount", "world", Pose(mount_translations, mount_rotations, times=mount_times))
    tree.attach_urdf(panda_urdf(), "mount")
    actuated = [name for name, joint in tree.joints.items() if joint.is_actuated]
    sample_times = np.linspace(0.5, 9.5, 30)
    positions = np.array([rng.uniform(tree.joints[n].lower, tree.joints[n].upper, size=30)
                          for n in actuated]).T
    tree.set_joint_trajectory(sample_times, positions, actuated)
    return tree, (mount_times, mount_translations, mount_rotations), actuated, (
        sample_times, positions)


@pytest.mark.parametrize("t", [4.321, 0.1, 9.9])
def test_the_panda_on_a_moving_mount_at_one_time_matches_pinocchio(rng, t):
    tree, mount, actuated, (sample_times, positions) = panda_on_mount(rng)
    model = pin.buildModelFromUrdf(str(panda_urdf()))
    data = model.createData()
    q = pin.neutral(model)
    for column, name in enumerate(actuated):
        q[model.joints[model.getJointId(name)].idx_q] = np.interp(t, sample_times,
                                                                  positions[:, column])
    for joint_id in range(1, model.njoints):  # panda_finger_joint2 mimics joint 1
        joint = tree.joints[model.names[joint_id]]
        if joint.mimic is not None:
            primary = q[model.joints[model.getJointId(joint.mimic.joint)].idx_q]
            q[model.joints[joint_id].idx_q] = (joint.mimic.multiplier * primary
                                               + joint.mimic.offset)
    pin.framesForwardKinematics(model, data, q)
    mount_pose = hand_pose(*mount, t)
    for link in ("panda_hand", "panda_leftfinger", "panda_rightfinger", "panda_link3"):
        expected = mount_pose @ data.oMf[model.getFrameId(link)].homogeneous
        one = tree.pose(link, "world", times=t).matrix[0]
        np.testing.assert_allclose(one, expected, atol=1e-12)
        np.testing.assert_allclose(one, batched_at(tree, link, "world", t), atol=1e-12)
    # between two links, in both directions
    np.testing.assert_allclose(
        tree.pose("panda_hand", "panda_link3", times=t).matrix[0],
        np.linalg.solve(data.oMf[model.getFrameId("panda_link3")].homogeneous,
                        data.oMf[model.getFrameId("panda_hand")].homogeneous), atol=1e-12)


def test_a_continuous_joint_turns_past_half_a_turn_at_one_time():
    urdf = """<robot name="w"><link name="base"/><link name="wheel"/><link name="rim"/>
      <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/>
        <axis xyz="0 0 1"/></joint>
      <joint name="rim_joint" type="fixed"><parent link="wheel"/><child link="rim"/>
        <origin xyz="0.5 0 0"/></joint></robot>"""
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    # samples under half a turn apart (continuous joints take the short way between samples)
    tree.set_joint_trajectory([0.0, 1.0, 2.0], [[0.0], [2.5], [5.0]], ["spin"])
    angle = 4.25
    expected = homogeneous(rot_z(angle), rot_z(angle) @ [0.5, 0.0, 0.0])
    np.testing.assert_allclose(tree.pose("rim", "world", times=1.7).matrix[0], expected,
                               atol=1e-12)


def test_joints_without_samples_hold_their_rest_value_and_warn_at_one_time():
    tree = FrameTree()
    tree.add("mount", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0]))
    tree.attach_urdf(panda_urdf(), "mount")
    model = pin.buildModelFromUrdf(str(panda_urdf()))
    data = model.createData()
    q = np.clip(np.zeros(model.nq), model.lowerPositionLimit, model.upperPositionLimit)
    pin.framesForwardKinematics(model, data, q)
    expected = homogeneous(np.eye(3), [0.5, 0, 0]) @ data.oMf[
        model.getFrameId("panda_hand")].homogeneous
    with pytest.warns(JointWithoutSamplesWarning):
        result = tree.pose("panda_hand", "world", times=0.5)
    np.testing.assert_allclose(result.matrix[0], expected, atol=1e-12)


# -- state: threads and pickling ----------------------------------------------------------------
def test_queries_in_several_threads_at_once_each_get_their_own_time(rng):
    """Four threads query one path at different times, switching every microsecond: with
    one Pinocchio workspace shared by all threads, a few of these 8,000 queries read
    another thread's kinematics (2 to 9 per run when tried)."""
    tree, *_ = panda_on_mount(rng)
    times = np.linspace(0.0, 10.0, 40)
    expected = tree.pose("panda_hand", "world", times=times).matrix
    wrong: list[tuple[int, float]] = []

    def work(offset: int) -> None:
        for _ in range(200):
            for row in range(offset, len(times), 4):
                result = tree.pose("panda_hand", "world", times=times[row]).matrix[0]
                error = float(np.abs(result - expected[row]).max())
                if error > 1e-12:
                    wrong.append((row, error))

    threads = [threading.Thread(target=work, args=(offset,)) for offset in range(4)]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads between Pinocchio's calls too
    try:
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert wrong == []


def test_a_used_compiled_model_pickles_and_evaluates_in_the_copy(rng):
    tree, *_ = panda_on_mount(rng)
    tree.pose("panda_hand", "world", times=1.0)  # creates the model's pin.Data
    model = prepare_path(tree._frozen(), "panda_hand", "world").model
    copy = pickle.loads(pickle.dumps(model))
    q = pin.randomConfiguration(copy.model)
    pin.framesForwardKinematics(model.model, model.data, q)
    pin.framesForwardKinematics(copy.model, copy.data, q)
    frame_id = model.frame_ids["panda_hand"]
    np.testing.assert_array_equal(copy.data.oMf[frame_id].homogeneous,
                                  model.data.oMf[frame_id].homogeneous)


@pytest.mark.parametrize("joints", [MAX_DEGREES_OF_FREEDOM, MAX_DEGREES_OF_FREEDOM + 1])
def test_one_time_on_a_long_chain_matches_a_hand_composition(joints, rng):
    """Up to MAX_DEGREES_OF_FREEDOM Pinocchio answers one time, beyond it the numpy kernels
    (pinocchio.Data grows with the cube of the joints): the same pose either way."""
    links = "".join(f'<link name="l{index}"/>' for index in range(joints + 1))
    chain = "".join(
        f'<joint name="j{index}" type="revolute"><parent link="l{index}"/>'
        f'<child link="l{index + 1}"/><origin xyz="0.1 0 0.02" rpy="0.3 0 0"/>'
        f'<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
        for index in range(joints))
    tree = FrameTree()
    tree.attach_urdf(f'<robot name="chain">{links}{chain}</robot>', "world")
    names = [f"j{index}" for index in range(joints)]
    values = rng.uniform(-1, 1, size=(2, joints))
    tree.set_joint_trajectory([0.0, 2.0], values, names)
    pose = tree.pose(f"l{joints}", "world", times=0.5)
    at = 0.75 * values[0] + 0.25 * values[1]
    roll = np.array([[1, 0, 0], [0, np.cos(0.3), -np.sin(0.3)], [0, np.sin(0.3), np.cos(0.3)]])
    expected = np.eye(4)
    for angle in at:
        origin = np.eye(4)
        origin[:3, :3], origin[:3, 3] = roll, [0.1, 0.0, 0.02]
        turn = np.eye(4)
        turn[:2, :2] = [[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]]
        expected = expected @ origin @ turn
    np.testing.assert_allclose(pose.matrix[0], expected, rtol=0, atol=1e-12)
