"""No shared mutable state: arrays that leave or enter the library cannot change a tree.

Every array a caller gets (query results, local poses, joint tracks, sample times) is either
read-only (numpy raises ``ValueError`` on a write) or the caller's own copy; arrays a caller
passes in are copied. Each test writes where a caller could, then checks the tree's answers
against values written out by hand.
"""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable

import numpy as np
import pytest

from hardening.api_cases import START, sample_tree
from pinframes import FrameTree, JointTrack, Pose


def scribble(array: np.ndarray) -> None:
    """Write into ``array`` as a careless caller would; read-only arrays refuse."""
    try:
        array[...] = np.ones_like(array) * 7
    except ValueError as exc:
        assert "read-only" in str(exc)


def assert_unchanged_after_scribbling(get: Callable[[], np.ndarray], expected) -> None:
    scribble(get())
    np.testing.assert_allclose(get(), expected, atol=1e-12)


def static_tree() -> FrameTree:
    tree = FrameTree("w")
    tree.add("a", "w", Pose([1.0, 2.0, 3.0]))
    return tree


def test_a_static_query_result_does_not_share_the_cache():
    tree = static_tree()
    result = tree.pose("a", "w")
    with pytest.raises(ValueError, match="read-only"):
        result.translation[0] = 99.0
    with pytest.raises(ValueError, match="read-only"):
        result.rotation[0, 0] = 99.0
    np.testing.assert_array_equal(tree.pose("a", "w").translation, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(tree.pose("w", "a").translation, [-1.0, -2.0, -3.0])


@pytest.mark.parametrize("frame", ["w", "a"])
def test_the_identity_of_one_tree_is_not_the_identity_of_all(frame):
    tree = static_tree()
    scribble(tree.pose(frame, frame).translation)
    scribble(tree.pose(frame, frame).rotation)
    for other in (FrameTree("x"), tree):
        name = frame if other is tree else "x"
        pose = other.pose(name, name)
        np.testing.assert_array_equal(pose.translation, [0.0, 0.0, 0.0])
        np.testing.assert_array_equal(pose.rotation, np.eye(3))
    np.testing.assert_array_equal(Pose.identity().translation, [0.0, 0.0, 0.0])


def test_timed_query_results_and_their_derived_values():
    tree = sample_tree()
    # table at (1, 0, 0.8) turned by yaw 0.3 about z; turntable z from 0.1 (0 s) to 0.2 (2 s)
    assert_unchanged_after_scribbling(
        lambda: tree.pose("turntable", "world", times=[0.0, 1.0]).translation,
        [[1.0, 0.0, 0.9], [1.0, 0.0, 0.95]])
    assert_unchanged_after_scribbling(
        lambda: tree.pose("turntable", "world").translation, [[1.0, 0.0, 0.9], [1.0, 0.0, 1.0]])
    assert_unchanged_after_scribbling(
        lambda: tree.pose("turntable", "world").inverse().inverse().translation,
        [[1.0, 0.0, 0.9], [1.0, 0.0, 1.0]])
    # turntable in table: keyframe translations (0, 0, 0.1) and (0, 0, 0.2) at 0 s and 2 s
    np.testing.assert_allclose(tree.pose("turntable", "table", times=[1.0]).translation,
                               [[0.0, 0.0, 0.15]], atol=1e-12)


def test_local_pose_arrays_are_read_only():
    tree = sample_tree()
    for name in ("table", "turntable"):
        pose = tree.local_pose(name)
        for array in (pose.translation, pose.rotation):
            with pytest.raises(ValueError, match="read-only"):
                array[...] = 0.0
    np.testing.assert_allclose(tree.pose("table", "world").translation, [1.0, 0.0, 0.8])
    np.testing.assert_allclose(tree.local_pose("turntable").translation,
                               [[0.0, 0.0, 0.1], [0.0, 0.0, 0.2]])


def test_keyframe_times_and_sample_times_cannot_move_a_frame():
    tree = sample_tree()
    scribble(tree.local_pose("turntable").times)  # a converted copy: writing is harmless
    axis = tree.sample_times("turntable", "table")
    scribble(axis.offsets)
    np.testing.assert_array_equal(tree.sample_times("turntable", "table").offsets,
                                  [0, 2_000_000_000])
    np.testing.assert_allclose(tree.pose("turntable", "table", times=[1.0]).translation,
                               [[0.0, 0.0, 0.15]], atol=1e-12)


def test_joint_track_values_and_times_are_read_only():
    tree = sample_tree()
    track = tree.joint_track("arm/j1")
    for array in (track.values, track.times):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 7
    np.testing.assert_allclose(tree.joint_track("arm/j1").values, [0.0, 0.5])


def test_arrays_passed_in_are_copied():
    translation = np.array([[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    quaternions = np.array([[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0]])
    times = np.array([0, 1_000_000_000], dtype="timedelta64[ns]")
    pose = Pose(translation, quaternions, times=times)
    translation[:] = 9.0
    quaternions[:] = [1.0, 0.0, 0.0, 0.0]
    times[1] = np.timedelta64(5, "s")
    np.testing.assert_array_equal(pose.translation, [[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    np.testing.assert_allclose(pose.rotation[1], np.diag([-1.0, -1.0, 1.0]), atol=1e-15)
    assert pose.times[1] == np.timedelta64(1, "s")

    matrix = np.eye(4)
    from_matrix = Pose.from_matrix(matrix)
    matrix[0, 3] = 4.0
    np.testing.assert_array_equal(from_matrix.translation, [0.0, 0.0, 0.0])


def test_joint_trajectory_input_arrays_are_copied():
    tree = sample_tree()
    times = np.array([START, START + np.timedelta64(1, "s")])
    positions = np.array([[0.0], [0.5]])
    tree.set_joint_trajectory(times, positions, ["arm/j1"])
    positions[:] = 3.0
    times[1] = START + np.timedelta64(9, "s")
    np.testing.assert_array_equal(tree.joint_track("arm/j1").times, [0, 1_000_000_000])
    np.testing.assert_allclose(tree.joint_track("arm/j1").values, [0.0, 0.5])

    values = np.array([0.0, 1.0])
    offsets = np.array([0, 10], dtype=np.int64)
    track = JointTrack(offsets, START, values)
    values[1] = 5.0
    offsets[1] = 3
    np.testing.assert_array_equal(track.values, [0.0, 1.0])
    np.testing.assert_array_equal(track.times, [0, 10])


def test_one_pose_in_two_trees_stays_the_same_in_both():
    shared = Pose([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], times=[0.0, 2.0])
    first, second = FrameTree("w"), FrameTree("w")
    first.add("m", "w", shared)
    second.add("m", "w", shared)
    scribble(first.local_pose("m").translation)
    scribble(first.pose("m", "w", times=[1.0]).translation)
    for tree in (first, second):
        np.testing.assert_allclose(tree.pose("m", "w", times=[1.0]).translation,
                                   [[1.0, 0.0, 0.0]])
        np.testing.assert_allclose(tree.local_pose("m").translation[1], [2.0, 0.0, 0.0])


def test_composed_sampled_and_inverted_poses_are_immutable_too():
    a = Pose([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], times=[0.0, 2.0])
    b = Pose([0.0, 1.0, 0.0])
    for derived in (a @ b, b @ a, a.inverse(), a.at([1.0]), b.at([0.0, 1.0]),
                    Pose.from_xyz_rpy(1.0, 2.0, 3.0)):
        for array in (derived.translation, derived.rotation):
            with pytest.raises(ValueError, match="read-only"):
                array[...] = 0.0
    np.testing.assert_allclose(a.at([1.0]).translation, [[1.0, 0.0, 0.0]])
    np.testing.assert_allclose(b.translation, [0.0, 1.0, 0.0])


def test_spatial_data_arrays_are_copied_and_read_only():
    from pinframes import SpatialData

    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    triangles = np.array([[0, 1, 2]])
    temperature = np.array([20.0, 21.0, 22.0])
    data = SpatialData(points, triangles, {"temperature": temperature})
    points[0, 0] = triangles[0, 0] = temperature[0] = 9
    assert points.flags.writeable  # the caller's own array stays theirs
    np.testing.assert_array_equal(data.points[0], [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(data.triangles, [[0, 1, 2]])
    np.testing.assert_array_equal(data.attributes["temperature"], [20.0, 21.0, 22.0])
    for array in (data.points, data.triangles, data.attributes["temperature"]):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 5


def test_a_pose_stack_and_the_poses_taken_from_it_are_read_only():
    tree = static_tree()
    tree.add("b", "a", Pose([0.0, 1.0, 0.0]))
    stack = tree.poses(["a", "b"], relative_to="w")
    first = stack[1]
    for array in (stack.translation, stack.rotation, first.translation):
        with pytest.raises(ValueError, match="read-only"):
            array[...] = 0.0
    # b in w: (1, 2, 3) + (0, 1, 0)
    np.testing.assert_array_equal(tree.poses(["a", "b"], relative_to="w").translation,
                                  [[1.0, 2.0, 3.0], [1.0, 3.0, 3.0]])


def test_joints_set_together_share_one_read_only_copy_of_their_times():
    """One copy of the times per call, not one per joint (7 joints x 10^7 samples held
    560 MB of identical times), still a copy: the caller's array stays theirs."""
    tree = FrameTree()
    tree.attach_urdf("""<robot name="two"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="j1" type="continuous"><parent link="a"/><child link="b"/></joint>
      <joint name="j2" type="continuous"><parent link="b"/><child link="c"/></joint>
    </robot>""", "world")
    times = np.array([0.0, 1.0, 2.0])
    tree.set_joint_trajectory(times, np.zeros((3, 2)), ["j1", "j2"])
    times[1] = 1.5
    first, second = tree.joint_track("j1"), tree.joint_track("j2")
    assert first.times is second.times
    assert not first.times.flags.writeable
    np.testing.assert_array_equal(first.times, [0, 1_000_000_000, 2_000_000_000])


@pytest.mark.parametrize("duplicate", [copy.deepcopy,
                                       lambda tree: pickle.loads(pickle.dumps(tree))],
                         ids=["deepcopy", "pickle"])
def test_a_queried_tree_pickles_and_deep_copies_and_answers_alike(duplicate):
    """The description a query builds (read-only mappings, prepared paths) is a cache: it
    stays behind, and the copy builds its own."""
    tree = sample_tree()
    times = np.linspace(0.0, 1.5, 12)  # the batched kernels and, below, one time
    expected = tree.pose("arm/c", "world", times=times, time_ref=START)
    expected_once = tree.pose("arm/c", "world", times=0.7, time_ref=START)
    twin = duplicate(tree)
    np.testing.assert_array_equal(
        twin.pose("arm/c", "world", times=times, time_ref=START).matrix, expected.matrix)
    np.testing.assert_array_equal(
        twin.pose("arm/c", "world", times=0.7, time_ref=START).matrix, expected_once.matrix)
