"""``solve_joints(tilt=...)``: process windows, the tool's z within tilt windows about the
target's x and y; checked with Pinocchio called directly on the URDF and plain numpy."""

from __future__ import annotations

import warnings

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import TOLERANCE, example_robot
from pinframes import FrameTree, Pose
from pinframes.errors import ArgumentTypeError, InvalidDataError, JointWithoutSamplesWarning

ARM = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint"]
"""Four of the UR5's joints (its wrists held at 0): five rows for a free-spin torch are one
too many, unless a window frees a tilt."""
TILTS = np.array([0.1, 0.2, -0.25, 0.05, 0.15])  # rad about the target's x, per sample


@pytest.fixture(scope="module")
def ur5() -> tuple[pin.Model, FrameTree]:
    urdf = example_robot("ur5_robot.urdf")
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    return pin.buildModelFromUrdf(str(urdf)), tree


def configurations(times: np.ndarray) -> np.ndarray:
    """UR5 configurations (T, 6) along a short motion, the two last wrist joints at 0."""
    return np.array([[0.2 + 0.1 * t, -1.2 + 0.1 * t, 1.5 - 0.2 * t, -1.8, 0.0, 0.0]
                     for t in times])


def tool0(model: pin.Model, q: np.ndarray) -> pin.SE3:
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[model.getFrameId("tool0")].copy()


def tilted_targets(model: pin.Model, times: np.ndarray) -> list[pin.SE3]:
    """Targets whose z the tool's reaches only tilted by TILTS about the target's x: the
    tool's pose at the configurations, turned back by those angles."""
    return [tool0(model, q) * pin.SE3(pin.utils.rotate("x", -tilt), np.zeros(3))
            for q, tilt in zip(configurations(times), TILTS, strict=True)]


def as_pose(targets: list[pin.SE3], times: np.ndarray) -> Pose:
    return Pose(np.array([t.translation for t in targets]),
                np.array([t.rotation for t in targets]), times=times)


def hand_tilts(model: pin.Model, positions: np.ndarray, targets: list[pin.SE3]
               ) -> tuple[np.ndarray, np.ndarray]:
    """Per sample, the tilt (a, b) of the tool's z in its target (z = Rx(a) Ry(b) e_z, so
    z = (sin b, -sin a cos b, cos a cos b)) and the distance of the origins, by Pinocchio."""
    tilts, distances = [], []
    for solved, target in zip(positions, targets, strict=True):
        q = np.zeros(model.nq)
        q[:len(ARM)] = solved
        in_target = target.actInv(tool0(model, q))
        x, y, z = in_target.rotation[:, 2]
        tilts.append([np.arctan2(-y, z), np.arcsin(x)])
        distances.append(np.linalg.norm(in_target.translation))
    return np.array(tilts), np.array(distances)


def solve(tree: FrameTree, target: Pose, **options):
    """The four joints solved from near the first configuration (the wrists held at 0, as
    the warning says)."""
    seed = dict(zip(ARM, configurations(np.zeros(1))[0] + 0.05, strict=False))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        return tree.solve_joints("tool0", target, joints=ARM, seed=seed, free_axis="z",
                                 **options)


def test_a_target_reachable_only_inside_its_window_is_reached_and_its_tilt_reported(ur5):
    model, tree = ur5
    times = np.linspace(0.0, 1.0, TILTS.shape[0])
    targets = tilted_targets(model, times)
    exact = solve(tree, as_pose(targets, times))
    windowed = solve(tree, as_pose(targets, times), tilt=(0.3, 0.0))
    assert not exact.reached.any()  # without the window: out of reach
    assert exact.tilt is None
    assert windowed.all_reached
    tilts, distances = hand_tilts(model, windowed.positions, targets)
    assert np.all(distances <= TOLERANCE)
    assert np.all(np.abs(tilts[:, 0]) <= 0.3 + TOLERANCE)
    assert np.all(np.abs(tilts[:, 1]) <= TOLERANCE)
    np.testing.assert_allclose(windowed.tilt, tilts, atol=1e-9)
    # these four joints reach each target's position with one tilt only: the one built in
    np.testing.assert_allclose(tilts[:, 0], TILTS, atol=1e-6)


def test_a_tilt_past_its_window_is_not_reached(ur5):
    model, tree = ur5
    times = np.linspace(0.0, 1.0, TILTS.shape[0])
    targets = tilted_targets(model, times)
    solution = solve(tree, as_pose(targets, times), tilt=(0.12, 0.0))
    inside = np.abs(TILTS) <= 0.12
    np.testing.assert_array_equal(solution.reached, inside)
    # the orientation error is how far the tilt lies past the windows, by hand
    tilts, distances = hand_tilts(model, solution.positions, targets)
    excess = np.hypot(np.maximum(np.abs(tilts[:, 0]) - 0.12, 0.0), np.abs(tilts[:, 1]))
    np.testing.assert_allclose(solution.orientation_error, excess, atol=1e-9)
    np.testing.assert_allclose(solution.position_error, distances, atol=1e-9)
    assert np.all(np.hypot(excess, distances)[~inside] > TOLERANCE)


