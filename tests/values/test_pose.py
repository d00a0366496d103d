import numpy as np
import pytest

from pinframes import Pose
from pinframes.errors import InvalidPoseError, InvalidTimeError, ReferenceTimeError

from geometry import homogeneous, rot_x, rot_z

QUARTER_TURN_Z = [0.0, 0.0, np.sin(np.pi / 4), np.cos(np.pi / 4)]


def test_static_pose_attributes():
    pose = Pose([1.0, 2.0, 3.0], QUARTER_TURN_Z)
    assert not pose.is_time_dependent
    assert pose.times is None and pose.reference_time is None
    np.testing.assert_allclose(pose.rotation, rot_z(np.pi / 2), atol=1e-15)
    np.testing.assert_allclose(pose.matrix, homogeneous(rot_z(np.pi / 2), [1, 2, 3]), atol=1e-15)
    np.testing.assert_allclose(pose.quaternion, QUARTER_TURN_Z, atol=1e-15)


def test_static_part_broadcasts_against_moving_part():
    pose = Pose([[0, 0, 0], [1, 0, 0], [2, 0, 0]], rot_x(0.3), times=[0, 1, 2])
    assert pose.rotation.shape == (3, 3, 3)
    np.testing.assert_allclose(pose.rotation[2], rot_x(0.3))
    turning = Pose([1, 2, 3], [[0, 0, 0, 1], QUARTER_TURN_Z], times=["0s", "2s"])
    assert turning.translation.shape == (2, 3)
    assert list(turning.times) == [np.timedelta64(0, "ns"), np.timedelta64(2, "s")]


def test_absolute_times_set_the_reference_time():
    pose = Pose(np.zeros((2, 3)), times=["2024-03-01T08:00:00", "2024-03-01T08:00:02"])
    assert pose.reference_time == np.datetime64("2024-03-01T08:00:00")
    assert pose.times[1] == np.timedelta64(2, "s")
    shifted = Pose(np.zeros((2, 3)), times=["2024-03-01T08:00:00", "2024-03-01T08:00:02"],
                   reference_time="2024-03-01T07:59:59")
    assert shifted.times[0] == np.timedelta64(1, "s")


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"translation": [0, 0, np.nan]}, "translation"),
        ({"translation": [0, 0]}, "translation"),
        ({"rotation": np.eye(3) * 2}, "rotation"),
        ({"rotation": np.diag([1.0, 1.0, -1.0])}, "rotation"),
        ({"rotation": [0, 0, 0, 2]}, "rotation"),
        ({"rotation": np.eye(4)}, "rotation"),
        ({"translation": np.zeros((3, 3)), "times": [0, 1]}, "translation"),
        ({"translation": np.zeros((2, 3))}, "translation"),
    ],
)
def test_invalid_poses_name_the_field(kwargs, field):
    with pytest.raises(InvalidPoseError) as info:
        Pose(**kwargs)
    assert info.value.field == field


def test_reflection_is_named_as_such():
    with pytest.raises(InvalidPoseError, match="reflection"):
        Pose(rotation=np.diag([1.0, -1.0, 1.0]))


@pytest.mark.parametrize("times", [[0, 0], [1, 0], [0, 2, 1]])
def test_times_must_strictly_increase(times):
    with pytest.raises(InvalidTimeError, match="strictly increasing"):
        Pose(np.zeros((len(times), 3)), times=times)


def test_inverse_and_composition_match_matrix_algebra(rng):
    q = rng.normal(size=4)
    a = Pose(rng.normal(size=3), q / np.linalg.norm(q))
    b = Pose.from_xyz_rpy(*rng.normal(size=6))
    np.testing.assert_allclose(a.inverse().matrix, np.linalg.inv(a.matrix), atol=1e-12)
    np.testing.assert_allclose((a @ b).matrix, a.matrix @ b.matrix, atol=1e-12)


def test_from_matrix_round_trips_and_checks_the_last_row():
    matrix = homogeneous(rot_x(0.2) @ rot_z(1.0), [0.1, 0.2, 0.3])
    np.testing.assert_allclose(Pose.from_matrix(matrix).matrix, matrix, atol=1e-15)
    bad = matrix.copy()
    bad[3, 0] = 1.0
    with pytest.raises(InvalidPoseError):
        Pose.from_matrix(bad)


