"""FrameTree.pose against hand-derived poses, plain numpy, and Pinocchio called directly."""

import os
import subprocess
import sys

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pinframes import FrameTree, Pose
from pinframes.errors import ExtrapolationError, InvalidTimeError, ReferenceTimeError

from geometry import homogeneous, rot_z

SECOND = np.timedelta64(1, "s")


def spin_z(degrees_from, degrees_to, times):
    return Pose(rotation=[rot_z(np.radians(degrees_from)), rot_z(np.radians(degrees_to))],
                times=times)


def test_child_of_a_spinning_parent_follows_the_circle_not_the_chord():
    tree = FrameTree()
    tree.add("table", "world", spin_z(0, 90, [0, 10]))
    tree.add("point", "table", Pose([1.0, 0.0, 0.0]))
    mid = tree.pose("point", "world", times=5.0)
    np.testing.assert_allclose(mid.translation, [[np.cos(np.pi / 4), np.sin(np.pi / 4), 0]],
                               atol=1e-15)


def test_default_times_are_the_union_of_moving_frames_on_the_path_only():
    tree = FrameTree()
    tree.add("a", "world", spin_z(0, 90, [0, 2]))
    tree.add("b", "a", Pose([[0, 0, 0], [1, 0, 0]], times=[1, 3]))
    tree.add("elsewhere", "world", Pose(np.zeros((2, 3)), times=[7, 8]))
    tree.add("static", "world", Pose([0, 5, 0]))
    result = tree.pose("b", "static")
    assert (result.times / SECOND).tolist() == [0, 1, 2, 3]
    assert tree.pose("static", "world").times is None
    only_a = tree.pose("a", "world")
    assert (only_a.times / SECOND).tolist() == [0, 2]


def test_times_may_name_a_frame():
    tree = FrameTree()
    tree.add("a", "world", spin_z(0, 90, [0, 2]))
    tree.add("clock", "world", Pose(np.zeros((3, 3)), times=[0.5, 1.0, 1.5]))
    result = tree.pose("a", "world", times="clock")
    assert (result.times / np.timedelta64(500, "ms")).tolist() == [1, 2, 3]
    with pytest.raises(InvalidTimeError):
        tree.pose("a", "world", times="world")


def test_pose_of_a_frame_in_itself_is_the_identity():
    tree = FrameTree()
    tree.add("a", "world", spin_z(0, 90, [0, 2]))
    np.testing.assert_allclose(tree.pose("a", "a").matrix, np.eye(4))


def independent_sample(times, keyframe_times, translations, rotations, t):
    """Linear translation and SLERP as R0 exp(w log(R0^T R1)), with Pinocchio's exp3/log3."""
    i = int(np.clip(np.searchsorted(keyframe_times, t, side="right") - 1, 0,
                    len(keyframe_times) - 2))
    w = float(np.clip((t - keyframe_times[i]) / (keyframe_times[i + 1] - keyframe_times[i]),
                      0, 1))
    translation = (1 - w) * translations[i] + w * translations[i + 1]
    rotation = rotations[i] @ pin.exp3(w * pin.log3(rotations[i].T @ rotations[i + 1]))
    return homogeneous(rotation, translation)


def random_rotations(rng, count, max_step=1.0):
    """Rotations whose consecutive steps stay below ``max_step`` radians (no SLERP ambiguity)."""
    out = [pin.exp3(rng.normal(size=3))]
    for _ in range(count - 1):
        axis = rng.normal(size=3)
        out.append(out[-1] @ pin.exp3(axis / np.linalg.norm(axis) * rng.uniform(0, max_step)))
    return np.array(out)


