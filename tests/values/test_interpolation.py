"""Interpolation schemes (values/interpolation.py): the segment search, the schemes' record on
keyframes and trajectories, and a second joint scheme taken end to end by one class.

Numbers are checked against hand-computed values, never against pinframes itself."""

from __future__ import annotations

import numpy as np
import pytest

from pinframes import FrameTree, Joint, JointTrajectory, Pose
from pinframes.values.interpolation import (
    JointInterpolation,
    Keyframes,
    LinearSlerp,
    LinearValues,
    Segments,
    segment_position,
)

S = 10**9


def test_segments_by_hand():
    samples = np.array([0, 2 * S, 6 * S])
    times = np.array([-S, 0, S, 2 * S, 5 * S, 6 * S, 7 * S])
    segments = Segments(samples, times)
    assert segments.index.tolist() == [0, 0, 0, 1, 1, 1, 1]
    np.testing.assert_array_equal(segments.fraction, [0, 0, 0.5, 0, 0.75, 1, 1])
    # 1 / 2 s on the first segment, 1 / 4 s on the second, 0 where the value is held
    np.testing.assert_array_equal(segments.inverse_duration, [0, 0.5, 0.5, 0.25, 0.25, 0.25, 0])
    one = Segments(np.array([5]), times)
    assert one.index.tolist() == [0] * 7
    assert one.fraction.tolist() == [0.0] * 7 and one.inverse_duration.tolist() == [0.0] * 7
    assert segment_position(samples, 5 * S) == (1, 0.75)


def test_the_schemes_are_recorded():
    pose = Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 1.0])
    assert pose.keyframes.interpolation is LinearSlerp
    assert isinstance(pose.keyframes.scheme(), LinearSlerp)
    trajectory = JointTrajectory(np.array([0, S]), None, np.array([0.0, 1.0]))
    assert trajectory.interpolation is LinearValues
    # placing keyframes keeps their scheme
    placed = pose.keyframes.placed((np.eye(3), np.array([0.0, 0.0, 1.0])))
    assert placed.interpolation is LinearSlerp
    np.testing.assert_array_equal(placed.translations, [[0, 0, 1], [1, 0, 1]])


def test_linear_slerp_rates_by_hand():
    """A quarter turn about z and 2 m along x in 2 s: pi/4 rad/s and 1 m/s, 0 when held."""
    rotations = np.array([np.eye(3), [[0, -1, 0], [1, 0, 0], [0, 0, 1]]], dtype=float)
    keyframes = Keyframes(np.array([0, 2 * S]), rotations, np.array([[0.0, 0, 0], [2, 0, 0]]))
    linear, angular = keyframes.rates(np.array([-S, S, 3 * S]))
    np.testing.assert_allclose(linear, [[0, 0, 0], [1, 0, 0], [0, 0, 0]], atol=1e-15)
    np.testing.assert_allclose(angular, [[0, 0, 0], [0, 0, np.pi / 4], [0, 0, 0]], atol=1e-15)
    translation, quaternion = keyframes.pose_at(S)
    np.testing.assert_allclose(translation, [1, 0, 0])
    np.testing.assert_allclose(quaternion, [0, 0, np.sin(np.pi / 8), np.cos(np.pi / 8)])


class HeldValues(JointInterpolation):
    """A second joint scheme, written here: each sample's value holds until the next."""

    def sample(self, times, segments=None):
        if segments is None:
            segments = Segments(self.times, times)
        held = self.values[segments.index].copy()
        held[times >= self.times[-1]] = self.values[-1]
        return held

    def value_at(self, time, position=None):
        index, _ = position or segment_position(self.times, time)
        return float(self.values[-1] if time >= self.times[-1] else self.values[index])

    def rates(self, times, segments=None):
        return np.zeros(times.shape)


@pytest.mark.parametrize("count", [1, 20])  # the one-time path and the batched kernels
def test_a_second_joint_scheme_is_one_class(count):
    """A slider driven by a held trajectory: every query takes the scheme the trajectory
    records, without a change anywhere else."""
    tree = FrameTree()
    tree.attach_joint("carriage", "world", Joint("slide", "prismatic", (1.0, 0.0, 0.0),
                                                 lower=-9.0, upper=9.0))
    tree.replace_joint_trajectory("slide", JointTrajectory(
        np.array([0, S, 2 * S]), None, np.array([0.0, 1.0, 3.0]), HeldValues))
    times = np.linspace(-0.5, 2.5, count) if count > 1 else np.array([1.5])
    pose = tree.pose("carriage", "world", times=times)
    held = np.where(times < 1.0, 0.0, np.where(times < 2.0, 1.0, 3.0))
    np.testing.assert_array_equal(pose.translation[:, 0], held)
    velocity = tree.velocity("carriage", "world", times=times)
    np.testing.assert_array_equal(velocity.linear, np.zeros((times.shape[0], 3)))
    assert tree.joint_trajectory("slide").interpolation is HeldValues
    # a resampled or grafted copy keeps the scheme
    assert tree.resampled([0.0, 2.0]).joint_trajectory("slide").interpolation is HeldValues
    other = FrameTree()
    other.graft(tree, "world", prefix="a/")
    assert other.joint_trajectory("a/slide").interpolation is HeldValues



@pytest.mark.parametrize("count", [1, 20])  # the one-time path and the batched kernels
def test_joints_on_equal_times_from_other_references_are_searched_apart(count):
    """Two sliders hold the same sample offsets and values, counted from reference times
    10 s apart: at one instant each is at its own place (a shared segment search would put
    both at the first's)."""
    tree = FrameTree()
    tree.attach_joint("x", "world", Joint("slide_x", "prismatic", (1.0, 0.0, 0.0),
                                          lower=-99.0, upper=99.0))
    tree.attach_joint("y", "x", Joint("slide_y", "prismatic", (0.0, 1.0, 0.0),
                                      lower=-99.0, upper=99.0))
    start = np.datetime64("2026-01-01T00:00:00", "ns")
    offsets = np.array([0, 20 * S])
    values = np.array([0.0, 20.0])  # 1 m/s
    tree.replace_joint_trajectory("slide_x", JointTrajectory(offsets, start, values))
    tree.replace_joint_trajectory("slide_y", JointTrajectory(
        offsets, start + np.timedelta64(10, "s"), values))
    seconds = np.linspace(10.0, 20.0, count) if count > 1 else np.array([15.0])
    times = start + (seconds * 1e9).astype("timedelta64[ns]")
    pose = tree.pose("y", "world", times=times)
    np.testing.assert_allclose(pose.translation[:, 0], seconds, atol=1e-9)
    np.testing.assert_allclose(pose.translation[:, 1], seconds - 10.0, atol=1e-9)
    velocity = tree.velocity("y", "world", times=times)
    np.testing.assert_allclose(velocity.linear[:, :2], np.ones((count, 2)), atol=1e-9)
