"""Robots and paths for the inverse-kinematics tests, and their checks by Pinocchio called
directly on the URDF (``pin.buildModelFromUrdf`` + ``framesForwardKinematics``), never by
pinframes' own kinematics."""

from __future__ import annotations

import textwrap
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from pinframes import FrameTree, Pose

DATA = Path(__file__).resolve().parent / "data"
TOLERANCE = 1e-6  # m and rad: solve_joints' default tolerances


def example_robot(name: str) -> Path:
    """A URDF file of example-robot-data, by file name (skips when it is not installed)."""
    for file in metadata.files("example-robot-data") or []:
        if file.name == name:
            return Path(str(file.locate()))
    pytest.skip("example-robot-data is not installed")


@dataclass(frozen=True)
class Arm:
    """A robot of the tests: its URDF, tool frame, solved joints (the first ``solved`` of
    Pinocchio's configuration), a configuration inside its limits and how far each joint
    swings about it."""

    name: str
    urdf: Path
    tool: str
    solved: int
    home: tuple[float, ...]
    swing: tuple[float, ...]

    def model(self) -> pin.Model:
        return pin.buildModelFromUrdf(str(self.urdf))

    def tree(self) -> FrameTree:
        tree = FrameTree("floor")
        tree.attach_urdf(self.urdf, "floor")
        return tree


def arm(name: str) -> Arm:
    """UR5 and Panda of example-robot-data; xArm7 (UFACTORY's description) and Motoman
    SIA10D (ROS-Industrial's) from tests/data."""
    if name == "UR5":
        return Arm(name, example_robot("ur5_robot.urdf"), "tool0", 6,
                   (0.0, -1.2, 1.5, -1.8, -1.571, 0.0), (0.8, 0.3, 0.4, 0.4, 0.4, 0.8))
    if name == "Panda":
        return Arm(name, example_robot("panda.urdf"), "panda_hand", 7,
                   (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, 0.02, 0.02),
                   (0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6, 0.0, 0.0))
    if name == "xArm7":
        return Arm(name, DATA / "xarm7" / "xarm7.urdf", "link_eef", 7,
                   (0.0, -0.3, 0.0, 1.0, 0.0, 1.3, 0.0), (0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6))
    assert name == "SIA10D"
    return Arm(name, DATA / "motoman_sia10d" / "sia10d.urdf", "link_t", 7,
               (0.0, 0.5, 0.0, -1.0, 0.0, 0.8, 0.0), (0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6))


def swinging(home: np.ndarray, swing: np.ndarray, times: np.ndarray) -> np.ndarray:
    """A smooth joint trajectory (T, n): each joint swings about ``home`` at its own
    frequency (0.6 to 1.3 rad/s)."""
    joint = np.arange(home.shape[0])[None, :]
    return home + swing * np.sin(0.6 * times[:, None] * (1 + 0.2 * joint) + joint)


def frame_poses(model: pin.Model, frame: str, configurations: np.ndarray) -> list[pin.SE3]:
    """Placements of ``frame`` in the model's root, by Pinocchio."""
    data = model.createData()
    frame_id = model.getFrameId(frame)
    poses = []
    for q in configurations:
        pin.framesForwardKinematics(model, data, q)
        poses.append(data.oMf[frame_id].copy())
    return poses


def as_pose(placements: list[pin.SE3], times: np.ndarray) -> Pose:
    return Pose(np.array([p.translation for p in placements]),
                np.array([p.rotation for p in placements]), times=times)


def errors(placements: list[pin.SE3], targets: list[pin.SE3]) -> tuple[np.ndarray, np.ndarray]:
    """Position (m) and orientation (rad) errors of ``placements`` in ``targets``."""
    offsets = [target.actInv(placement) for placement, target in zip(placements, targets,
                                                                       strict=True)]
    return (np.array([np.linalg.norm(o.translation) for o in offsets]),
            np.array([np.linalg.norm(pin.log3(o.rotation)) for o in offsets]))


def on_target(model: pin.Model, frame: str, configurations: np.ndarray,
              targets: list[pin.SE3]) -> np.ndarray:
    """Per sample, whether Pinocchio puts ``frame`` within the tolerances of its target."""
    position, orientation = errors(frame_poses(model, frame, configurations), targets)
    return (position <= TOLERANCE) & (orientation <= TOLERANCE)


def within_limits(model: pin.Model, positions: np.ndarray) -> bool:
    """Whether the solved joints (the first columns of Pinocchio's ``q``) keep their URDF
    limits."""
    count = positions.shape[1]
    return bool(np.all(positions >= model.lowerPositionLimit[:count])
                and np.all(positions <= model.upperPositionLimit[:count]))


def largest_step(positions: np.ndarray) -> float:
    """The largest change of the joints between two samples (Euclidean norm, rad or m)."""
    return float(np.linalg.norm(np.diff(positions, axis=0), axis=1).max())


