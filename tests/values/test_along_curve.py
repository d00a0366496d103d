"""Pose.along_curve: seam frames from a polyline, against hand-derived axes and times."""

import numpy as np
import pytest

from pinframes import InvalidPoseError, Pose, read_scene
from pinframes.errors import FileFormatError


def parabola_direction(points, at=0):
    """Unit direction at ``points[at]`` of the parabola through three points, parametrised
    by the length along their chords: numpy's quadratic fit, differentiated there."""
    points = np.asarray(points, dtype=float)
    lengths = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0),
                                                              axis=1))])
    fits = [np.polyfit(lengths, points[:, axis], 2) for axis in range(3)]
    slope = np.array([2 * fit[0] * lengths[at] + fit[1] for fit in fits])
    return slope / np.linalg.norm(slope)


def across(normal, x):
    """The unit part of ``normal`` perpendicular to the unit ``x``."""
    z = np.asarray(normal, dtype=float) - np.dot(normal, x) * x
    return z / np.linalg.norm(z)


def test_axes_and_times_of_a_bent_line_by_hand():
    # (0,0,0) -> (3,4,0) -> (3,4,12): segment lengths 5 and 12, at 2 m/s 2.5 s and 6 s
    points = [[0, 0, 0], [3, 4, 0], [3, 4, 12]]
    pose = Pose.along_curve(points, [[0, 0, 1], [0, 0, 1], [1, 0, 0]], speed=2.0)
    np.testing.assert_allclose(pose.seconds, [0.0, 2.5, 8.5], atol=1e-12)
    np.testing.assert_allclose(pose.translation, points, atol=0)
    # x everywhere the parabola through the three points, by hand: inside 12 d1 + 5 d2 for
    # the unit chords d1 = (3, 4, 0) / 5 and d2 = (0, 0, 1), that is (36, 48, 25) / 65 (not
    # the neighbours' chord (3, 4, 12) / 13); (66, 88, -25) at the start and (-36, -48, 145)
    # at the end
    first_x = np.array([66.0, 88.0, -25.0]) / np.sqrt(66**2 + 88**2 + 25**2)
    middle_x = np.array([36.0, 48.0, 25.0]) / 65
    np.testing.assert_allclose(middle_x, parabola_direction(points, at=1), atol=1e-12)
    last_x = np.array([-36.0, -48.0, 145.0]) / np.sqrt(36**2 + 48**2 + 145**2)
    np.testing.assert_allclose(first_x, parabola_direction(points), atol=1e-12)
    np.testing.assert_allclose(-last_x, parabola_direction(points[::-1]), atol=1e-12)
    np.testing.assert_allclose(pose.rotation[:, :, 0], [first_x, middle_x, last_x], atol=1e-15)
    # z: the normal without its part along x; y = z x x
    middle_z = np.array([-3.0, -4.0, 12.0]) / 13  # (0,0,1) - (25/65) x, made unit
    np.testing.assert_allclose(pose.rotation[1, :, 2], middle_z, atol=1e-15)
    for index, (x, normal) in enumerate([(first_x, [0, 0, 1]), (last_x, [1, 0, 0])]):
        z = across(normal, x)
        np.testing.assert_allclose(pose.rotation[-index, :, 2], z, atol=1e-15)
        np.testing.assert_allclose(pose.rotation[-index, :, 1], np.cross(z, x), atol=1e-15)
    np.testing.assert_allclose(pose.rotation[1, :, 1], np.cross(middle_z, middle_x),
                               atol=1e-15)


def test_two_points_travel_along_their_chord():
    pose = Pose.along_curve([[1, 1, 0], [1, 3, 0]], [0, 0, 1], speed=0.5)
    np.testing.assert_allclose(pose.seconds, [0.0, 4.0])
    np.testing.assert_allclose(pose.rotation, [[[0, -1, 0], [1, 0, 0], [0, 0, 1]]] * 2,
                               atol=0)


def test_the_last_normal_is_refused_along_the_travel_direction():
    # equal steps: the last direction is (3 p3 - 4 p2 + p1) / 2 = (-1, 0, 3) / 2, and a
    # normal along it is refused there, and only there
    points = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 0, 1]]
    with pytest.raises(InvalidPoseError) as caught:
        Pose.along_curve(points, [[0, 0, 1]] * 3 + [[-1, 0, 3]], speed=1.0)
    assert caught.value.field == "normals[3]"
    assert "parallel" in str(caught.value)