def test_chain_matches_plain_numpy_composition_of_independently_interpolated_frames(rng):
    tree = FrameTree()
    chain = ["world"]
    keyframes = {}
    for index in range(6):
        name = f"f{index}"
        if index % 2:
            kt = np.sort(rng.uniform(0, 10, size=5)) + np.arange(5) * 0.01
            translations = rng.normal(size=(5, 3))
            rotations = random_rotations(rng, 5)
            keyframes[name] = (kt, translations, rotations)
            tree.add(name, chain[-1], Pose(translations, rotations, times=kt))
        else:
            static = homogeneous(pin.exp3(rng.normal(size=3)), rng.normal(size=3))
            keyframes[name] = static
            tree.add(name, chain[-1], Pose.from_matrix(static))
        chain.append(name)
    query_times = np.linspace(-1, 11, 37)
    result = tree.pose("f5", "world", times=query_times)
    for position, t in enumerate(query_times):
        expected = np.eye(4)
        for name in chain[1:]:
            edge = keyframes[name]
            expected = expected @ (edge if isinstance(edge, np.ndarray)
                                   else independent_sample(None, *edge, t))
        np.testing.assert_allclose(result.matrix[position], expected, atol=1e-12)
    inverse = tree.pose("world", "f5", times=query_times)
    np.testing.assert_allclose(inverse.matrix, np.linalg.inv(result.matrix), atol=1e-12)


def test_pose_of_a_in_b_is_the_exact_inverse_of_b_in_a_between_keyframes(rng):
    tree = FrameTree()
    tree.add("a", "world", Pose(rng.normal(size=(4, 3)), random_rotations(rng, 4),
                                times=[0, 1, 2, 3]))
    tree.add("b", "world", Pose(rng.normal(size=(3, 3)), random_rotations(rng, 3),
                                times=[0.3, 1.7, 2.2]))
    times = np.linspace(0, 3, 31)
    product = tree.pose("a", "b", times=times).matrix @ tree.pose("b", "a", times=times).matrix
    np.testing.assert_allclose(product, np.broadcast_to(np.eye(4), product.shape), atol=1e-12)


def test_extrapolation_policy():
    tree = FrameTree()
    tree.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1]))
    held = tree.pose("a", "world", times=[-5, 5])
    np.testing.assert_allclose(held.translation[:, 0], [0, 1])
    with pytest.raises(ExtrapolationError) as info:
        tree.pose("a", "world", times=[0.5, 5], extrapolation="error")
    assert info.value.frame == "a"
    with pytest.raises(ValueError):
        tree.pose("a", "world", extrapolation="linear")


def test_single_time_and_times_outside_give_one_pose_per_requested_time():
    tree = FrameTree()
    tree.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1]))
    assert len(tree.pose("a", "world", times=0.5)) == 1
    outside = tree.pose("a", "world", times=[5, 6, 7])
    assert outside.is_time_dependent and len(outside) == 3
    tree.add("s", "world", Pose([0, 1, 0]))
    static_at_times = tree.pose("s", "world", times=[1, 2])
    assert static_at_times.translation.shape == (2, 3)


# -- the reference-time table (SPEC section 4) -------------------------------------------
T0 = np.datetime64("2024-01-01T00:00:00", "ns")


def tree_with(tree_reference=None, frame_references=None):
    """Frames a and b under world, each moving over 10 s from its reference time."""
    tree = FrameTree(reference_time=tree_reference)
    for name, reference in zip(["a", "b"], frame_references or [None, None], strict=True):
        tree.add(name, "world", Pose([[0, 0, 0], [10, 0, 0]], times=[0, 10],
                                     reference_time=reference))
    return tree


def test_table_time_and_time_ref_with_tree_reference_uses_the_query_time_ref():
    tree = tree_with(T0)
    result = tree.pose("a", "world", times=[1.0], time_ref=T0 + 2 * SECOND)
    assert result.reference_time == T0 + 2 * SECOND
    np.testing.assert_allclose(result.translation, [[3, 0, 0]])


def test_table_time_ref_without_time_is_ignored_and_the_tree_reference_used():
    tree = tree_with(T0)
    result = tree.pose("a", "world", time_ref=T0 + 2 * SECOND)
    assert result.reference_time == T0
    assert (result.times / SECOND).tolist() == [0, 10]


def test_table_tree_reference_is_used_without_time_ref():
    tree = tree_with(T0, [T0 + 5 * SECOND, None])
    result = tree.pose("a", "world", times=[0.0, 6.0])
    assert result.reference_time == T0
    np.testing.assert_allclose(result.translation[:, 0], [0, 1])


