"""Finite inputs that overflow when combined, and complex numbers, are pinframes errors:
never an infinite or NaN answer, never a silently dropped imaginary part."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from pinframes import (
    FrameTree,
    InvalidDataError,
    InvalidPoseError,
    Joint,
    JointError,
    Pose,
    SpatialData,
)

HUGE = 1e308  # metres: finite, but two of them add up to more than a float holds
EIGHTH_TURN_Z = [0.0, 0.0, np.sin(np.pi / 8), np.cos(np.pi / 8)]  # 45 degrees about z


@pytest.fixture(autouse=True)
def _quiet_overflow():
    with warnings.catch_warnings():  # numpy says "overflow encountered" before we refuse
        warnings.simplefilter("ignore", RuntimeWarning)
        yield


def far_chain() -> FrameTree:
    tree = FrameTree("world")
    tree.add("a", "world", Pose([HUGE, 0.0, 0.0]))
    tree.add("b", "a", Pose([HUGE, 0.0, 0.0]))
    tree.add("mover", "b", Pose([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], times=[0.0, 1.0]))
    return tree


@pytest.mark.parametrize("frame", ["b", "mover"])
def test_a_chain_of_huge_translations_is_refused_not_infinite(frame):
    tree = far_chain()
    with pytest.raises(InvalidPoseError, match="overflows") as info:
        tree.pose(frame, relative_to="world")
    assert info.value.frame == frame and info.value.field == "translation"
    with pytest.raises(InvalidPoseError, match=f"'{frame}' in 'world'"):
        tree.poses(["a", frame], relative_to="world")
    # the parts are fine on their own
    np.testing.assert_array_equal(tree.pose("a", relative_to="world").translation,
                                  [HUGE, 0.0, 0.0])


def test_composing_and_inverting_huge_poses_is_refused():
    step = Pose([HUGE, 0.0, 0.0])
    with pytest.raises(InvalidPoseError, match="overflows"):
        step @ step
    diagonal = Pose([1.5e308, 1.5e308, 0.0], EIGHTH_TURN_Z)  # |t| = 2.1e308 along one axis
    with pytest.raises(InvalidPoseError, match="overflows"):
        diagonal.inverse()


def test_velocities_of_huge_steps_are_refused():
    tree = FrameTree("world")
    tree.add("jump", "world", Pose([[-HUGE, 0.0, 0.0], [HUGE, 0.0, 0.0]], times=[0.0, 1.0]))
    with pytest.raises(InvalidPoseError, match="overflows") as info:
        tree.velocity("jump", times=[0.5])
    assert info.value.field == "linear" and info.value.frame == "jump"


def test_points_that_overflow_are_refused():
    tree = FrameTree("world")
    tree.add("far", "world", Pose([HUGE, 0.0, 0.0]))
    with pytest.raises(InvalidDataError, match="overflows") as info:
        tree.transform_points([HUGE, 0.0, 0.0], "far", "world")
    assert info.value.field == "points" and info.value.frame == "far"


def test_complex_numbers_are_refused_not_truncated():
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 0.0, 0.0]))
    tree.attach_joint("arm", "table", Joint("turn", "revolute", (0.0, 0.0, 1.0)))
    point = np.array([1.0 + 2.0j, 0.0, 0.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # not even a ComplexWarning on the way
        with pytest.raises(InvalidDataError, match="complex") as info:
            tree.transform_points(point, "table", "world")
        assert info.value.field == "points"
        with pytest.raises(InvalidDataError, match="complex"):
            tree.transform_vectors(point, "table", "world")
        with pytest.raises(InvalidDataError, match="complex"):
            SpatialData(point[None])
        with pytest.raises(InvalidPoseError, match="complex") as info:
            Pose(point)
        assert info.value.field == "translation"
        with pytest.raises(InvalidPoseError, match="complex"):
            Pose.from_euler("z", np.array([1j]))
        with pytest.raises(JointError, match="complex"):
            tree.set_joint_trajectory([0.0], np.array([[0.5 + 0.5j]]))
