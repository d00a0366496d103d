"""The 6-axis arms of the closed-form tests and their checks by Pinocchio called directly on
the URDF (never by pinframes' kinematics): forward kinematics, joint axes, and a damped
least-squares solver started from many random configurations, which finds the solutions
the closed form must not miss."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pinocchio as pin

from ik_paths import DATA, example_robot
from pinframes import FrameTree, Pose
from urdf.ros_packages import UR_DESCRIPTION, UR_XACRO, xacro_command

ARMS = DATA / "ros_industrial_arms"
KR6R900 = ARMS / "kuka_experimental" / "kr6r900sixx.urdf"
KR6R700 = ARMS / "kuka_experimental" / "kr6r700sixx.urdf"
IRB2400 = ARMS / "abb" / "irb2400.urdf"
IRB2600 = ARMS / "abb_experimental" / "irb2600_12_165.urdf"
HC10 = ARMS / "motoman" / "hc10.urdf"
"""Yaskawa's HC10: a cobot whose wrist is offset, neither family."""


def ros_industrial_arms() -> list[Path]:
    """Every arm of tests/data/ros_industrial_arms but the HC10."""
    return sorted(path for path in ARMS.glob("*/*.urdf") if path != HC10)


def universal_robots() -> list[Path]:
    """The UR3, UR5 and UR10 of example-robot-data (their full joint ranges)."""
    return [example_robot(f"{name}_robot.urdf") for name in ("ur3", "ur5", "ur10")]


UR_TYPES = tuple(sorted(folder.name for folder in (UR_DESCRIPTION / "config").iterdir()))
"""The arms of tests/data/ur_description (ur3, ur3e, ur5, ..., ur30): their nominal
parameter files, as published."""


def ur_description_tree(ur_type: str) -> FrameTree:
    """The ``ur_type`` arm as pinframes reads ``ur.urdf.xacro`` with ``ur_type:=...``."""
    tree = FrameTree("floor")
    tree.attach_urdf(UR_XACRO, "floor", xacro_args={"name": "ur", "ur_type": ur_type})
    return tree


def ur_description_urdf(ur_type: str, scratch: Path) -> Path:
    """The ``ur_type`` arm as the ``xacro`` command expands ``ur.urdf.xacro``, written into
    ``scratch``, for Pinocchio: a continuous joint (the UR3's wrist 3) is made revolute over
    (-pi, pi], the range in which pinframes gives its one value, so that Pinocchio reads
    one angle for it (a continuous joint would be its cosine and sine); nothing else
    changes."""
    text = xacro_command(UR_XACRO, {"name": "ur", "ur_type": ur_type},
                         {"ur_description": str(UR_DESCRIPTION)}, scratch)
    text = re.sub(r'type="continuous">(.*?)<limit ',
                  rf'type="revolute">\1<limit lower="{-math.pi!r}" upper="{math.pi!r}" ',
                  text, flags=re.DOTALL)
    path = scratch / f"{ur_type}.urdf"
    path.write_text(text)
    return path


def arm_tree(urdf: Path) -> FrameTree:
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    return tree


def arm_model(urdf: Path) -> pin.Model:
    return pin.buildModelFromUrdf(str(urdf))


def tool_pose(model: pin.Model, q: np.ndarray, frame: str = "tool0") -> pin.SE3:
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    return data.oMf[model.getFrameId(frame)].copy()


def pose_errors(model: pin.Model, q: np.ndarray, target: pin.SE3, frame: str = "tool0"
                ) -> tuple[float, float]:
    """Metres and radians between the tool at ``q`` and ``target``."""
    error = pin.log6(tool_pose(model, q, frame).inverse() * target).vector
    return (float(np.linalg.norm(tool_pose(model, q, frame).translation - target.translation)),
            float(np.linalg.norm(error[3:])))


def random_configurations(model: pin.Model, count: int, rng: np.random.Generator
                          ) -> np.ndarray:
    """``count`` configurations within the limits (at most half a turn from 0)."""
    lower = np.maximum(model.lowerPositionLimit, -np.pi)
    upper = np.minimum(model.upperPositionLimit, np.pi)
    return rng.uniform(lower, upper, size=(count, model.nq))


def targets_pose(placements: list[pin.SE3]) -> Pose:
    times = np.arange(len(placements), dtype=float)
    return Pose(np.array([p.translation for p in placements]),
                np.array([p.rotation for p in placements]), times=times)


def numeric_solutions(model: pin.Model, target: pin.SE3, starts: np.ndarray,
                      frame: str = "tool0") -> list[np.ndarray]:
    """The configurations within the limits that damped least squares reaches (1e-10)
    from each of ``starts``, whole turns of a joint moved into its range when they fit."""
    data = model.createData()
    tool = model.getFrameId(frame)
    found = []
    for start in starts:
        q = start.copy()
        for _ in range(200):
            pin.framesForwardKinematics(model, data, q)
            error = pin.log6(data.oMf[tool].inverse() * target).vector
            if np.linalg.norm(error) < 1e-11:
                break
            jacobian = pin.computeFrameJacobian(model, data, q, tool, pin.LOCAL)
            damping = 1e-6 + 1e-2 * min(1.0, float(np.linalg.norm(error)))
            step = jacobian.T @ np.linalg.solve(jacobian @ jacobian.T + damping * np.eye(6),
                                                error)
            q = q + np.clip(step, -0.5, 0.5)
        else:
            continue
        q = within_limits(model, q)
        if q is not None:
            found.append(q)
    return found


def within_limits(model: pin.Model, q: np.ndarray) -> np.ndarray | None:
    """``q`` with each joint moved by whole turns into its range (the lowest such value),
    or None when a joint's value has none."""
    moved = q.copy()
    for joint, (low, high) in enumerate(zip(model.lowerPositionLimit,
                                            model.upperPositionLimit, strict=True)):
        value = low + np.mod(q[joint] - low, 2 * np.pi)
        if value > high + 1e-9:
            return None
        moved[joint] = value
    return moved


def lowest_in_range(model: pin.Model, positions: np.ndarray) -> np.ndarray:
    """Solutions (k, 6) with each joint at its lowest value within its range by whole
    turns (so that two solutions that differ by turns compare equal)."""
    low = model.lowerPositionLimit
    return low + np.mod(positions - low, 2 * np.pi)


def joint_axes(model: pin.Model, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per joint, its axis direction and a point of it in the world, at ``q``."""
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    directions, points = [], []
    for joint in range(1, model.njoints):
        jacobian = pin.getJointJacobian(model, data, joint, pin.LOCAL_WORLD_ALIGNED)
        directions.append(jacobian[3:, model.idx_vs[joint]])
        points.append(data.oMi[joint].translation.copy())
    return np.array(directions), np.array(points)


def meeting_point(direction_a: np.ndarray, point_a: np.ndarray, direction_b: np.ndarray,
                  point_b: np.ndarray) -> np.ndarray:
    """The point midway between the closest points of two lines (least squares)."""
    matrix = np.stack([direction_a, -direction_b], axis=1)
    along, *_ = np.linalg.lstsq(matrix, point_b - point_a, rcond=None)
    return 0.5 * (point_a + along[0] * direction_a + point_b + along[1] * direction_b)