def serial_urdf(name: str, joints: list[tuple[str, str, str, str, float, float]],
                tool: tuple[str, str] | None = None) -> str:
    """A URDF text of a serial chain from link ``base``: per joint ``(name, type, child
    link, "x y z" origin, lower, upper)``, axes z except a name ending ``_x`` (x); ``tool``:
    a fixed ``(link, "x y z" origin)`` on the last link."""
    parts = [f'<?xml version="1.0"?>\n<robot name="{name}">\n  <link name="base"/>']
    parent = "base"
    for joint, kind, child, origin, lower, upper in joints:
        axis = "1 0 0" if joint.endswith("_x") else "0 0 1"
        parts.append(
            f'  <link name="{child}"/>\n  <joint name="{joint}" type="{kind}">\n'
            f'    <parent link="{parent}"/><child link="{child}"/>\n'
            f'    <origin xyz="{origin}"/><axis xyz="{axis}"/>\n'
            f'    <limit lower="{lower:g}" upper="{upper:g}" velocity="1" effort="1"/>\n'
            '  </joint>')
        parent = child
    if tool is not None:
        parts.append(f'  <link name="{tool[0]}"/>\n  <joint name="{tool[0]}_joint" type="fixed">\n'
                     f'    <parent link="{parent}"/><child link="{tool[0]}"/>'
                     f'<origin xyz="{tool[1]}"/>\n  </joint>')
    return "\n".join([*parts, "</robot>", ""])


POSITIONER = serial_urdf("positioner", [("turn", "revolute", "faceplate", "0 0 0.4", -3.0, 3.0)])
"""A one-axis positioner: its faceplate 0.4 m above its base, turning about z."""


TILT_TURN = serial_urdf("positioner", [
    ("tilt_x", "revolute", "cradle", "0 0 0.3", -2.0, 2.0),
    ("turn", "revolute", "faceplate", "0 0 0", -6.0, 6.0)])
"""A two-axis positioner: tilt about x 0.3 m above its base, then turn about z."""

GIRTH_RADIUS = 0.1  # m, the pipe of girth_seam
GIRTH_HEIGHT = 0.05  # m, the seam's height on the faceplate


def girth_seam(count: int) -> tuple[np.ndarray, np.ndarray]:
    """Half a turn along the pipe's girth on the faceplate: origins (T, 3) and axes (T, 3, 3),
    x along the travel, z out of the pipe (the weld's face)."""
    around = np.linspace(0.0, np.pi, count)
    zeros = np.zeros(count)
    origins = np.stack([GIRTH_RADIUS * np.cos(around), GIRTH_RADIUS * np.sin(around),
                        zeros + GIRTH_HEIGHT], 1)
    outward = np.stack([np.cos(around), np.sin(around), zeros], 1)
    travel = np.stack([-np.sin(around), np.cos(around), zeros], 1)
    return origins, np.stack([travel, np.cross(outward, travel), outward], axis=2)


def faceplates(urdf: Path, base: pin.SE3, positioner: np.ndarray) -> list[pin.SE3]:
    """The frame ``faceplate`` of the positioner ``urdf`` mounted at ``base``, per row of
    its joint values ``positioner``, by Pinocchio."""
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    frame = model.getFrameId("faceplate")
    placements = []
    for q in positioner:
        pin.framesForwardKinematics(model, data, q)
        placements.append(base * data.oMf[frame])
    return placements


def pipe_scene(positioner: Path, trajectories: tuple[str, str] | None = None) -> str:
    """A scene: the UR5 (prefix ur/) and the positioner ``positioner`` (prefix pos/, its
    base at x 0.55 m) with a seam on its faceplate whose face turns a quarter turn about the
    faceplate's y over 1 s, the torch target 0.1 m above it; each robot's ``trajectory``
    the file named in ``trajectories``."""
    sine, cosine = float(np.sin(np.pi / 8)), float(np.cos(np.pi / 8))
    ur_motion, pos_motion = ("", "") if trajectories is None else (
        f", trajectory: {trajectories[0]}", f", trajectory: {trajectories[1]}")
    return textwrap.dedent(f"""\
        pinframes_scene: 1
        name: pipe
        frames:
          - {{name: positioner_base, parent: world, xyz: [0.55, 0, 0]}}
          - name: seam
            parent: pos/faceplate
            xyz: [0, 0, 0.05]
            keyframes:
              - {{time: 0, quaternion: [0.5, 0.5, 0.5, 0.5]}}
              - {{time: 1, quaternion: [0, {sine!r}, 0, {cosine!r}]}}
          - {{name: torch_target, parent: seam, xyz: [0, 0, 0.1], quaternion: [1, 0, 0, 0]}}
        robots:
          - {{name: ur5, urdf: {example_robot("ur5_robot.urdf")}, parent: world,
              prefix: ur/{ur_motion}}}
          - {{name: positioner, urdf: {positioner}, parent: positioner_base,
              prefix: pos/{pos_motion}}}
        """)
