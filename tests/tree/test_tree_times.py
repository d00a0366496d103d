"""FrameTree.time_union and FrameTree.resampled, against times and values worked out by hand."""

from __future__ import annotations

import numpy as np
import pytest

from pinframes import FrameNotFoundError, FrameTree, Joint, Pose, ReferenceTimeError

from geometry import rot_z

T0 = np.datetime64("2024-03-01T08:00:00", "ns")
S = 1_000_000_000


def tree() -> FrameTree:
    """slide: x from 0 to 2 m over 0..2 s (tree time); cart: y from 0 to 1 m over its own
    1..3 s after T0 + 10 s; a revolute joint sampled at 0, 4 s; one static frame."""
    t = FrameTree("world", reference_time=T0)
    t.add("slide", "world", Pose([[0, 0, 0], [2.0, 0, 0]], times=[0.0, 2.0]))
    t.add("cart", "slide", Pose([[0, 0, 0], [0, 1.0, 0]], rot_z(0.5), times=[1.0, 3.0],
                                reference_time=T0 + np.timedelta64(10, "s")))
    t.add("post", "world", Pose([0, 0, 1.0]))
    t.attach_joint("arm", "post", Joint("swing", "revolute", (0.0, 0.0, 1.0)))
    t.set_joint_trajectory([0.0, 4.0], [[0.0], [2.0]], ["swing"])
    return t


def test_time_union_of_the_whole_tree_and_of_some_frames():
    union = tree().time_union()
    assert union.reference == T0
    np.testing.assert_array_equal(union.offsets, [0, 2 * S, 4 * S, 11 * S, 13 * S])
    part = tree().time_union(["cart", "post"])
    np.testing.assert_array_equal(part.offsets, [11 * S, 13 * S])
    assert tree().time_union(["post", "world"]) is None
    with pytest.raises(FrameNotFoundError):
        tree().time_union(["nowhere"])


def test_the_time_union_goes_back_into_queries_as_times():
    t = tree()
    union = t.time_union()  # 0, 2, 4, 11, 13 s after T0
    pose = t.pose("cart", relative_to="world", times=union)
    np.testing.assert_array_equal(pose.times.astype(np.int64), union.offsets)
    assert pose.reference_time == T0
    # by hand: the slide holds x = 2 m after 2 s; the cart's y runs 0..1 m over 11..13 s
    np.testing.assert_allclose(pose.translation, [[0, 0, 0], [2, 0, 0], [2, 0, 0],
                                                  [2, 0, 0], [2, 1, 0]], atol=1e-15)
    relative = FrameTree("world")
    relative.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0.0, 10.0]))
    np.testing.assert_allclose(relative.pose("a", times=relative.time_union()).seconds,
                               [0.0, 10.0])
    np.testing.assert_allclose(Pose([0, 0, 0], times=union).seconds, [0, 2, 4, 11, 13])


def test_time_union_without_a_tree_reference_uses_the_earliest_frame_reference():
    t = FrameTree("world")
    t.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=["2024-01-01T00:00:05",
                                                           "2024-01-01T00:00:06"]))
    t.add("b", "world", Pose([[0, 0, 0], [1, 0, 0]], times=["2024-01-01T00:00:01",
                                                           "2024-01-01T00:00:02"]))
    union = t.time_union()
    assert union.reference == np.datetime64("2024-01-01T00:00:01", "ns")
    np.testing.assert_array_equal(union.offsets, [0, S, 4 * S, 5 * S])


def test_resampled_copy_holds_samples_at_the_given_times_only():
    original = tree()
    copy = original.resampled([0.5, 1.0, 11.5, 12.0])
    slide = copy.local_pose("slide")
    np.testing.assert_array_equal(slide.times.astype(np.int64), [S // 2, S, 23 * S // 2, 12 * S])
    # x moves 1 m/s until 2 s, then holds
    np.testing.assert_allclose(slide.translation[:, 0], [0.5, 1.0, 2.0, 2.0], atol=1e-15)
    cart = copy.local_pose("cart")
    assert cart.reference_time == T0 + np.timedelta64(10, "s")  # kept, times on its basis
    np.testing.assert_array_equal(cart.times.astype(np.int64), [-19 * S // 2, -9 * S,
                                                                3 * S // 2, 2 * S])
    # y moves 0.5 m/s from its 1 s to 3 s, held at 0 before
    np.testing.assert_allclose(cart.translation[:, 1], [0.0, 0.0, 0.25, 0.5], atol=1e-15)
    np.testing.assert_allclose(cart.rotation, np.broadcast_to(rot_z(0.5), (4, 3, 3)),
                               atol=1e-15)
    track = copy.joint_track("swing")
    np.testing.assert_allclose(track.values, [0.25, 0.5, 2.0, 2.0], atol=1e-15)
    assert not copy.is_moving("post")
    assert original.local_pose("slide").times.shape == (2,)  # the original is untouched


def test_resampled_with_absolute_times_and_a_time_ref():
    absolute = tree().resampled(["2024-03-01T08:00:01", "2024-03-01T08:00:12"])
    np.testing.assert_allclose(absolute.local_pose("slide").translation[:, 0], [1.0, 2.0])
    np.testing.assert_allclose(absolute.local_pose("cart").translation[:, 1], [0.0, 0.5])
    shifted = tree().resampled([0.0, 1.0], time_ref="2024-03-01T08:00:11")
    np.testing.assert_allclose(shifted.local_pose("cart").translation[:, 1], [0.0, 0.5])
    np.testing.assert_allclose(shifted.local_pose("slide").translation[:, 0], [2.0, 2.0])


def test_relative_times_need_something_to_count_from():
    t = FrameTree("world")
    t.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=["2024-01-01T00:00:05",
                                                           "2024-01-01T00:00:06"]))
    with pytest.raises(ReferenceTimeError):
        t.resampled([0.0, 1.0])
    resampled = t.resampled([0.0, 0.5], time_ref="2024-01-01T00:00:05")
    np.testing.assert_allclose(resampled.local_pose("a").translation[:, 0], [0.0, 0.5])
