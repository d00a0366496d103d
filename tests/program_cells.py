"""A small cell for the program tests: the bundled six-axis welding robot at the origin with
a tool 0.2 m out along its flange's z, and the same robot as Pinocchio reads it, to check
the tool's poses independently."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin

import pinframes
from ik_paths import frame_poses
from robot_checks import urdf_velocity_limits

ROBOT_URDF = Path(__file__).parents[1] / "models" / "welding_robot" / "welding_robot.urdf"
TOOL_OFFSET = pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.2]))
"""The tool in the flange, metres."""
ACCELERATION = 6.0
"""Every joint's acceleration limit in these tests, rad/s^2."""
START = np.array([0.0, 0.3, -0.3, 0.0, 0.8, 0.0])
"""A configuration the programs start from, rad (the tool in front of the robot)."""


def cell() -> pinframes.FrameTree:
    """The robot on ``world`` (joints ``robot/joint_1`` .. ``robot/joint_6``), tool ``tcp``."""
    tree = pinframes.FrameTree("world")
    tree.attach_urdf(ROBOT_URDF, parent="world", prefix="robot/")
    tree.add("tcp", "robot/flange", pinframes.Pose(TOOL_OFFSET.translation))
    return tree


def limits(tree: pinframes.FrameTree, acceleration: float = ACCELERATION) -> dict:
    """Acceleration limits for every joint (URDF names, as a MoveIt file gives them)."""
    return {name.removeprefix("robot/"): {"acceleration": acceleration} for name in tree.joints}


def tool_placements(positions: np.ndarray) -> list[pin.SE3]:
    """The tool in the world at each row of ``positions`` (T, 6), by Pinocchio alone."""
    model = pin.buildModelFromUrdf(str(ROBOT_URDF))
    return [flange * TOOL_OFFSET for flange in frame_poses(model, "flange",
                                                           np.atleast_2d(positions))]


def tool_origins(positions: np.ndarray) -> np.ndarray:
    """The tool's origin (T, 3) in the world at each row of ``positions``."""
    return np.array([placement.translation for placement in tool_placements(positions)])


def limit_shares(positions: np.ndarray, step: float) -> tuple[float, float]:
    """The largest share of its limit that a joint's velocity and acceleration take, from
    finite differences of ``positions`` (T, 6) sampled every ``step`` seconds: the URDF's
    velocity limits (read by yourdfpy) and :data:`ACCELERATION`."""
    velocity = np.diff(positions, axis=0) / step
    acceleration = np.diff(positions, n=2, axis=0) / step**2
    urdf = urdf_velocity_limits(ROBOT_URDF)
    limit = np.array([urdf[f"joint_{i}"] for i in range(1, 7)])
    return float((np.abs(velocity) / limit).max()), float(np.abs(acceleration).max()
                                                          / ACCELERATION)


def with_midpoints(positions: np.ndarray) -> np.ndarray:
    """``positions`` and the joint values halfway between each two samples (as the tree
    interpolates them)."""
    middles = (positions[:-1] + positions[1:]) / 2
    return np.concatenate([positions, middles])


def distance_to_segment(points: np.ndarray, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Each point's distance (m) to the segment from ``start`` to ``end``."""
    direction = end - start
    along = np.clip((points - start) @ direction / (direction @ direction), 0.0, 1.0)
    return np.linalg.norm(points - (start + along[:, None] * direction), axis=1)