def test_table_frames_with_references_use_the_lowest_one():
    tree = tree_with(None, [T0 + 5 * SECOND, T0 + 2 * SECOND])
    result = tree.pose("a", "b")
    assert result.reference_time == T0 + 2 * SECOND
    assert (result.times / SECOND).tolist() == [0, 3, 10, 13]
    # a is at x = t - 5, b at x = t - 2 (clamped to [0, 10]) in absolute seconds from T0.
    absolute = np.array([2, 5, 12, 15])
    a_x = np.clip(absolute - 5, 0, 10)
    b_x = np.clip(absolute - 2, 0, 10)
    np.testing.assert_allclose(result.translation[:, 0], a_x - b_x)
    with_time = tree.pose("a", "world", times=[1.0])
    assert with_time.reference_time == T0 + 5 * SECOND


def test_table_frames_with_references_and_a_query_time_ref():
    tree = tree_with(None, [T0, T0])
    result = tree.pose("a", "world", times=[1.0], time_ref=T0 + 4 * SECOND)
    assert result.reference_time == T0 + 4 * SECOND
    np.testing.assert_allclose(result.translation, [[5, 0, 0]])


def test_table_no_reference_anywhere_and_a_time_ref_is_an_error():
    tree = tree_with()
    with pytest.raises(ReferenceTimeError) as info:
        tree.pose("a", "world", times=[1.0], time_ref=T0)
    assert info.value.field == "time_ref"
    assert tree.pose("a", "world", time_ref=T0).reference_time is None


def test_table_no_reference_anywhere_gives_none():
    tree = tree_with()
    assert tree.pose("a", "world").reference_time is None
    assert tree.pose("a", "world", times=[1.0]).reference_time is None


def test_absolute_query_times_without_any_reference_are_an_error():
    tree = tree_with()
    with pytest.raises(ReferenceTimeError):
        tree.pose("a", "world", times=["2024-01-01T00:00:01"])


def test_absolute_query_times_with_frame_references():
    tree = tree_with(None, [T0, T0])
    result = tree.pose("a", "world", times=["2024-01-01T00:00:04"])
    np.testing.assert_allclose(result.translation, [[4, 0, 0]])
    assert result.reference_time == T0
    assert result.times[0] == 4 * SECOND


def test_a_datetime_query_on_a_static_path_carries_its_own_reference():
    tree = FrameTree()
    tree.add("s", "world", Pose([1, 0, 0]))
    result = tree.pose("s", "world", times=["2024-01-01T00:00:04", "2024-01-01T00:00:05"])
    assert result.reference_time == np.datetime64("2024-01-01T00:00:04")


def test_times_more_than_292_years_from_the_result_reference_are_an_error_not_a_wrap():
    tree = tree_with("1700-01-01", ["2200-01-01", None])
    with pytest.raises(ReferenceTimeError) as info:
        tree.pose("a", "world")
    assert info.value.field == "time_ref"
    assert "292 years" in str(info.value)
    nearer = tree.pose("a", "world", times=["2200-01-01T00:00:00.5"], time_ref="2200-01-01")
    np.testing.assert_allclose(nearer.translation, [[0.5, 0, 0]])
    assert nearer.times.astype("int64").tolist() == [500_000_000]


def test_a_frame_500_years_from_the_query_times_is_an_error_not_sampled_at_a_wrapped_time():
    tree = tree_with(None, ["2200-01-01", "1700-01-01"])
    with pytest.raises(ReferenceTimeError) as info:  # the union: each frame is out of reach
        tree.pose("a", "b")
    assert (info.value.frame, info.value.field) in {("a", "reference_time"),
                                                    ("b", "reference_time")}
    with pytest.raises(ReferenceTimeError) as info:
        tree.pose("a", "b", times=["2200-01-01T00:00:05"], time_ref="2200-01-01")
    assert (info.value.frame, info.value.field) == ("b", "reference_time")
    np.testing.assert_allclose(tree.pose("a", "world", times=["2200-01-01T00:00:05"])
                               .translation, [[5, 0, 0]])


