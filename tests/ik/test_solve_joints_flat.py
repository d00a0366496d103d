"""``solve_joints(flat=...)``: a tilt-turn positioner keeps a pipe's girth seam flat (PA)
while a UR5 holds its torch on it; checked by Pinocchio called directly on the two URDFs and
by plain numpy, never by pinframes' kinematics."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import TILT_TURN, TOLERANCE, example_robot, faceplates, girth_seam
from pinframes import FrameTree, Pose
from pinframes.errors import (
    ArgumentTypeError,
    InvalidDataError,
    JointError,
    JointWithoutSamplesWarning,
)

BASE = np.array([0.55, 0.0, 0.0])  # the positioner's base in the floor


def rotation_x(angle: float) -> np.ndarray:
    cosine, sine = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, cosine, -sine], [0.0, sine, cosine]])


@pytest.fixture(scope="module")
def cell(tmp_path_factory: pytest.TempPathFactory) -> tuple[FrameTree, Path, np.ndarray]:
    """A UR5 at the floor's origin, the positioner before it, a pipe seam on its faceplate
    and the torch target on the seam (z into the weld)."""
    urdf = tmp_path_factory.mktemp("positioner") / "positioner.urdf"
    urdf.write_text(TILT_TURN)
    times = np.linspace(0.0, 9.0, 91)
    tree = FrameTree("floor")
    add_cell(tree, urdf, times)
    return tree, urdf, times


def add_cell(tree: FrameTree, urdf: Path, times: np.ndarray) -> None:
    """The UR5, the positioner of ``urdf``, the seam and the torch target under ``floor``."""
    tree.attach_urdf(example_robot("ur5_robot.urdf"), "floor")
    tree.add("positioner_base", "floor", Pose(BASE))
    tree.attach_urdf(urdf, "positioner_base", prefix="positioner/")
    tree.add("seam", "positioner/faceplate", Pose(*girth_seam(times.shape[0]), times=times))
    tree.add("torch_target", "seam", Pose([0.0, 0.0, 0.0], rotation_x(np.pi)))


def solved_joints(tree: FrameTree) -> list[str]:
    robot = [name for name in tree.joints if not name.startswith("positioner/")]
    return [*robot, "positioner/tilt_x", "positioner/turn"]


def faceplate_in_floor(urdf: Path, positioner: np.ndarray) -> list[pin.SE3]:
    """The faceplate in the floor per sample, by Pinocchio on the positioner's URDF."""
    return faceplates(urdf, pin.SE3(np.eye(3), BASE), positioner)


def face_angles(urdf: Path, positioner: np.ndarray) -> np.ndarray:
    """Degrees between the seam's z and the floor's +z per sample."""
    _, axes = girth_seam(positioner.shape[0])
    faces = np.array([plate.rotation.dot(seam[:, 2]) for plate, seam in
                      zip(faceplate_in_floor(urdf, positioner), axes, strict=True)])
    return np.degrees(np.arccos(np.clip(faces[:, 2], -1.0, 1.0)))


def test_a_girth_seam_is_kept_flat_over_half_a_turn_with_the_torch_on_it(cell):
    tree, urdf, times = cell
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z", flat="seam")
    positions = solution.positions
    assert solution.all_reached
    np.testing.assert_allclose(solution.seconds, times)
    assert np.all(face_angles(urdf, positions[:, 6:]) <= 2.0)
    # the torch on its target, by Pinocchio on the UR5's URDF and the hand-built seam
    robot = pin.buildModelFromUrdf(str(example_robot("ur5_robot.urdf")))
    data = robot.createData()
    tool = robot.getFrameId("tool0")
    origins, axes = girth_seam(times.shape[0])
    plates = faceplate_in_floor(urdf, positions[:, 6:])
    for q, plate, origin, seam in zip(positions[:, :6], plates, origins, axes, strict=True):
        pin.framesForwardKinematics(robot, data, q)
        torch = data.oMf[tool]
        assert np.linalg.norm(torch.translation - plate.act(origin)) <= TOLERANCE
        into_the_weld = -plate.rotation.dot(seam[:, 2])
        assert np.degrees(np.arccos(min(1.0, torch.rotation[:, 2].dot(into_the_weld)))) <= 1e-4
    # the positioner did the turning: its turn covers the half turn of the seam
    assert abs(abs(positions[-1, 7] - positions[0, 7]) - np.pi) < 0.05
    # and the welders' view of the solved motion agrees: flat at every sample
    driven = tree.copy()
    driven.set_joint_trajectory(solution.seconds, positions, joint_names=solution.joint_names)
    assert set(driven.weld_process("tool0", "seam").position) == {"PA"}