def test_a_circle_gets_its_tangent_and_outward_normal_between_points():
    """Inside a uniformly sampled circle the central difference is the exact tangent, and
    between points the axes turn by SLERP: the tangent of the time's angle. At the ends the
    parabola through three points misses the tangent by step**3 / 4 radians."""
    radius, count = 0.5, 13
    angles = np.linspace(0.0, np.pi, count)
    outward = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(count)])
    points = radius * outward
    pose = Pose.along_curve(points, outward, times=np.linspace(0.0, 6.0, count))
    tangent = np.column_stack([-np.sin(angles), np.cos(angles), np.zeros(count)])
    np.testing.assert_allclose(pose.rotation[1:-1, :, 0], tangent[1:-1], atol=1e-15)
    np.testing.assert_allclose(pose.rotation[1:-1, :, 2], outward[1:-1], atol=1e-15)
    np.testing.assert_allclose(pose.rotation[1:-1, :, 1], [[0, 0, 1]] * (count - 2),
                               atol=1e-15)  # y = outward x tangent = +z
    # at the ends, equal chords: 4 p1 - 3 p0 - p2 (and the same from the other end)
    step = np.pi / (count - 1)
    for index, (p0, p1, p2), sign in ((0, points[:3], 1.0), (-1, points[::-1][:3], -1.0)):
        direction = sign * (4 * p1 - 3 * p0 - p2)
        np.testing.assert_allclose(pose.rotation[index, :, 0],
                                   direction / np.linalg.norm(direction), atol=1e-15)
        miss = np.arccos(np.clip(pose.rotation[index, :, 0] @ tangent[index], -1, 1))
        assert step**3 / 4 * 0.95 < miss < step**3 / 4 * 1.05
    between = pose.at([1.25])  # halfway between points 2 and 3 (0.5 s apart)
    middle = 2.5 * step
    np.testing.assert_allclose(between.rotation[0, :, 0], [-np.sin(middle), np.cos(middle), 0],
                               atol=1e-12)
    chord_middle = radius * (outward[2] + outward[3]) / 2
    np.testing.assert_allclose(between.translation[0], chord_middle, atol=1e-15)


def test_times_may_be_absolute_and_points_and_speed_pint_quantities():
    points = [[0, 0, 0], [1, 0, 0], [1, 1, 0]]
    pose = Pose.along_curve(points, [0, 0, 1], times=["2024-03-01T08:00:00",
                                                      "2024-03-01T08:00:01",
                                                      "2024-03-01T08:00:03"])
    assert pose.reference_time == np.datetime64("2024-03-01T08:00:00", "ns")
    np.testing.assert_allclose(pose.seconds, [0.0, 1.0, 3.0])
    units = pytest.importorskip("pint").UnitRegistry()
    in_mm = Pose.along_curve(np.array(points) * 1000 * units.mm, [0, 0, 1], speed=0.5)
    np.testing.assert_allclose(in_mm.translation, points, atol=1e-15)
    np.testing.assert_allclose(in_mm.seconds, [0.0, 2.0, 4.0])
    by_the_minute = Pose.along_curve(points, [0, 0, 1], speed=units.Quantity(1.2, "m/min"))
    np.testing.assert_allclose(by_the_minute.seconds, [0.0, 50.0, 100.0])
    with pytest.raises(InvalidPoseError) as caught:
        Pose.along_curve(points, [0, 0, 1], speed=units.Quantity(1.2, "m"))
    assert caught.value.field == "speed" and "a speed" in caught.value.message


@pytest.mark.parametrize(
    ("points", "normals", "timing", "field", "words"),
    [
        ([[0, 0, 0]], [0, 0, 1], {"speed": 1.0}, "points", "at least 2 points"),
        ([[0, 0, 0], [1, 0, 0], [1, 0, 0], [2, 0, 0]], [0, 0, 1], {"speed": 1.0}, "points[2]",
         "repeats point 1"),
        ([[0, 0, 0], [1, 0, 0], [0, 0, 0]], [0, 0, 1], {"speed": 1.0}, "points[1]",
         "turns back"),
        ([[0, 0, 0], [1, 0, 0]], [[0, 0, 1], [2, 0, 0]], {"speed": 1.0}, "normals[1]",
         "parallel"),
        ([[0, 0, 0], [1, 0, 0]], [[0, 0, 1], [0, 0, 0]], {"speed": 1.0}, "normals[1]", "zero"),
        ([[0, 0, 0], [1, 0, 0]], [[0, 0, 1]] * 3, {"speed": 1.0}, "normals", "one per point"),
        ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [0, 0, 1], {"times": [0, 1, 1]}, "times[2]",
         "point 2 is not after point 1"),
        ([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [0, 0, 1], {"times": [0, 1]}, "times",
         "2 times for 3 points"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {}, "speed", "either speed"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {"speed": 1.0, "times": [0, 1]}, "speed",
         "either speed"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {"speed": 0.0}, "speed", "positive"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {"speed": float("nan")}, "speed", "positive"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {"speed": True}, "speed", "positive"),
        ([[0, 0, 0], [1, 0, 0]], [0, 0, 1], {"speed": "1"}, "speed", "positive"),
        ([[0, 0, 0], [np.nan, 0, 0]], [0, 0, 1], {"speed": 1.0}, "points", "finite"),
        ([[0, 0, 0], [1e308, 0, 0], [-1e308, 1, 0]], [0, 0, 1], {"times": [0, 1, 2]},
         "points[2]", "overflows"),
        ([0, 0, 0], [0, 0, 1], {"speed": 1.0}, "points", "(N, 3)"),
    ],
)
def test_bad_curves_are_refused_naming_the_point(points, normals, timing, field, words):
    with pytest.raises(InvalidPoseError) as caught:
        Pose.along_curve(points, normals, **timing)
    assert caught.value.field == field
    assert words in caught.value.message


