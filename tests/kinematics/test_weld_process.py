"""FrameTree.weld_process against torches and seams built by hand (SPEC section 9).

Every expected number comes from plain numpy here: rotations written out, the torch axis
from the angles, velocities differentiated by hand.
"""

from pathlib import Path

import numpy as np
import pytest
import yaml

from pinframes import FrameTree, Pose, read_scene
from pinframes.errors import FrameNotFoundError, InvalidDataError, TreeStructureError

from geometry import rot_x, rot_y, rot_z

MODELS = Path(__file__).resolve().parents[2] / "models"


def torch_rotation(travel: float, work: float, spin: float = 0.0) -> np.ndarray:
    """Torch axes in seam axes whose wire axis has the given travel and work angles (rad):
    a = (sin travel, -cos travel cos work, -cos travel sin work); x, y turned by ``spin``
    about it."""
    wire = np.array([np.sin(travel), -np.cos(travel) * np.cos(work),
                     -np.cos(travel) * np.sin(work)])
    helper = np.array([0.0, 0.0, 1.0]) if abs(wire[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    x = helper - helper @ wire * wire
    x /= np.linalg.norm(x)
    y = np.cross(wire, x)
    x, y = np.cos(spin) * x + np.sin(spin) * y, -np.sin(spin) * x + np.cos(spin) * y
    return np.column_stack([x, y, wire])


@pytest.fixture
def bench():
    """A seam on a workpiece turned in the world, nothing moving."""
    tree = FrameTree("world")
    tree.add("workpiece", "world", Pose([0.4, -0.2, 0.9], rot_z(0.6) @ rot_x(0.2)))
    tree.add("seam", "workpiece", Pose([0.1, 0.05, 0.02], rot_z(-1.1)))
    return tree


@pytest.mark.parametrize(
    ("travel_deg", "work_deg"),
    [(10, 90), (-15, 90), (5, 45), (0, 135), (-30, 60), (80, 20)],
)
@pytest.mark.parametrize("spin", [0.0, 1.3, -2.9])
def test_angles_and_offset_of_torches_built_from_known_angles(bench, travel_deg, work_deg,
                                                              spin):
    travel, work = np.radians(travel_deg), np.radians(work_deg)
    offset = np.array([0.002, -0.0015, 0.012])
    bench.add("torch", "seam", Pose(offset, torch_rotation(travel, work, spin)))
    process = bench.weld_process("torch", "seam")
    assert len(process) == 1 and process.times is None and process.seconds is None
    np.testing.assert_allclose(process.travel_angle, [travel], atol=1e-12)
    np.testing.assert_allclose(process.work_angle, [work], atol=1e-12)
    np.testing.assert_allclose(process.offset, [offset], atol=1e-15)
    np.testing.assert_array_equal(process.travel_speed, [0.0])
    assert process.ctwd is None
    assert (process.torch, process.seam, process.workpiece) == ("torch", "seam", "workpiece")


def test_turning_the_torch_about_its_wire_changes_nothing(bench):
    """Two torches on one moving carrier, one of them spinning about its z axis, each with a
    contact tip 15 mm back up the wire: the same process at every time."""
    tree = bench
    carrier = Pose([[0.0, 0.0, 0.01], [0.08, 0.01, 0.012]], torch_rotation(0.2, 1.4),
                   times=[0.0, 4.0])
    tree.add("carrier", "seam", carrier)
    tree.add("plain", "carrier", Pose())
    tree.add("spinning", "carrier", Pose(rotation=[rot_z(0.0), rot_z(3.0)], times=[0.0, 4.0]))
    for torch in ("plain", "spinning"):
        tree.add(f"{torch}_tip", torch, Pose([0.0, 0.0, -0.015]))
    times = np.linspace(0.0, 4.0, 9)
    plain = tree.weld_process("plain", "seam", times=times, contact_tip="plain_tip")
    spinning = tree.weld_process("spinning", "seam", times=times, contact_tip="spinning_tip")
    for name in ("travel_speed", "travel_angle", "work_angle", "offset", "ctwd"):
        np.testing.assert_allclose(getattr(spinning, name), getattr(plain, name), atol=1e-14,
                                   err_msg=name)
    # the weld point (where the wire meets the seam's plane) moves 0.08 m with the torch
    # and, as the torch rises by 2 mm, slides ahead by 0.002 a_x / -a_z, in 4 s
    wire = torch_rotation(0.2, 1.4)[:, 2]
    np.testing.assert_allclose(plain.travel_speed, (0.08 + 0.002 * wire[0] / -wire[2]) / 4,
                               atol=1e-15)
    np.testing.assert_allclose(plain.travel_angle, 0.2, atol=1e-12)
    np.testing.assert_allclose(plain.work_angle, 1.4, atol=1e-12)


def test_contact_tip_to_work_distance_by_hand(bench):
    """Tip h above the surface, contact tip d back up the wire: the wire meets the plane
    after h / cos(travel) / sin(work), the contact tip is d further back."""
    travel, work, height, back = np.radians(12), np.radians(70), 0.004, 0.015
    bench.add("torch", "seam", Pose([0.001, 0.002, height], torch_rotation(travel, work, 0.4)))
    bench.add("tip", "torch", Pose([0.0, 0.0, -back]))
    bench.add("off_axis_tip", "torch", Pose([0.003, -0.002, -back]))  # not on the wire
    process = bench.weld_process("torch", "seam", contact_tip="tip")
    np.testing.assert_allclose(process.ctwd,
                               [height / (np.cos(travel) * np.sin(work)) + back], atol=1e-15)
    assert process.contact_tip == "tip"
    off_axis = bench.weld_process("torch", "seam", contact_tip="off_axis_tip")
    wire = torch_rotation(travel, work, 0.4)
    tip_in_seam = np.array([0.001, 0.002, height]) + wire @ [0.003, -0.002, -back]
    np.testing.assert_allclose(off_axis.ctwd, [tip_in_seam[2] / -wire[2, 2]], atol=1e-15)
    bench.add("upside_down", "seam", Pose([0, 0, 0.01], rot_x(0.3)))  # the wire points up
    bench.add("upside_down_tip", "upside_down", Pose([0.0, 0.0, -back]))
    away = bench.weld_process("upside_down", "seam", contact_tip="upside_down_tip")
    assert np.isnan(away.ctwd).all()


def test_seam_on_a_tilted_moving_table():
    """The table slides and turns about its own tilted z axis; the torch slides through the
    world with a fixed orientation. The speed is that of the weld point w = q + s A (where
    the wire meets the seam's plane, through o with normal n) relative to the table,
    differentiated by hand: s = n.(o - q) / n.A, and d/dt R^T (w - p) = R^T (dw/dt - dp/dt -
    omega x (w - p))."""
    tilt = rot_x(0.3)
    table_start, table_end = np.array([1.0, 0.0, 0.5]), np.array([1.5, 0.3, 0.6])
    torch_start, torch_end = np.array([1.2, 0.1, 0.7]), np.array([1.4, 0.5, 0.75])
    torch_axes = rot_z(0.4) @ rot_x(np.pi - 0.25)
    seam_axes, seam_origin = rot_z(0.7), np.array([0.2, -0.1, 0.05])
    tree = FrameTree("world")
    tree.add("table", "world", Pose([table_start, table_end], [tilt, tilt @ rot_z(0.5)],
                                    times=[0.0, 10.0]))
    tree.add("seam", "table", Pose(seam_origin, seam_axes))
    tree.add("torch", "world", Pose([torch_start, torch_end], torch_axes, times=[0.0, 10.0]))
    times = np.array([1.0, 2.5, 4.0, 7.5, 9.0])
    process = tree.weld_process("torch", "seam", times=times)
    np.testing.assert_allclose(process.seconds, times)
    omega = tilt @ [0.0, 0.0, 0.05]  # rad/s in the world
    for index, time in enumerate(times):
        table_axes = tilt @ rot_z(0.05 * time)
        table_at = table_start + (table_end - table_start) * time / 10
        torch_at = torch_start + (torch_end - torch_start) * time / 10
        seam_in_world = table_axes @ seam_axes
        wire = seam_in_world.T @ torch_axes[:, 2]
        assert process.travel_angle[index] == pytest.approx(np.arcsin(wire[0]), abs=1e-12)
        assert process.work_angle[index] == pytest.approx(np.arctan2(-wire[2], -wire[1]),
                                                          abs=1e-12)
        np.testing.assert_allclose(
            process.offset[index],
            seam_in_world.T @ (torch_at - table_at - table_axes @ seam_origin), atol=1e-12)
        table_rate, torch_rate = (table_end - table_start) / 10, (torch_end - torch_start) / 10
        wire_world, normal = torch_axes[:, 2], seam_in_world[:, 2]
        seam_at = table_at + table_axes @ seam_origin
        reach = normal @ (seam_at - torch_at) / (normal @ wire_world)
        seam_rate = table_rate + np.cross(omega, seam_at - table_at)
        reach_rate = (np.cross(omega, normal) @ (seam_at - torch_at)
                      + normal @ (seam_rate - torch_rate)
                      - reach * np.cross(omega, normal) @ wire_world) / (normal @ wire_world)
        weld_at = torch_at + reach * wire_world
        weld_rate = torch_rate + reach_rate * wire_world
        relative = table_axes.T @ (weld_rate - table_rate - np.cross(omega, weld_at - table_at))
        assert process.travel_speed[index] == pytest.approx(seam_axes[:, 0] @ relative,
                                                            abs=1e-12)
    # relative to the world, a torch on the seam's plane: the torch's own velocity
    tree.add("torch_on_seam", "seam", Pose([0.01, 0.0, 0.0], rot_x(np.pi)))
    on_seam = tree.weld_process("torch_on_seam", "seam", times=times, workpiece="world")
    np.testing.assert_allclose(on_seam.offset[:, 2], 0.0, atol=1e-15)
    seam_x_in_world = np.array([tilt @ rot_z(0.05 * t) @ seam_axes[:, 0] for t in times])
    tip_rates = [table_end / 10 - table_start / 10 + np.cross(
        omega, tilt @ rot_z(0.05 * t) @ (seam_origin + seam_axes @ [0.01, 0.0, 0.0]))
        for t in times]
    np.testing.assert_allclose(on_seam.travel_speed,
                               np.einsum("ti,ti->t", seam_x_in_world, tip_rates), atol=1e-12)


def test_curve_seam_on_a_turning_pipe():
    """A pipe turns about its horizontal axis under a torch fixed in the world; the seam
    point is a curve on the pipe (Pose.along_curve) that brings each point of a girth seam
    under the torch at its time. At the curve's points the seam axes are exact: the design
    angles, the design offset, and the speed omega * r of the pipe surface."""
    radius, omega = 0.1, 0.1  # m, rad/s
    push, work, stand_off = np.radians(10), np.radians(90), 0.003
    angles = np.linspace(0.0, 1.0, 21)  # the pipe turns 1 rad in 10 s
    on_pipe = np.column_stack([np.zeros(21), -radius * np.sin(angles),
                               radius * np.cos(angles)])
    tree = FrameTree("world")
    tree.add("pipe", "world", Pose([0.0, 0.0, 1.0], [rot_x(0.0), rot_x(-1.0)],
                                   times=[0.0, 10.0]))
    tree.add("seam_point", "pipe", Pose.along_curve(on_pipe, on_pipe / radius,
                                                   times=angles / omega))
    # at the top of the pipe the seam axes are x = -y, y = +x, z = +z of the world
    seam_at_top = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    design = torch_rotation(push, work, spin=0.8)
    tree.add("torch", "world", Pose([0.0, 0.0, 1.0 + radius + stand_off],
                                    seam_at_top @ design))
    tree.add("contact_tip", "torch", Pose([0.0, 0.0, -0.015]))
    process = tree.weld_process("torch", "seam_point", contact_tip="contact_tip")
    np.testing.assert_allclose(process.seconds, angles / omega, atol=1e-9)
    inside = slice(1, -1)
    np.testing.assert_allclose(process.travel_angle[inside], push, atol=1e-12)
    np.testing.assert_allclose(process.work_angle[inside], work, atol=1e-12)
    np.testing.assert_allclose(process.offset[inside], [[0.0, 0.0, stand_off]] * 19, atol=1e-12)
    np.testing.assert_allclose(process.ctwd[inside], stand_off / np.cos(push) + 0.015,
                               atol=1e-12)
    # the weld point, stand_off tan(push) ahead on the seam's plane, moves at omega * r
    # relative to the pipe, plus what the plane's dip between points (chords inside the
    # circle: the seam origin sinks at omega r (1 - cos step) / step) moves it along the
    # leaning wire
    step = angles[1] - angles[0]
    dip = omega * radius * (1 - np.cos(step)) / step
    # (the last segment ends at the parabola's axes, turned by step**3 / 4: 6e-9 m/s off)
    expected_speed = omega * radius + dip * np.tan(push)
    np.testing.assert_allclose(process.travel_speed[1:-2], expected_speed, atol=1e-12)
    assert process.travel_speed[-2] == pytest.approx(expected_speed, abs=1e-8)
    # at the two ends the seam's x is the parabola's through the last three points, which
    # misses the tangent by step**3 / 4 (about the pipe axis: the travel angle only)
    miss = np.abs(process.travel_angle[[0, -1]] - push)
    assert np.all((0.95 * step**3 / 4 < miss) & (miss < 1.05 * step**3 / 4))
    np.testing.assert_allclose(process.work_angle[[0, -1]], work, atol=1e-12)


def test_bundled_cell_welds_at_the_design_angles_and_speed():
    """The cell was designed for 10 degrees push, 90 degrees work and 17.2 mm/s
    (cell_design.yaml: the half circle of radius 0.10955 m in 20 s). Its robot motion holds
    the torch on the seam to the solver's accuracy (1e-6 m and rad), and seam_point's axes
    are the circle's to 1e-9 rad."""
    cell = yaml.safe_load((MODELS / "welding_cell" / "cell_design.yaml").read_text())
    seam, torch = cell["seam"], cell["torch"]
    tree = read_scene(MODELS / "welding_cell" / "scene.yaml")
    process = tree.weld_process("torch_tcp", "seam_point", workpiece="workpiece")
    assert len(process) == 2001
    np.testing.assert_allclose(process.seconds, np.linspace(0.0, 20.0, 2001), atol=1e-9)
    design_speed = np.pi * 0.10955 / 20.0  # m/s
    assert design_speed == pytest.approx(seam["travel_speed_m_per_s"], rel=1e-11)
    assert round(design_speed * 1000, 1) == 17.2
    # linear joint interpolation between the samples: within 0.1 % of the design speed
    np.testing.assert_allclose(process.travel_speed, design_speed, rtol=1e-3)
    assert torch["push_angle"] == pytest.approx(np.radians(10), abs=1e-11)
    assert torch["work_angle"] == pytest.approx(np.radians(90), abs=1e-11)
    np.testing.assert_allclose(process.travel_angle, np.radians(10), atol=1e-6)
    np.testing.assert_allclose(process.work_angle, np.radians(90), atol=1e-6)
    np.testing.assert_allclose(process.offset, 0.0, atol=1e-6)


def test_times_follow_pose_and_reference_times_carry_over():
    tree = FrameTree("world", reference_time="2024-03-01T08:00:00")
    tree.add("seam", "world", Pose.along_curve([[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0]], [0, 0, 1],
                                               speed=0.01))
    tree.add("torch", "world", Pose([[0, 0, 0.01], [0.2, 0, 0.01]], rot_x(np.pi),
                                    times=[0.0, 20.0]))
    process = tree.weld_process("torch", "seam")
    assert process.reference_time == np.datetime64("2024-03-01T08:00:00")
    np.testing.assert_allclose(process.seconds, [0.0, 10.0, 20.0])
    np.testing.assert_allclose(process.travel_speed, 0.01, atol=1e-15)
    stamped = tree.weld_process("torch", "seam", times=["2024-03-01T08:00:05"],
                                time_ref="2024-03-01T08:00:04")
    assert stamped.reference_time == np.datetime64("2024-03-01T08:00:04")
    np.testing.assert_allclose(stamped.seconds, [1.0])
    np.testing.assert_allclose(stamped.offset, [[0.0, 0.0, 0.01]], atol=1e-15)


def test_bad_frames_are_named():
    tree = FrameTree("world")
    tree.add("seam", "world", Pose())
    tree.add("torch", "world", Pose([0, 0, 0.01], rot_x(np.pi)))
    for arguments, missing in [(("torch", "sea"), "sea"), (("torc", "seam"), "torc")]:
        with pytest.raises(FrameNotFoundError) as caught:
            tree.weld_process(*arguments)
        assert caught.value.frame == missing
    for keyword in ("contact_tip", "workpiece"):
        with pytest.raises(FrameNotFoundError) as caught:
            tree.weld_process("torch", "seam", **{keyword: "tip"})
        assert caught.value.frame == "tip"
    with pytest.raises(TreeStructureError) as caught:
        tree.weld_process("torch", "world")
    assert caught.value.field == "workpiece"
    for up in ([0, 0, 0], [1, 2], [0, np.nan, 1]):
        with pytest.raises(InvalidDataError) as caught:
            tree.weld_process("torch", "seam", up=up)
        assert caught.value.field == "up"


def test_travel_speed_is_the_weld_points_on_a_turning_pipe():
    """A pipe of radius r turns at omega under a seam frame held at its top; the tool centre
    point is 15 mm up the wire, which leans 10 degrees ahead. The weld point lies on the
    pipe's tangent plane, stand_off tan(push) ahead of the top: the pipe's surface there
    moves at omega r along the seam (the torch origin: omega (r + stand_off), 14 % more)."""
    radius, omega, stand_off, push = 0.10955, 0.1, 0.015, np.radians(10)
    tree = FrameTree("world")
    tree.add("pipe", "world", Pose([0.0, 0.0, 1.0], [rot_x(0.0), rot_x(-1.0)],
                                   times=[0.0, 10.0]))
    seam_at_top = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    tree.add("seam", "world", Pose([0.0, 0.0, 1.0 + radius], seam_at_top))
    tree.add("torch", "seam", Pose([-stand_off * np.tan(push), 0.0, stand_off],
                                   torch_rotation(push, np.pi / 2)))
    process = tree.weld_process("torch", "seam", workpiece="pipe")
    np.testing.assert_allclose(process.seconds, [0.0, 10.0])
    np.testing.assert_allclose(process.travel_speed, omega * radius, atol=1e-15)
    np.testing.assert_allclose(process.offset[:, 2], stand_off, atol=1e-15)


def test_without_times_every_sample_that_moves_torch_or_seam_on_the_workpiece():
    """The torch rides the seam (nothing moves between them); the workpiece slides under
    both: its keyframes are the samples, and the weld point moves backwards on it."""
    tree = FrameTree("world")
    tree.add("seam", "world", Pose())
    tree.add("torch", "seam", Pose([0, 0, 0.01], rot_x(np.pi)))
    tree.add("table", "world", Pose([[0, 0, 0], [1, 0, 0], [3, 0, 0]], times=[0.0, 1.0, 2.0]))
    moved = tree.weld_process("torch", "seam", workpiece="table")
    np.testing.assert_allclose(moved.seconds, [0.0, 1.0, 2.0])
    np.testing.assert_allclose(moved.travel_speed, [-1.0, -2.0, -2.0])  # seam x = world x
    assert len(tree.weld_process("torch", "seam")) == 1  # nothing moves on the seam's parent


def test_work_angle_of_a_wire_along_the_travel_direction_is_nan(bench):
    bench.add("along", "seam", Pose([0.0, 0.0, 0.01], rot_y(np.pi / 2)))  # z = seam x
    bench.add("nearly", "seam", Pose([0.0, 0.0, 0.01], rot_y(np.pi / 2) @ rot_x(1e-6)))
    assert np.isnan(bench.weld_process("along", "seam").work_angle).all()
    nearly = bench.weld_process("nearly", "seam")
    # z = (cos 1e-6, -sin 1e-6, 0): seen from the work, straight along -y
    np.testing.assert_allclose(nearly.work_angle, [np.arctan2(0.0, np.sin(1e-6))], atol=1e-9)


def test_a_cell_far_from_the_root_keeps_its_micrometres():
    """Torch and seam under a cell 5,000 km from the root (map coordinates), the cell
    turned on its side: the offset is exact, computed in the cell, and the position is that
    of the turned seam (face sideways: PC)."""
    tree = FrameTree("map")
    tree.add("cell", "map", Pose([5.0e5, 5.0e6, 30.0], rot_x(np.pi / 2)))
    tree.add("seam", "cell", Pose.along_curve([[0, 0, 0], [0.1, 0, 0]], [0, 0, 1],
                                              times=[0.0, 10.0]))
    offset = np.array([1e-6, -2e-6, 0.012])
    tree.add("torch", "cell", Pose([[0, 0, 0], [0.1, 0, 0]], rot_x(np.pi),
                                   times=[0.0, 10.0]))
    tree.add("tip", "torch", Pose(offset * [1, -1, -1]))  # the torch's y and z turn over
    process = tree.weld_process("tip", "seam")
    # composed through the map's origin, the cell's 5e6 m left 7.6e-12 m of rounding
    np.testing.assert_allclose(process.offset, [offset] * 2, atol=1e-15)
    assert process.position.tolist() == ["PC", "PC"]