def test_windows_keep_the_nominal_orientation_where_it_is_reachable(ur5):
    """Six joints on a target along a line, reachable without tilt all along: with windows
    of 0.2 rad the solution is the one without (no tilt), not one in a corner of its
    windows (as the smallest motion alone gave: 0.2 rad about y for the whole path)."""
    model, tree = ur5
    times = np.linspace(0.0, 2.0, 41)
    start = tool0(model, np.array([0.2, -1.2, 1.5, -1.8, -1.571, 0.0]))
    turns = [pin.SE3(pin.utils.rotate("x", 0.3 * t), np.array([0.0, 0.1 * t, 0.0])) for t in times]
    targets = [start * turn for turn in turns]
    exact = tree.solve_joints("tool0", as_pose(targets, times), free_axis="z")
    windowed = tree.solve_joints("tool0", as_pose(targets, times), free_axis="z",
                                 tilt=(0.2, 0.2), seed=exact.positions[0])
    assert exact.all_reached and windowed.all_reached
    np.testing.assert_allclose(windowed.tilt, 0.0, atol=1e-6)
    np.testing.assert_allclose(windowed.positions, exact.positions, atol=1e-6)


def test_windows_are_used_only_where_the_nominal_is_out_of_reach(ur5):
    """Four joints: the samples whose target the tool reaches untilted keep no tilt (by
    Pinocchio), the others tilt within the window as far as they need; all reached."""
    model, tree = ur5
    times = np.linspace(0.0, 1.0, 9)
    tilts = np.array([0.0, 0.0, 0.0, 0.1, 0.2, 0.15, 0.0, 0.0, 0.0])
    targets = [tool0(model, q) * pin.SE3(pin.utils.rotate("x", -tilt), np.zeros(3))
               for q, tilt in zip(configurations(times), tilts, strict=True)]
    solution = solve(tree, as_pose(targets, times), tilt=(0.3, 0.0))
    assert solution.all_reached
    measured, distances = hand_tilts(model, solution.positions, targets)
    assert distances.max() <= TOLERANCE
    nominal = tilts == 0.0
    np.testing.assert_allclose(measured[nominal], 0.0, atol=1e-6)
    assert np.all(np.abs(measured[~nominal, 0]) > 0.05)
    assert np.all(np.abs(measured[:, 0]) <= 0.3 + TOLERANCE)
    np.testing.assert_allclose(solution.tilt, measured, atol=1e-6)


@pytest.mark.parametrize(("tilt", "free_axis", "error"), [
    ((0.1,), None, ArgumentTypeError), ("ab", None, ArgumentTypeError),
    ((0.1, -0.1), None, InvalidDataError), ((0.1, 2.0), None, InvalidDataError),
    ((0.1, 0.1), "x", ArgumentTypeError)])
def test_bad_windows_are_errors(ur5, tilt, free_axis, error):
    _, tree = ur5
    with pytest.raises(error):
        tree.solve_joints("tool0", Pose([0.4, 0.1, 0.4]), tilt=tilt, free_axis=free_axis)


def test_without_a_free_axis_the_spin_is_the_target_s(ur5):
    """Six joints, windows of 0.2 rad, no free axis: the tool's orientation in its target
    is Rx(a) Ry(b) with no turn about z (by hand from Pinocchio's pose)."""
    model, tree = ur5
    times = np.linspace(0.0, 1.0, 11)
    start = tool0(model, np.array([0.2, -1.2, 1.5, -1.8, -1.571, 0.0]))
    targets = [start * pin.SE3(pin.utils.rotate("y", 0.4 * t) @ pin.utils.rotate("z", 0.3 * t),
                               np.array([0.0, 0.05 * t, 0.0])) for t in times]
    solution = tree.solve_joints("tool0", as_pose(targets, times), tilt=(0.2, 0.2))
    assert solution.all_reached
    for q, target, tilt in zip(solution.positions, targets, solution.tilt, strict=True):
        rotation = target.actInv(tool0(model, q)).rotation
        a, b = tilt
        np.testing.assert_allclose(rotation, pin.utils.rotate("x", a) @ pin.utils.rotate("y", b),
                                   atol=1e-6)
        assert abs(a) <= 0.2 + TOLERANCE and abs(b) <= 0.2 + TOLERANCE


def test_the_window_error_of_hand_built_orientations():
    """Orientations built as Rx(a) Ry(b) Rz(c): the measured tilt and excess, one at a time
    (the solver's) and many at once (the batch check's), are those of a, b and c."""
    from pinframes.kinematics.ik._tool_error import WindowMatch, tilts_of

    rng = np.random.default_rng(7)
    angles = rng.uniform([-0.6, -0.6, -0.5], [0.6, 0.6, 0.5], size=(50, 3))
    rotations = np.array([pin.utils.rotate("x", a) @ pin.utils.rotate("y", b)
                          @ pin.utils.rotate("z", c) for a, b, c in angles])
    offsets = rng.normal(size=(50, 3))
    np.testing.assert_allclose(tilts_of(rotations), angles[:, :2], atol=1e-12)
    for free_spin in (False, True):
        match = WindowMatch(0.2, 0.1, free_spin=free_spin)
        excess = np.hypot(np.maximum(np.abs(angles[:, 0]) - 0.2, 0.0),
                          np.maximum(np.abs(angles[:, 1]) - 0.1, 0.0))
        if not free_spin:
            excess = np.hypot(excess, angles[:, 2])
        one_by_one = [match.measure(pin.SE3(rotation, offset))[:2]
                      for rotation, offset in zip(rotations, offsets, strict=True)]
        np.testing.assert_allclose(np.array(one_by_one),
                                   np.stack([np.linalg.norm(offsets, axis=1), excess], 1),
                                   atol=1e-12)
        np.testing.assert_allclose(np.stack(match.errors(rotations, offsets), 1),
                                   np.array(one_by_one), atol=1e-12)
