"""Points and directions moved between frames, per time, against hand-derived values."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hardening.tree_model import build_tree
from hardening.tree_strategies import absolute_trees, trees
from pinframes import FrameTree, InvalidDataError, Pose, SpatialData
from pinframes.errors import ExtrapolationError, FrameNotFoundError

from geometry import rot_z

QUARTER_TURN_Z = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]
FIXED = settings(max_examples=30, deadline=None, derandomize=True, database=None,
                 suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def turning_table() -> FrameTree:
    """A table 0.8 m up at x = 1.5 m turning 90 degrees about z in 10 s."""
    tree = FrameTree("world")
    tree.add("positioner", "world", Pose([1.5, 0.0, 0.8]))
    tree.add("table", "positioner", Pose(rotation=[[0, 0, 0, 1], QUARTER_TURN_Z],
                                         times=[0.0, 10.0]))
    return tree


def test_a_point_on_a_turning_table_follows_its_circle():
    tree = turning_table()
    times = [0.0, 5.0, 10.0, 12.0]
    points = tree.transform_points([0.2, 0.0, 0.05], "table", "world", times)
    angles = np.array([0.0, np.pi / 4, np.pi / 2, np.pi / 2])  # held after 10 s
    expected = np.stack([1.5 + 0.2 * np.cos(angles), 0.2 * np.sin(angles),
                         np.full(4, 0.85)], axis=1)
    np.testing.assert_allclose(points, expected, atol=1e-15)


def test_one_point_per_time_and_profiles_per_time():
    tree = turning_table()
    times = [0.0, 5.0, 10.0]
    # (T, 3) with per_time=True: row i at time i
    rows = tree.transform_points([[0.1, 0, 0], [0.1, 0, 0], [0, 0.1, 0]], "table", "world",
                                 times, per_time=True)
    np.testing.assert_allclose(rows, [[1.6, 0, 0.8], [1.5 + 0.1 / np.sqrt(2),
                                                      0.1 / np.sqrt(2), 0.8],
                                      [1.4, 0, 0.8]], atol=1e-15)
    # (M, 3) with M != T: every point at every time
    profile = np.array([[0.1, 0, 0], [0.2, 0, 0]])
    out = tree.transform_points(profile, "table", "world", times)
    assert out.shape == (3, 2, 3)
    for index, angle in enumerate([0.0, np.pi / 4, np.pi / 2]):
        np.testing.assert_allclose(out[index], profile @ rot_z(angle).T + [1.5, 0, 0.8],
                                   atol=1e-15)
    # (T, M, 3): a profile per time; (1, M, 3): the same profile at every time
    per_time = np.stack([profile, 2 * profile, 3 * profile])
    out = tree.transform_points(per_time, "table", "world", times)
    np.testing.assert_allclose(out[2], (3 * profile) @ rot_z(np.pi / 2).T + [1.5, 0, 0.8],
                               atol=1e-15)
    square = np.eye(3)  # M == T: still every point at every time, unless paired on request
    assert tree.transform_points(square, "table", "world", times).shape == (3, 3, 3)
    assert tree.transform_points(square[None], "table", "world", times).shape == (3, 3, 3)
    assert tree.transform_points(square, "table", "world", times, per_time=True).shape == (3, 3)


def test_without_times_every_point_is_at_every_keyframe_whatever_their_count():
    tree = turning_table()  # two keyframes, at 0 s and 10 s
    points = np.array([[0.1, 0.0, 0.0], [0.0, 0.2, 0.0]])  # as many points as keyframes
    expected = np.stack([points @ rot_z(angle).T + [1.5, 0.0, 0.8]
                         for angle in (0.0, np.pi / 2)])
    np.testing.assert_allclose(tree.transform_points(points, "table", "world"), expected,
                               atol=1e-15)
    np.testing.assert_allclose(tree.transform_vectors(points, "table", "world"),
                               expected - [1.5, 0.0, 0.8], atol=1e-15)
    # the same rule as get_data
    tree.assign_data("profile", SpatialData(points), "table")
    np.testing.assert_allclose(tree.get_data("profile", relative_to="world").points, expected,
                               atol=1e-15)
    # pairing is asked for explicitly, and a count that does not match is an error
    paired = tree.transform_points(points, "table", "world", per_time=True)
    np.testing.assert_allclose(paired, [expected[0, 0], expected[1, 1]], atol=1e-15)
    with pytest.raises(InvalidDataError, match="3 rows were given for 2 times") as info:
        tree.transform_points(np.zeros((3, 3)), "table", "world", per_time=True)
    assert info.value.field == "points" and info.value.frame == "table"


def test_vectors_only_rotate():
    tree = FrameTree()
    tree.add("far", "world", Pose([100.0, -50.0, 7.0], QUARTER_TURN_Z))
    np.testing.assert_allclose(tree.transform_vectors([1.0, 0.0, 0.0], "far", "world"),
                               [0.0, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(tree.transform_points([1.0, 0.0, 0.0], "far", "world"),
                               [100.0, -49.0, 7.0], atol=1e-13)
    # a static path keeps the shape
    assert tree.transform_points(np.zeros((4, 3)), "far", "world").shape == (4, 3)
    assert tree.transform_points(np.zeros((2, 4, 3)), "far", "world").shape == (2, 4, 3)


def test_pose_transforms_static_and_sampled():
    static = Pose([1.0, 2.0, 3.0], QUARTER_TURN_Z)
    np.testing.assert_allclose(static.transform_points([[1.0, 0.0, 0.0]]), [[1.0, 3.0, 3.0]],
                               atol=1e-15)
    sampled = Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0])
    assert sampled.transform_points([0.0, 0.0, 1.0]).tolist() == [[0, 0, 1], [1, 0, 1]]
    assert sampled.transform_points(np.zeros((5, 3))).shape == (2, 5, 3)
    assert sampled.transform_vectors(np.ones((2, 3))).shape == (2, 2, 3)
    assert sampled.transform_vectors(np.ones((2, 3)), per_time=True).tolist() == [
        [1, 1, 1], [1, 1, 1]]


def test_round_trip_a_to_b_to_a(rng):
    tree = turning_table()
    tree.add("arm", "world", Pose([[0, 0, 1], [1, 1, 1]], times=[2.0, 4.0]))
    times = np.linspace(-1.0, 12.0, 27)
    points = rng.normal(size=(27, 3))
    there = tree.transform_points(points, "table", "arm", times, per_time=True)
    back = tree.transform_points(there, "arm", "table", times, per_time=True)
    np.testing.assert_allclose(back, points, atol=1e-13)


@FIXED
@given(spec=trees() | absolute_trees(), data=st.data())
def test_transformed_points_match_numpy_composition(spec, data):
    tree = build_tree(spec)
    a = data.draw(st.sampled_from(tree.frames))
    b = data.draw(st.sampled_from(tree.frames))
    instants = spec.instants()
    rng = np.random.default_rng(len(instants))
    points = rng.normal(size=(len(instants), 3))
    world = spec.poses_in_root(instants)
    a_in_b = np.linalg.inv(world[b]) @ world[a]
    expected = np.einsum("nij,nj->ni", a_in_b[:, :3, :3], points) + a_in_b[:, :3, 3]
    ours = tree.transform_points(points, a, b, spec.query_times(instants), per_time=True)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=1e-11)


@pytest.mark.parametrize(
    ("points", "message"),
    [
        (np.zeros((4, 2)), "shape"),
        (np.zeros((2, 2, 2, 3)), "shape"),
        (np.zeros((5, 2, 3)), "5 profiles"),
        ([[0.0, np.nan, 0.0]], "non-finite"),
        ("abc", "numbers"),
    ],
)
def test_bad_points_name_the_argument_and_the_frame(points, message):
    tree = turning_table()
    with pytest.raises(InvalidDataError, match=message) as info:
        tree.transform_points(points, "table", "world", [0.0, 1.0, 2.0])
    assert info.value.field == "points" and info.value.frame == "table"
    with pytest.raises(InvalidDataError) as info:
        tree.transform_vectors(points, "table", "world", [0.0, 1.0, 2.0])
    assert info.value.field == "vectors" and info.value.frame == "table"


def test_unknown_frames_and_extrapolation_follow_pose():
    tree = turning_table()
    with pytest.raises(FrameNotFoundError):
        tree.transform_points([0, 0, 0], "nowhere", "world", [0.0])
    with pytest.raises(ExtrapolationError):
        tree.transform_points([0, 0, 0], "table", "world", [11.0], extrapolation="error")


def test_absolute_times_and_time_ref_follow_pose():
    tree = FrameTree(reference_time="2024-03-01T08:00:00")
    tree.add("table", "world", Pose(rotation=[[0, 0, 0, 1], QUARTER_TURN_Z], times=[0.0, 10.0]))
    at_five = tree.transform_points([1.0, 0.0, 0.0], "table", "world",
                                    ["2024-03-01T08:00:05"])
    np.testing.assert_allclose(at_five, [[np.sqrt(0.5), np.sqrt(0.5), 0.0]], atol=1e-15)
    shifted = tree.transform_points([1.0, 0.0, 0.0], "table", "world", [0.0],
                                    time_ref="2024-03-01T08:00:05")
    np.testing.assert_allclose(shifted, at_five, atol=1e-15)
