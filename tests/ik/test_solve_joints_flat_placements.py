"""Flat that is flat: a tilt/turn positioner of our own beside a UR5 (example-robot-data) in
five placements, a girth seam on its faceplate, ``flat=`` without a seed; with and without
process windows. The face's angle from up and the torch on the seam are checked with
Pinocchio on the two URDFs and the seam by plain numpy, never by pinframes' kinematics."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import TILT_TURN, TOLERANCE, example_robot, faceplates, girth_seam
from pinframes import FrameTree, Pose

TIMES = np.linspace(0.0, 9.0, 91)  # s: half a turn of the girth
PLACEMENTS = [  # the positioner's base in the floor: position (m), turn about z (rad)
    ((0.55, 0.0, 0.0), 0.0), ((0.0, 0.55, 0.0), np.pi / 2), ((0.45, 0.3, 0.0), 0.6),
    ((0.4, -0.4, 0.0), -0.8), ((-0.5, 0.2, 0.0), 2.8)]


def rotation(axis: str, angle: float) -> np.ndarray:
    return pin.utils.rotate(axis, angle)


@pytest.fixture(scope="module")
def positioner(tmp_path_factory: pytest.TempPathFactory) -> Path:
    urdf = tmp_path_factory.mktemp("tilt_turn") / "positioner.urdf"
    urdf.write_text(TILT_TURN)
    return urdf


def cell(urdf: Path, base: pin.SE3) -> FrameTree:
    tree = FrameTree("floor")
    tree.attach_urdf(example_robot("ur5_robot.urdf"), "floor")
    tree.add("positioner_base", "floor", Pose(base.translation, base.rotation))
    tree.attach_urdf(urdf, "positioner_base", prefix="positioner/")
    tree.add("seam", "positioner/faceplate", Pose(*girth_seam(TIMES.shape[0]), times=TIMES))
    tree.add("torch_target", "seam", Pose([0.0, 0.0, 0.0], rotation("x", np.pi)))
    return tree


@pytest.mark.parametrize(("position", "yaw"), PLACEMENTS)
@pytest.mark.parametrize("tilt", [None, (0.1745, 0.1745)])
def test_flat_without_a_seed_is_flat_in_every_placement(positioner, position, yaw, tilt):
    base = pin.SE3(rotation("z", yaw), np.asarray(position, dtype=float))
    tree = cell(positioner, base)
    joints = [*(name for name in tree.joints if not name.startswith("positioner/")),
              "positioner/tilt_x", "positioner/turn"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints have no samples
        solution = tree.solve_joints("tool0", "torch_target", joints=joints, free_axis="z",
                                     flat="seam", tilt=tilt)
    assert solution.all_reached and solution.flat_error is not None
    np.testing.assert_allclose(solution.seconds, TIMES)
    origins, axes = girth_seam(len(solution))
    plates = faceplates(positioner, base, solution.positions[:, 6:])
    faces = np.array([plate.rotation @ seam[:, 2] for plate, seam in
                      zip(plates, axes, strict=True)])
    angles = np.arccos(np.clip(faces[:, 2], -1.0, 1.0))
    np.testing.assert_allclose(solution.flat_error, angles, atol=1e-7)  # arccos near 0
    assert angles.max() <= np.radians(0.5) + 1e-6  # PA all along, no longer PB
    robot = pin.buildModelFromUrdf(str(example_robot("ur5_robot.urdf")))
    data = robot.createData()
    tool = robot.getFrameId("tool0")
    along = []
    for q, plate, origin in zip(solution.positions[:, :6], plates, origins, strict=True):
        pin.framesForwardKinematics(robot, data, q)
        torch = data.oMf[tool]
        assert np.linalg.norm(torch.translation - plate.act(origin)) <= TOLERANCE
        in_plate = plate.actInv(torch.translation)
        along.append(np.arctan2(in_plate[1], in_plate[0]))  # the weld point's way round
    # the weld point never runs backwards along the seam
    assert np.all(np.diff(np.unwrap(along)) > 0.0)
