"""The welding process along a seam: ``FrameTree.weld_process`` beside a ``pose()`` of the
same path, and beside a plain-numpy computation of the torch angles.

Case: the bundled welding cell (robot on its joint trajectory, turning positioner, the
2001-point ``seam_point`` curve), ``torch_tcp`` along ``seam_point`` relative to
``workpiece`` at 10^5 times over the 20 s (between samples and keyframes). Methods:

- ``pose()``: ``tree.pose("torch_tcp", "seam_point", times)``, the yardstick (goal: the
  process costs at most 3x this);
- ``pose() + numpy``: the same pose, then the angles and offset in numpy, as a user would
  write them without ``weld_process`` (no speed);
- ``weld_process``: travel speed (exact, from the velocity), both angles, offset;
- ``plain numpy``: no pinframes at all: joint values interpolated, the robot's forward
  kinematics from the Pinocchio model's joint placements, the positioner by SLERP, the seam
  point on its polyline (read from cell_design.yaml), the angles from the torch axis.
  ``max|diff|`` is the largest difference of the travel and work angles to it, radians.

Both thread settings, each in a child process (see ``_machine.py``).

Run: ``python benchmarks/bench_process.py [--quick]``.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pinocchio as pin
import yaml

import _reference as ref
from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings
from pinframes import read_scene

CELL = Path(__file__).resolve().parents[1] / "models" / "welding_cell"
URDF = CELL.parent / "welding_robot" / "welding_robot.urdf"
SAMPLES = 100_000
AXES = {"JointModelRX": 0, "JointModelRY": 1, "JointModelRZ": 2}


def static_matrix(entry: dict) -> np.ndarray:
    """(4, 4) of a cell_design.yaml frame entry with ``xyz`` and ``quat_xyzw``."""
    out = np.eye(4)
    out[:3, :3] = ref.matrices_from_quaternions(np.array([entry["quat_xyzw"]]))[0]
    out[:3, 3] = entry["xyz"]
    return out


class PlainNumpy:
    """The torch axis and origin in seam_point axes, from the cell's files, numpy only."""

    def __init__(self) -> None:
        cell = yaml.safe_load((CELL / "cell_design.yaml").read_text())
        frames = {entry["name"]: entry for entry in cell["frames"]}
        motion = np.loadtxt(CELL / "robot_motion.csv", delimiter=",", skiprows=1)
        self.sample_times, self.joint_values = motion[:, 0], motion[:, 1:]
        model = pin.buildModelFromUrdf(str(URDF))
        self.joints = [(model.jointPlacements[i].homogeneous,
                        np.eye(3)[AXES[model.joints[i].shortname()]])
                       for i in range(1, model.njoints)]
        flange = model.frames[model.getFrameId("flange")]
        self.base = static_matrix(frames["robot_base"])
        self.tool = flange.placement.homogeneous @ static_matrix(frames["torch_tcp"])
        keyframes = frames["positioner"]["keyframes"]
        quaternions = np.array(keyframes["quat_xyzw"])
        self.positioner = (np.array(keyframes["times_s"]), np.zeros((len(quaternions), 3)),
                           quaternions)
        self.positioner_base = static_matrix(frames["positioner_base"])
        self.seam = static_matrix(frames["workpiece"]) @ static_matrix(frames["weld_seam"])
        curve = frames["seam_point"]["curve"]
        arc = curve["arc"]
        angles = np.linspace(0.0, arc["angle"], arc["count"])
        centre = np.array(arc["centre_xyz"])
        start = np.array(arc["start_xyz"]) - centre
        self.points = centre + ref.rodrigues(np.array(arc["axis_xyz"]), angles) @ start
        # the seam point's frame at each point turns about y (the arc's axis) by the
        # tangent's angle; at the two ends by that of the parabola through the last three
        # points (equal chords: 4 p1 - 3 p0 - p2), x = (cos a, 0, -sin a)
        self.frame_angles = angles.copy()
        p = self.points
        for index, direction in ((0, 4 * p[1] - 3 * p[0] - p[2]),
                                 (-1, 3 * p[-1] - 4 * p[-2] + p[-3])):
            self.frame_angles[index] = np.arctan2(-direction[2], direction[0])
        self.point_times = np.linspace(0.0, curve["duration_s"], arc["count"])

    def angles(self, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Travel angle (rad), work angle (rad), offset (m) of the torch at ``times``."""
        torch = np.broadcast_to(self.base, (len(times), 4, 4))
        for column, (placement, axis) in enumerate(self.joints):
            values = np.interp(times, self.sample_times, self.joint_values[:, column])
            step = np.zeros((len(times), 4, 4))
            step[:, :3, :3] = placement[:3, :3] @ ref.rodrigues(axis, values)
            step[:, :3, 3] = placement[:3, 3]
            step[:, 3, 3] = 1.0
            torch = torch @ step
        torch = torch @ self.tool
        point = np.zeros((len(times), 4, 4))
        point[:, :3, :3] = ref.rodrigues(np.array([0.0, 1.0, 0.0]),
                                         np.interp(times, self.point_times, self.frame_angles))
        for axis in range(3):
            point[:, axis, 3] = np.interp(times, self.point_times, self.points[:, axis])
        point[:, 3, 3] = 1.0
        seam = (self.positioner_base @ ref.interpolate(times, *self.positioner) @ self.seam
                @ point)
        rotation_t = np.swapaxes(seam[:, :3, :3], 1, 2)
        wire = np.einsum("nij,nj->ni", rotation_t, torch[:, :3, 2])
        offset = np.einsum("nij,nj->ni", rotation_t, torch[:, :3, 3] - seam[:, :3, 3])
        return np.arcsin(wire[:, 0]), np.arctan2(-wire[:, 2], -wire[:, 1]), offset


def angles_from_pose(pose) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Travel angle, work angle and offset from a pose of the torch in the seam axes."""
    wire = pose.rotation[:, :, 2]
    return np.arcsin(wire[:, 0]), np.arctan2(-wire[:, 2], -wire[:, 1]), pose.translation


def child(quick: bool) -> None:
    tree = read_scene(CELL / "scene.yaml")
    times = np.linspace(0.0, 20.0, SAMPLES // 10 if quick else SAMPLES)
    plain = PlainNumpy()
    calls = {
        "pose()": lambda: tree.pose("torch_tcp", "seam_point", times=times),
        "pose() + numpy": lambda: angles_from_pose(
            tree.pose("torch_tcp", "seam_point", times=times)),
        "weld_process": lambda: tree.weld_process("torch_tcp", "seam_point", times=times,
                                                  workpiece="workpiece"),
        "plain numpy": lambda: plain.angles(times),
    }
    case = f"welding cell, {len(times):,} times"
    rows = interleaved(case, calls, 3 if quick else 9, reference="pose()")
    travel, work, _ = plain.angles(times)
    process = calls["weld_process"]()
    rows[2]["error"] = float(max(np.abs(process.travel_angle - travel).max(),
                                 np.abs(process.work_angle - work).max()))
    by_pose = angles_from_pose(calls["pose()"]())
    rows[1]["error"] = float(max(np.abs(by_pose[0] - travel).max(),
                                 np.abs(by_pose[1] - work).max()))
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child, "10^4 times, fewer repeats")
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference="pose()")
    print("goal (issue 27): weld_process at 10^5 times <= 3x pose() of the same path")


if __name__ == "__main__":
    main()
