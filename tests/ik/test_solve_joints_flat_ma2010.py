"""Flat that is flat on a real cell: ROS-Industrial's Yaskawa MA2010 and MOTOPOS D500
tilt/turn positioner (tests/data/ma2010_cell) with the positioner in six placements, a whole
girth seam (361 keyframes, 8 mm/s) on a pipe on its faceplate, ``flat=`` without a seed;
with and without process windows. Every number is measured with Pinocchio on the placed
URDF (tests/girth_cell.py), at the samples and between them (joints linear)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from girth_cell import (
    FLAT_TOLERANCE,
    PACKAGES,
    PATH_TOLERANCE,
    PLACEMENTS,
    SPEED,
    TILT,
    TOLERANCE,
    measure,
    placed_cell,
    seam_keyframes,
)
from pinframes import Pose, read_urdf

FAST = ["shipped", "left_side"]  # the others in the slow set


def solved(folder, placement: str, tilt, turns: float = 1.0, **options):
    """The placed cell's URDF, and its solve of a girth seam ``turns`` times round."""
    urdf = placed_cell(folder, *PLACEMENTS[placement])
    tree = read_urdf(urdf, package_dirs=[PACKAGES])
    times, origins, axes = seam_keyframes(turns)
    tree.add("seam", "workpiece", Pose(origins, axes, times=times))
    joints = [name for name in tree.joints if tree.joints[name].is_actuated]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints have no samples
        solution = tree.solve_joints("torch_tip", "seam", joints=joints, free_axis="z",
                                     flat="seam", tilt=tilt, **options)
    return urdf, solution


def check_flat_all_along(urdf, solution, tilt) -> None:
    """Every sample reached and flat (the face within flat_tolerance of up), the torch tip
    on the seam point, its z the face's (or within the windows), and between the samples
    the tip within path_tolerance of the seam, the face flat and the weld point going
    forwards at about the seam's speed."""
    times = seam_keyframes()[0]
    assert solution.all_reached
    assert set(np.round(times, 6)).issubset(np.round(solution.seconds, 6))
    measured = measure(urdf, solution.joint_names, solution.seconds, solution.positions)
    assert measured.face.max() <= FLAT_TOLERANCE
    np.testing.assert_allclose(solution.flat_error, measured.face, atol=1e-6)  # arccos near 0
    assert measured.off_seam.max() <= TOLERANCE
    windows = np.zeros(2) if tilt is None else np.asarray(tilt)
    assert np.all(np.abs(measured.tilt) <= windows + TOLERANCE)
    assert measured.off_circle_between.max() <= PATH_TOLERANCE
    assert measured.face_between.max() <= FLAT_TOLERANCE
    assert measured.speed_between.min() > 0.0  # the weld point never runs backwards
    np.testing.assert_allclose(measured.speed_between, SPEED, rtol=0.1)


@pytest.mark.parametrize("tilt", [None, TILT], ids=["no_windows", "windows"])
@pytest.mark.parametrize("placement", [
    *FAST, *(pytest.param(name, marks=pytest.mark.slow) for name in PLACEMENTS
             if name not in FAST)])
def test_a_whole_girth_seam_is_flat_without_a_seed(tmp_path, placement, tilt):
    """The D500's turn spans 400 degrees: a whole girth seam stays flat only from the
    flat configuration at one end of it (tilt -90 degrees, turn -180); the first sample's
    other flat configurations (tilt +90 degrees, turn 0) run onto the limit halfway."""
    urdf, solution = solved(tmp_path, placement, tilt)
    check_flat_all_along(urdf, solution, tilt)
    tilt_joint = solution.joint_names.index("d500_joint_1")
    assert abs(solution.positions[0, tilt_joint] + math.pi / 2) <= 1e-3


@pytest.mark.slow
def test_samples_past_the_turn_s_range_are_not_reached(tmp_path):
    """A seam 1.15 times round (414 degrees) outruns the D500's 400-degree turn: where the
    turn stands on its limit the face leaves up, and those samples are not reached (a
    whole turn back the turn is free, and flat); every other sample is reached and flat."""
    times = seam_keyframes(1.15)[0]
    urdf, solution = solved(tmp_path, "left_side", None, 1.15, times=times)
    measured = measure(urdf, solution.joint_names, solution.seconds, solution.positions)
    np.testing.assert_allclose(solution.flat_error, measured.face, atol=1e-6)
    off_flat = measured.face > FLAT_TOLERANCE
    assert 0 < np.count_nonzero(off_flat) <= 40  # 14 degrees of seam, one sample each
    assert not solution.reached[off_flat].any()
    assert solution.reached[~off_flat].all()
    turn = solution.positions[off_flat, solution.joint_names.index("d500_joint_2")]
    np.testing.assert_allclose(turn, 3.4906, atol=1e-4)  # on its limit; -2.79 is free