def test_from_xyz_rpy_is_rz_ry_rx():
    pose = Pose.from_xyz_rpy(1, 2, 3, 0.1, 0.2, 0.3)
    c, s = np.cos(0.2), np.sin(0.2)
    rot_y = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    np.testing.assert_allclose(pose.rotation, rot_z(0.3) @ rot_y @ rot_x(0.1), atol=1e-15)
    np.testing.assert_allclose(pose.to_xyz_rpy(), [1, 2, 3, 0.1, 0.2, 0.3], atol=1e-14)


def test_at_interpolates_linearly_and_by_slerp_and_holds_outside():
    pose = Pose([[0, 0, 0], [2, 0, 0]], [[0, 0, 0, 1], QUARTER_TURN_Z], times=[0, 2])
    sampled = pose.at([-1, 0.5, 1, 3])
    np.testing.assert_allclose(sampled.translation[:, 0], [0, 0.5, 1, 2])
    np.testing.assert_allclose(sampled.rotation[1], rot_z(np.pi / 8), atol=1e-15)
    np.testing.assert_allclose(sampled.rotation[2], rot_z(np.pi / 4), atol=1e-15)
    np.testing.assert_allclose(sampled.rotation[0], np.eye(3), atol=1e-15)
    np.testing.assert_allclose(sampled.rotation[3], rot_z(np.pi / 2), atol=1e-15)


def test_slerp_takes_the_shortest_arc():
    # 0 -> 270 degrees about z is stored; the short way is -90 degrees.
    pose = Pose(rotation=[rot_z(0.0), rot_z(1.5 * np.pi)], times=[0, 1])
    np.testing.assert_allclose(pose.at(0.5).rotation[0], rot_z(-np.pi / 4), atol=1e-15)


def test_at_with_absolute_times_and_time_ref():
    pose = Pose([[0, 0, 0], [10, 0, 0]], times=["2024-01-01T00:00:00", "2024-01-01T00:00:10"])
    at_abs = pose.at(["2024-01-01T00:00:02"])
    np.testing.assert_allclose(at_abs.translation, [[2, 0, 0]])
    assert at_abs.reference_time == np.datetime64("2024-01-01T00:00:00")
    with_ref = pose.at([1.0], time_ref="2024-01-01T00:00:05")
    np.testing.assert_allclose(with_ref.translation, [[6, 0, 0]])
    assert with_ref.reference_time == np.datetime64("2024-01-01T00:00:05")
    assert with_ref.times[0] == np.timedelta64(1, "s")
    relative = Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1])
    with pytest.raises(ReferenceTimeError):
        relative.at(["2024-01-01T00:00:02"])


def test_composition_of_two_timelines_uses_their_union():
    a = Pose([[0, 0, 0], [1, 0, 0]], times=[0, 2])
    b = Pose([[0, 0, 0], [0, 3, 0]], times=[1, 4])
    combined = a @ b
    assert combined.times.astype("timedelta64[s]").astype(int).tolist() == [0, 1, 2, 4]
    np.testing.assert_allclose(combined.translation,
                               [[0, 0, 0], [0.5, 0, 0], [1, 1, 0], [1, 3, 0]], atol=1e-15)


def test_composition_refuses_mixing_relative_and_absolute_poses():
    a = Pose(np.zeros((2, 3)), times=[0, 1])
    b = Pose(np.zeros((2, 3)), times=["2024-01-01T00:00:00", "2024-01-01T00:00:01"])
    with pytest.raises(ReferenceTimeError):
        a @ b


def test_times_500_years_apart_are_an_error_not_a_wrap_around():
    # the query rules (SPEC 4) apply to poses too: a ReferenceTimeError, as for tree.pose
    late = Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1], reference_time="2200-01-01")
    early = Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1], reference_time="1700-01-01")
    np.testing.assert_allclose(late.at(["2200-01-01T00:00:00.5"]).translation, [[0.5, 0, 0]])
    with pytest.raises(ReferenceTimeError, match="292 years"):
        late @ early
    with pytest.raises(ReferenceTimeError, match="292 years"):
        late.at(["2200-01-01T00:00:00.5"], time_ref="1700-01-01")
    with pytest.raises(ReferenceTimeError, match="292 years"):
        late.at([0.5], time_ref="1700-01-01")