def test_without_flat_the_same_solve_lets_the_seam_turn_away_from_up(cell):
    """What the flat test above rules out happens without flat=: it can fail."""
    tree, urdf, _ = cell
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z")
    assert solution.all_reached
    assert face_angles(urdf, solution.positions[:, 6:]).max() > 20.0


def test_up_may_point_elsewhere(cell):
    tree, urdf, _ = cell
    up = np.array([0.0, -1.0, 1.0]) / np.sqrt(2.0)
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z", flat="seam", up=up * 3.0)
    assert solution.all_reached
    _, axes = girth_seam(len(solution))
    plates = faceplate_in_floor(urdf, solution.positions[:, 6:])
    faces = np.array([plate.rotation.dot(seam[:, 2]) for plate, seam in
                      zip(plates, axes, strict=True)])
    assert np.degrees(np.arccos(np.clip(faces.dot(up), -1.0, 1.0))).max() <= 2.0


def test_a_flat_frame_no_solved_joint_turns_is_an_error(cell):
    tree, _, _ = cell
    with pytest.raises(JointError) as raised, pytest.warns(JointWithoutSamplesWarning):
        tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree)[:6],
                          free_axis="z", flat="seam")
    assert raised.value.field == "flat"


@pytest.mark.parametrize("up", [[0.0, 0.0, 0.0], [1.0, 2.0], [np.nan, 0.0, 1.0]])
def test_a_bad_up_is_an_error(cell, up):
    tree, _, _ = cell
    with pytest.raises(InvalidDataError) as raised:
        tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                          free_axis="z", flat="seam", up=up)
    assert raised.value.field == "up"


def test_up_is_in_the_root_s_axes_when_the_cell_is_mounted_turned(cell):
    """The same cell under a mount turned 90 degrees about x in the root: the root's +z is
    the cell floor's +y, and the seam's face turns there (checked in the root's axes)."""
    _, urdf, times = cell
    tree = FrameTree("site")
    tree.add("floor", "site", Pose([0.0, 0.0, 1.0], rotation_x(np.pi / 2)))
    add_cell(tree, urdf, times)
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z", flat="seam")
    assert solution.all_reached
    _, axes = girth_seam(len(solution))
    plates = faceplate_in_floor(urdf, solution.positions[:, 6:])
    faces = np.array([rotation_x(np.pi / 2) @ plate.rotation @ seam[:, 2]
                      for plate, seam in zip(plates, axes, strict=True)])
    assert np.degrees(np.arccos(np.clip(faces[:, 2], -1.0, 1.0))).max() <= 2.0


def test_flat_and_windows_together(cell):
    """flat= with tilt=: the face kept up and the torch within its windows."""
    tree, urdf, _ = cell
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z", flat="seam", tilt=(0.2, 0.1))
    assert solution.all_reached
    assert solution.tilt is not None
    assert np.all(np.abs(solution.tilt) <= [0.2 + TOLERANCE, 0.1 + TOLERANCE])
    assert face_angles(urdf, solution.positions[:, 6:]).max() <= 2.0


def test_a_tilt_limit_leaves_the_face_as_near_up_as_it_allows(tmp_path):
    """A tilt axis limited to +-0.5 rad can bring a face that looks sideways on the upright
    pipe only 0.5 rad up: by hand, the best is 90 degrees less 0.5 rad from up, with the
    tilt on its limit; the torch stays on target."""
    urdf = tmp_path / "positioner.urdf"
    urdf.write_text(TILT_TURN.replace('lower="-2" upper="2"', 'lower="-0.5" upper="0.5"'))
    tree = FrameTree("floor")
    add_cell(tree, urdf, np.linspace(0.0, 9.0, 31))
    solution = tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree),
                                 free_axis="z", flat="seam")
    assert solution.all_reached
    np.testing.assert_allclose(np.abs(solution.positions[:, 6]), 0.5, atol=1e-3)
    np.testing.assert_allclose(face_angles(urdf, solution.positions[:, 6:]),
                               90.0 - np.degrees(0.5), atol=0.5)


def test_up_without_flat_is_an_error(cell):
    tree, _, _ = cell
    with pytest.raises(ArgumentTypeError) as raised:
        tree.solve_joints("tool0", "torch_target", joints=solved_joints(tree), up=[0, 0, 1])
    assert raised.value.field == "up"
