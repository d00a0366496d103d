"""The MA2010 and MOTOPOS D500 cell of tests/data (ROS-Industrial's Yaskawa parts) with its
positioner placed elsewhere, a whole girth seam on a pipe standing on the positioner's
faceplate, and the checks of a solved motion by Pinocchio called directly on the placed URDF
and by plain numpy, never by pinframes' kinematics."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

DATA = Path(__file__).resolve().parent / "data"
CELL = DATA / "ma2010_cell"
PACKAGES = DATA / "motoman"

RADIUS = 0.1  # m: the pipe, standing on the faceplate (its axis the faceplate's z)
HEIGHT = 0.1  # m: the seam above the faceplate
SPEED = 0.008  # m/s along the seam
COUNT = 361  # keyframes: one per degree of the whole turn, both ends included
DURATION = 2.0 * math.pi * RADIUS / SPEED  # s: 78.5
FLAT_TOLERANCE = math.radians(0.5)  # solve_joints' default flat_tolerance
TILT = (0.1745, 0.1745)  # rad: process windows, 10 degrees about the seam's x and y
TOLERANCE = 1e-6  # m and rad: solve_joints' default tolerances
PATH_TOLERANCE = 1e-4  # m: solve_joints' default path_tolerance

SHIPPED = '<origin xyz="1.7 0 0" rpy="0 0 3.14159265" />'
"""The D500's base in the cell's world as cell.urdf ships it: 1.7 m before the arm, facing it."""

PLACEMENTS = {  # the D500's base in the world: position (m), turn about z (rad)
    "shipped": ((1.7, 0.0, 0.0), math.pi),
    "near": ((1.4, 0.0, 0.0), math.pi),
    "aside_turned": ((1.5, 0.6, 0.0), math.pi + 0.6),
    "left_side": ((0.0, 1.5, 0.0), -math.pi / 2),
    "raised_diagonal": ((1.2, -0.9, 0.2), 2.4),
    "sunk_turned": ((1.3, 0.5, -0.2), math.pi - 0.3),
}


def placed_cell(folder: Path, position: tuple[float, float, float], yaw: float) -> Path:
    """cell.urdf with the D500's base at ``position`` turned ``yaw`` about z, in ``folder``."""
    text = (CELL / "cell.urdf").read_text()
    assert text.count(SHIPPED) == 1
    x, y, z = position
    path = folder / "cell.urdf"
    path.write_text(text.replace(SHIPPED, f'<origin xyz="{x!r} {y!r} {z!r}" '
                                          f'rpy="0 0 {yaw!r}" />'))
    return path


def around(seconds: np.ndarray) -> np.ndarray:
    """The seam point's angle about the pipe's axis (rad) at ``seconds``."""
    return 2.0 * math.pi * np.asarray(seconds, dtype=float) / DURATION


def seam_keyframes(turns: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The seam in the workpiece (the faceplate), ``turns`` times round the pipe (one
    keyframe per degree): times (s), origins (T, 3) and axes (T, 3, 3): x along the travel, y
    the pipe's axis, z out of the pipe (the weld's face)."""
    count = round((COUNT - 1) * turns) + 1
    times = np.linspace(0.0, DURATION * turns, count)
    angle = around(times)
    zeros = np.zeros(count)
    outward = np.stack([np.cos(angle), np.sin(angle), zeros], 1)
    travel = np.stack([-np.sin(angle), np.cos(angle), zeros], 1)
    axis = np.stack([zeros, zeros, zeros + 1.0], 1)
    origins = RADIUS * outward + HEIGHT * axis
    return times, origins, np.stack([travel, axis, outward], axis=2)


@dataclass(frozen=True)
class Measured:
    """A solved motion measured on the placed URDF: at the solution's samples, the face's
    angle from up (rad), the torch tip's distance from the seam point (m) and its z's tilt
    in the seam's axes about x and y (rad); on a grid between the samples (the joints
    linear from one sample to the next), the face's angle from up, the tip's distance from
    the seam's circle (m) and the weld point's speed along the seam (m/s: the tip's way
    round the pipe)."""

    face: np.ndarray
    off_seam: np.ndarray
    tilt: np.ndarray
    face_between: np.ndarray
    off_circle_between: np.ndarray
    speed_between: np.ndarray


def measure(urdf: Path, joint_names: tuple[str, ...] | list[str], seconds: np.ndarray,
            positions: np.ndarray, between: int = 4) -> Measured:
    """:class:`Measured` of ``positions`` (T, n; columns ``joint_names``) at ``seconds``,
    with ``between`` - 1 grid points between consecutive samples, by Pinocchio's forward
    kinematics on ``urdf``."""
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    columns = [list(joint_names).index(model.names[index]) for index in range(1, model.njoints)]
    plate, tip = model.getFrameId("workpiece"), model.getFrameId("torch_tip")

    def placements(rows: np.ndarray) -> tuple[list[pin.SE3], list[pin.SE3]]:
        plates, tips = [], []
        for row in rows:
            pin.framesForwardKinematics(model, data, row[columns])
            plates.append(data.oMf[plate].copy())
            tips.append(data.oMf[tip].copy())
        return plates, tips

    angle = around(seconds)
    outward = np.stack([np.cos(angle), np.sin(angle), np.zeros_like(angle)], 1)
    plates, tips = placements(positions)
    faces = np.array([placement.rotation @ normal for placement, normal in
                      zip(plates, outward, strict=True)])
    face = np.arccos(np.clip(faces[:, 2], -1.0, 1.0))
    points = RADIUS * outward + [0.0, 0.0, HEIGHT]
    off_seam = np.array([np.linalg.norm(placement.actInv(torch.translation) - point)
                         for placement, torch, point in zip(plates, tips, points, strict=True)])
    tilt = []
    for placement, torch, normal in zip(plates, tips, outward, strict=True):
        travel = np.array([-normal[1], normal[0], 0.0])
        seam = np.stack([travel, [0.0, 0.0, 1.0], normal], 1)  # in the workpiece
        x, y, z = seam.T @ placement.rotation.T @ torch.rotation[:, 2]
        tilt.append((math.atan2(-y, z), math.asin(max(-1.0, min(1.0, x)))))
    fraction = np.arange(between) / between
    grid = np.concatenate([seconds[:-1, None] + fraction * np.diff(seconds)[:, None],
                           seconds[-1:, None]], axis=None)
    rows = np.stack([np.interp(grid, seconds, column) for column in positions.T], axis=1)
    plates, tips = placements(rows)
    in_plate = np.array([placement.actInv(torch.translation)
                         for placement, torch in zip(plates, tips, strict=True)])
    way_round = np.unwrap(np.arctan2(in_plate[:, 1], in_plate[:, 0]))
    off_circle = np.hypot(np.hypot(in_plate[:, 0], in_plate[:, 1]) - RADIUS,
                          in_plate[:, 2] - HEIGHT)
    angle = around(grid)
    normals = np.stack([np.cos(angle), np.sin(angle), np.zeros_like(angle)], 1)
    faces = np.array([placement.rotation @ normal for placement, normal in
                      zip(plates, normals, strict=True)])
    return Measured(face, off_seam, np.array(tilt),
                    np.arccos(np.clip(faces[:, 2], -1.0, 1.0)), off_circle,
                    RADIUS * np.diff(way_round) / np.diff(grid))
