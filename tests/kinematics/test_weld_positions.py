"""Welding positions (ISO 6947 PA .. PG) of seams built by hand, from weld_process.

A seam whose axes are rot_y(-slope) @ rot_x(rotation) in the world has its travel direction
``slope`` above the horizontal and its face turned by ``rotation`` from up about it: with
up = +z, u in seam axes is (sin slope, cos slope sin rotation, cos slope cos rotation).
"""

import numpy as np
import pytest

from pinframes import FrameTree, Pose

from geometry import rot_x, rot_y

# (slope, rotation) in degrees and the position the table of docs/welding-process.md gives
SEAMS = [
    ((0, 0), "PA"), ((10, -20), "PA"), ((-44, 22), "PA"),
    ((0, 45), "PB"), ((20, -60), "PB"), ((0, 23), "PB"),
    ((0, 90), "PC"), ((-30, -100), "PC"), ((0, 68), "PC"),
    ((0, 135), "PD"), ((5, -150), "PD"), ((0, 113), "PD"),
    ((0, 180), "PE"), ((30, -170), "PE"), ((-40, 158), "PE"),
    ((60, 0), "PF"), ((45, 180), "PF"), ((89, 90), "PF"),
    ((-60, 0), "PG"), ((-45, -90), "PG"), ((-89, 180), "PG"),
]


def seam_tree(slope: float, rotation: float) -> FrameTree:
    tree = FrameTree("world")
    tree.add("part", "world", Pose([0.5, 0.2, 0.8]))
    tree.add("seam", "part", Pose([0.1, 0.0, 0.0], rot_y(-slope) @ rot_x(rotation)))
    tree.add("torch", "seam", Pose([0.0, 0.0, 0.01], rot_x(np.pi)))
    return tree


@pytest.mark.parametrize(("angles", "position"), SEAMS)
def test_hand_built_seams_in_every_position(angles, position):
    slope, rotation = np.radians(angles)
    process = seam_tree(slope, rotation).weld_process("torch", "seam")
    np.testing.assert_allclose(process.slope, [slope], atol=1e-14)
    if abs(angles[0]) < 89:  # near vertical the face's rotation is not well conditioned
        turned = np.angle(np.exp(1j * (process.rotation - rotation)))
        np.testing.assert_allclose(turned, 0.0, atol=1e-13)
    assert process.position.tolist() == [position]


def test_every_position_appears_once_in_the_table():
    assert sorted({position for _, position in SEAMS}) == ["PA", "PB", "PC", "PD", "PE",
                                                           "PF", "PG"]


def test_slope_near_vertical_keeps_its_digits():
    """1e-12 rad short of straight up: asin(u_x) would give pi/2 exactly."""
    slope = np.pi / 2 - 1e-12
    process = seam_tree(slope, 0.3).weld_process("torch", "seam")
    assert np.pi / 2 - process.slope[0] == pytest.approx(1e-12, rel=1e-3)
    assert process.position.tolist() == ["PF"]
    straight_up = seam_tree(np.pi / 2, 0.0).weld_process("torch", "seam")
    assert straight_up.slope[0] == pytest.approx(np.pi / 2, abs=1e-15)
    assert np.isnan(straight_up.rotation[0])  # no face rotation about a vertical seam
    assert straight_up.position.tolist() == ["PF"]


def test_up_is_any_direction_of_the_root():
    """The same flat seam seen with gravity along -y of the world, and upside down."""
    tree = seam_tree(0.0, 0.0)
    sideways = tree.weld_process("torch", "seam", up=[0.0, 2.0, 0.0])
    # u = +y of the world = +y of the seam: rotation +90 degrees, horizontal (PC)
    np.testing.assert_allclose(sideways.rotation, [np.pi / 2], atol=1e-15)
    assert sideways.position.tolist() == ["PC"]
    overhead = tree.weld_process("torch", "seam", up=[0.0, 0.0, -1.0])
    np.testing.assert_allclose(np.abs(overhead.rotation), [np.pi], atol=1e-15)
    assert overhead.position.tolist() == ["PE"]
    uphill = tree.weld_process("torch", "seam", up=[1.0, 0.0, 1.0])
    np.testing.assert_allclose(uphill.slope, [np.pi / 4], atol=1e-15)


def test_positions_change_as_a_positioner_turns_the_seam():
    """A flat seam on a turntable tilted about x by 0 .. pi in 4 s: 45 degrees per second."""
    tree = FrameTree("world")
    tree.add("tilt", "world", Pose(rotation=[rot_x(0.0), rot_x(np.pi / 2), rot_x(np.pi)],
                                   times=[0.0, 2.0, 4.0]))
    tree.add("seam", "tilt", Pose([0.0, 0.0, 0.1]))
    tree.add("torch", "world", Pose([0.0, 0.0, 0.2], rot_x(np.pi)))
    times = [0.0, 0.4, 0.6, 1.2, 1.6, 2.2, 2.6, 3.2, 3.6, 4.0]
    process = tree.weld_process("torch", "seam", workpiece="tilt", times=times)
    # the seam's axes are rot_x(45 t): u = rot_x(45 t)^T e_z = (0, sin, cos), rotation 45 t
    np.testing.assert_allclose(process.rotation[:-1], np.radians(45) * np.array(times[:-1]),
                               atol=1e-12)
    assert process.position.tolist() == ["PA", "PA", "PB", "PB", "PC", "PC", "PD", "PD",
                                         "PE", "PE"]


def test_without_times_a_turning_workpiece_samples_the_positions():
    """The torch rides a seam fixed on a part that a positioner tilts: nothing moves on the
    workpiece, but the seam's position does (PA, then PC at 90 degrees)."""
    tree = FrameTree("world")
    tree.add("part", "world", Pose(rotation=[rot_x(0.0), rot_x(np.pi / 2)], times=[0.0, 5.0]))
    tree.add("seam", "part", Pose([0.0, 0.0, 0.1]))
    tree.add("torch", "seam", Pose([0.0, 0.0, 0.01], rot_x(np.pi)))
    process = tree.weld_process("torch", "seam")
    np.testing.assert_allclose(process.seconds, [0.0, 5.0])
    assert process.position.tolist() == ["PA", "PC"]
    np.testing.assert_allclose(process.travel_speed, 0.0, atol=1e-15)