# -- against Pinocchio called directly ------------------------------------------------------
def test_whole_tree_model_matches_pinocchio_forward_kinematics(rng):
    tree = FrameTree()
    names = ["world"]
    for index in range(12):
        parent = names[rng.integers(len(names))]
        if index % 3 == 0:
            pose = Pose(rng.normal(size=(3, 3)), random_rotations(rng, 3), times=[0, 1, 2])
        else:
            pose = Pose.from_matrix(homogeneous(pin.exp3(rng.normal(size=3)),
                                                rng.normal(size=3)))
        name = f"n{index}"
        tree.add(name, parent, pose)
        names.append(name)
    compiled = tree.to_pinocchio()
    data = compiled.model.createData()
    times = [0.0, 0.25, 1.5, 2.0]
    configurations = compiled.configurations(times)
    assert configurations.shape == (4, compiled.model.nq)
    for row, t in zip(configurations, times, strict=True):
        pin.framesForwardKinematics(compiled.model, data, row)
        for a in names:
            for b in names[::4]:
                expected = (data.oMf[compiled.frame_ids[b]].inverse()
                            * data.oMf[compiled.frame_ids[a]]).homogeneous
                np.testing.assert_allclose(tree.pose(a, b, times=[t]).matrix[0], expected,
                                           atol=1e-12)


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_the_pinocchio_model_orders_its_joints_the_same_in_every_process():
    # Sibling joints once followed set order, which string hashing changes per process.
    script = ("from pinframes import FrameTree, Pose\n"
              "tree = FrameTree()\n"
              "for name in 'hgfedcba':\n"
              "    tree.add(name, 'world', Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1]))\n"
              "print(' '.join(list(tree.to_pinocchio().model.names)[1:]))\n")
    orders = {subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                             check=True, env={**os.environ, "PYTHONHASHSEED": str(seed)}
                             ).stdout.strip() for seed in range(4)}
    assert orders == {"a b c d e f g h"}


# -- property tests on random trees -------------------------------------------------------
@st.composite
def random_trees(draw):
    seed = draw(st.integers(0, 2**32 - 1))
    count = draw(st.integers(2, 12))
    rng = np.random.default_rng(seed)
    tree = FrameTree()
    names = ["world"]
    for index in range(count):
        parent = names[rng.integers(len(names))]
        if rng.random() < 0.4:
            keyframes = int(rng.integers(1, 5))
            times = np.cumsum(rng.uniform(0.1, 1.0, size=keyframes))
            pose = Pose(rng.normal(size=(keyframes, 3)), random_rotations(rng, keyframes),
                        times=times)
        else:
            pose = Pose(rng.normal(size=3), pin.exp3(rng.normal(size=3)))
        tree.add(f"n{index}", parent, pose)
        names.append(f"n{index}")
    a, b, c = (names[i] for i in rng.integers(len(names), size=3))
    return tree, a, b, c


@settings(max_examples=60, deadline=None)
@given(random_trees())
def test_composing_along_a_path_equals_the_direct_query_and_inverses_cancel(case):
    tree, a, b, c = case
    times = np.linspace(0, 4, 9)
    a_in_b = tree.pose(a, b, times=times)
    b_in_c = tree.pose(b, c, times=times)
    a_in_c = tree.pose(a, c, times=times)
    np.testing.assert_allclose((b_in_c @ a_in_b).matrix, a_in_c.matrix, atol=1e-9)
    identity = (tree.pose(b, a, times=times) @ a_in_b).matrix
    np.testing.assert_allclose(identity, np.broadcast_to(np.eye(4), identity.shape), atol=1e-9)


def test_sample_times_are_the_times_pose_evaluates_at_by_default():
    tree = tree_with(None, [T0 + 5 * SECOND, T0 + 2 * SECOND])
    axis = tree.sample_times("a", "b")
    result = tree.pose("a", "b")
    assert axis.reference == result.reference_time
    assert axis.offsets.tolist() == result.times.astype("int64").tolist()
    tree.add("still", "world", Pose([1, 0, 0]))
    assert tree.sample_times("still") is None