def test_a_normal_nearly_along_the_travel_direction_is_refused():
    """Within a microradian of the travel direction the normal gives no z axis; at ten
    microradians it does, and z is the normal's part across the curve."""
    tilt = 1e-5
    pose = Pose.along_curve([[0, 0, 0], [1, 0, 0]], [1, tilt, 0], speed=1.0)
    np.testing.assert_allclose(pose.rotation[0, :, 2], [0, 1, 0], atol=1e-12)
    with pytest.raises(InvalidPoseError, match="parallel"):
        Pose.along_curve([[0, 0, 0], [1, 0, 0]], [1, 1e-7, 0], speed=1.0)


def test_a_helix_sampled_unevenly_gets_its_tangent():
    """A helix of radius 0.1 m rising 0.02 m per radian, sampled at 0, 1, 16 and 31 degrees:
    at the 1-degree point the chord of the neighbours is 6.9 degrees off the tangent, the
    three-point non-uniform difference within 0.01 degrees (the tangent by hand:
    (-r sin t, r cos t, c))."""
    radius, rise = 0.1, 0.02
    angles = np.radians([0.0, 1.0, 16.0, 31.0])
    points = np.column_stack([radius * np.cos(angles), radius * np.sin(angles),
                              rise * angles])
    normals = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(4)])
    pose = Pose.along_curve(points, normals, speed=0.01)
    tangent = np.array([-radius * np.sin(angles[1]), radius * np.cos(angles[1]), rise])
    tangent /= np.linalg.norm(tangent)
    chord = (points[2] - points[0]) / np.linalg.norm(points[2] - points[0])
    assert np.degrees(np.arccos(chord @ tangent)) > 6.8
    assert np.degrees(np.arccos(np.clip(pose.rotation[1, :, 0] @ tangent, -1, 1))) < 0.01
    np.testing.assert_allclose(pose.rotation[1, :, 0], parabola_direction(points[:3], at=1),
                               atol=1e-12)


def test_points_1e_170_m_apart_keep_their_directions():
    """Chords (1, 0, 0) then (1, 1, 0), times 1e-170 m: lengths 1 and sqrt 2, so inside
    sqrt(2) (1, 0, 0) + (1, 1, 0) / sqrt(2), that is (3, 1, 0) / sqrt(10), by hand."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 1.0, 0.0]]) * 1e-170
    pose = Pose.along_curve(points, [0, 0, 1], times=[0.0, 1.0, 2.0])
    np.testing.assert_allclose(pose.rotation[1, :, 0], np.array([3.0, 1.0, 0.0]) / np.sqrt(10),
                               atol=1e-15)
    assert np.all(np.isfinite(pose.rotation))
    with pytest.raises(InvalidPoseError) as caught:  # at a speed, no time between them
        Pose.along_curve(points, [0, 0, 1], speed=0.01)
    assert caught.value.field == "times[1]"


@pytest.mark.parametrize("lengths", [(1.0, 1.0), (1.0, 0.5), (0.2, 3.0)])
def test_a_turn_within_a_hundredth_of_a_degree_of_straight_back_is_refused(lengths):
    """179.99994 degrees is refused like 180; 179.98 degrees is a (sharp) turn."""
    def turned_by(degrees):
        back = np.radians(180.0 - degrees)
        return [[0, 0, 0], [lengths[0], 0, 0],
                [lengths[0] - lengths[1] * np.cos(back), lengths[1] * np.sin(back), 0]]
    for degrees in (180.0, 179.99994, 179.995):
        with pytest.raises(InvalidPoseError) as caught:
            Pose.along_curve(turned_by(degrees), [0, 0, 1], speed=1.0)
        assert caught.value.field == "points[1]" and "turns back" in caught.value.message
    sharp = Pose.along_curve(turned_by(179.98), [0, 0, 1], speed=1.0)
    np.testing.assert_allclose(sharp.rotation[1, :, 0],
                               parabola_direction(turned_by(179.98), at=1), atol=1e-9)


@pytest.mark.parametrize(("angle", "count"), [(4 * np.pi, 3), (-2 * np.pi, 2),
                                              (6 * np.pi, 4), (7.0, 3)])
def test_a_scene_arc_stepping_by_half_a_turn_or_more_is_refused_naming_the_arc(
        tmp_path, angle, count):
    """Whole turns from point to point would give a seam standing still."""
    path = tmp_path / "arc.yaml"
    path.write_text("pinframes_scene: 1\nframes:\n- name: c\n  parent: world\n  curve:\n"
                    f"    arc: {{centre: [0, 0, 0], axis: [0, 0, 1], start: [0.1, 0, 0], "
                    f"angle: {angle!r}, count: {count}}}\n    speed: 0.01\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(path)
    assert caught.value.field == "frames[0].curve.arc" and caught.value.frame == "c"
    assert "half a turn or more" in caught.value.message
