"""Selecting samples of a Pose, float seconds, its repr and its quaternion series."""

import numpy as np
import pinocchio as pin
import pytest

from pinframes import InvalidTimeError, Pose

REFERENCE = "2024-03-01T08:00:00"


@pytest.fixture
def moving(rng):
    translations = rng.normal(size=(6, 3))
    rotations = np.array([pin.exp3(rng.normal(size=3)) for _ in range(6)])
    seconds = np.array([0.0, 0.5, 1.25, 2.0, 3.0, 4.5])
    return Pose(translations, rotations, times=seconds, reference_time=REFERENCE), (
        translations, rotations, seconds)


@pytest.mark.parametrize("key", [2, -1, slice(1, 4), slice(None, None, 2),
                                 [0, 3, 5], np.array([True, False, True, True, False, True])])
def test_selection_keeps_samples_times_and_reference_time(moving, key):
    pose, (translations, rotations, seconds) = moving
    part = pose[key]
    expected = np.atleast_1d(np.arange(6)[key])
    assert len(part) == expected.size
    np.testing.assert_array_equal(part.translation, translations[expected])
    np.testing.assert_array_equal(part.rotation, rotations[expected])
    np.testing.assert_allclose(part.seconds, seconds[expected])
    assert part.reference_time == np.datetime64(REFERENCE, "ns")
    assert part.is_time_dependent


def test_a_mask_built_from_seconds_selects_those_times(moving):
    pose, (_, _, seconds) = moving
    late = pose[pose.seconds > 1.0]
    np.testing.assert_allclose(late.seconds, [1.25, 2.0, 3.0, 4.5])
    np.testing.assert_array_equal(
        late.absolute_times, np.datetime64(REFERENCE, "ns")
        + (seconds[2:] * 1e9).astype("timedelta64[ns]"))


@pytest.mark.parametrize("key", [slice(None, None, -1), [3, 1], slice(4, 2)])
def test_selections_that_reverse_or_empty_the_times_are_refused(moving, key):
    pose, _ = moving
    with pytest.raises(InvalidTimeError):
        pose[key]


def test_an_index_beyond_the_samples_is_an_index_error(moving):
    with pytest.raises(IndexError):
        moving[0][6]


def test_a_static_pose_is_its_own_only_sample():
    pose = Pose([1.0, 2.0, 3.0])
    assert len(pose) == 1
    assert pose[0] is pose and pose[-1] is pose
    assert pose.seconds is None
    with pytest.raises(InvalidTimeError):
        pose[1]


def test_seconds_are_floats_that_column_stack_takes():
    pose = Pose(np.zeros((3, 3)), times=["0s", "250ms", "P0DT0H0M2S"])
    assert pose.seconds.dtype == np.float64
    np.testing.assert_array_equal(pose.seconds, [0.0, 0.25, 2.0])
    table = np.column_stack([pose.seconds, pose.translation])
    assert table.shape == (3, 4)


def test_repr_shows_seconds_timestamps_and_the_first_and_last_numbers():
    quarter_z = [0.0, 0.0, np.sqrt(0.5), np.sqrt(0.5)]  # 90 degrees about z
    relative = Pose([[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 2.0, 3.5]],
                    [[0, 0, 0, 1], [0, 0, 0, 1], quarter_z], times=[0.0, 0.5, 1.0])
    assert repr(relative) == ("Pose(3 samples from 0 s to 1 s: translation=(0, 0, 0) to "
                              "(1, 2, 3.5), quaternion=(0, 0, 0, 1) to "
                              "(0, 0, 0.707107, 0.707107))")
    absolute = Pose([[0.0, 0.0, 0.0], [1.0, 2.0, 3.5]], times=[0.0, 2.5],
                    reference_time=REFERENCE)
    assert repr(absolute) == ("Pose(2 samples from 0 s to 2.5 s after 2024-03-01T08:00:00, "
                              "2024-03-01T08:00:00 to 2024-03-01T08:00:02.5: translation="
                              "(0, 0, 0) to (1, 2, 3.5), quaternion=(0, 0, 0, 1) to "
                              "(0, 0, 0, 1))")
    assert repr(absolute[1]) == ("Pose(1 sample at 2.5 s after 2024-03-01T08:00:00, "
                                 "2024-03-01T08:00:02.5: translation=(1, 2, 3.5), "
                                 "quaternion=(0, 0, 0, 1))")


def test_quaternion_series_is_sign_continuous_and_the_same_rotations():
    # three full turns about z: w = cos(angle / 2) changes sign every turn
    angles = np.linspace(0.0, 6 * np.pi, 181)
    rotations = [pin.exp3(np.array([0.0, 0.0, angle])) for angle in angles]
    quaternions = Pose(rotation=rotations, times=angles).quaternion
    assert quaternions[0, 3] >= 0.0
    assert np.all(np.einsum("ij,ij->i", quaternions[1:], quaternions[:-1]) > 0.0)
    # the continuous series of this turn is (0, 0, sin(a/2), cos(a/2)) itself
    expected = np.column_stack([np.zeros((angles.size, 2)), np.sin(angles / 2),
                                np.cos(angles / 2)])
    np.testing.assert_allclose(quaternions, expected, atol=1e-12)


def test_quaternion_of_a_static_pose_has_non_negative_w():
    rotation = pin.exp3(np.array([0.0, 0.0, 1.5 * np.pi]))  # w = cos(3 pi / 4) < 0
    q = Pose(rotation=rotation).quaternion
    assert q[3] >= 0.0
    np.testing.assert_allclose(np.abs(q), [0, 0, np.sin(0.75 * np.pi), -np.cos(0.75 * np.pi)],
                               atol=1e-12)
