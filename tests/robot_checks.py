"""Independent checks for solutions on URDF robots: placements by Pinocchio called directly,
velocity limits read with yourdfpy."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import yourdfpy

from ik_paths import frame_poses


def placements(urdf: Path, frame: str, configurations: np.ndarray) -> list[pin.SE3]:
    """Placements of ``frame`` in the root of ``urdf`` (metres), one per row of
    ``configurations`` (Pinocchio's ``q``), by ``framesForwardKinematics``."""
    return frame_poses(pin.buildModelFromUrdf(str(urdf)), frame, np.atleast_2d(configurations))


def urdf_velocity_limits(urdf: Path) -> dict[str, float]:
    """The ``<limit velocity=...>`` of each joint of ``urdf`` that has one, by yourdfpy."""
    robot = yourdfpy.URDF.load(str(urdf), build_scene_graph=False, load_meshes=False,
                               load_collision_meshes=False)
    return {name: joint.limit.velocity for name, joint in robot.joint_map.items()
            if joint.limit is not None and joint.limit.velocity is not None}


def urdf_mimic_multiplier(urdf: Path, joint: str) -> float:
    """The ``<mimic multiplier=...>`` of ``joint`` in ``urdf``, by yourdfpy."""
    robot = yourdfpy.URDF.load(str(urdf), build_scene_graph=False, load_meshes=False,
                               load_collision_meshes=False)
    return float(robot.joint_map[joint].mimic.multiplier)
