"""Generate the bundled welding cell: its design in ``cell_design.yaml``, joints in
``robot_motion.csv``. The scene pinframes reads is ``scene.yaml`` beside them.

Run from the repository root::

    PYTHONPATH=src python models/welding_cell/make_motion.py [--out DIR]

It rewrites ``cell_design.yaml`` and ``robot_motion.csv`` beside itself (or in ``--out DIR``)
and gives the same numbers on every run.

The cell (all lengths in metres, angles in radians, times in seconds, quaternions x y z w):

- ``world``: the floor, z up.
- ``robot_base``: where the robot's ``base_link`` sits: on a 0.3 m riser, 0.4 m to the side
  of the seam plane, facing +x (so every joint takes part in the motion).
- ``positioner_base``: a single-axis headstock positioner; its z axis (the turning axis) is
  horizontal along world +y, its x axis points up.
- ``positioner``: the faceplate, turned about ``positioner_base`` z by the angle theta(t),
  stored as keyframes every 0.5 s (read between keyframes by SLERP, which for one axis is
  linear in the angle).
- ``workpiece``: a pipe of outer diameter 219.1 mm (DN 200) clamped on the faceplate, its axis
  on the turning axis; its origin is on the axis in the plane of the girth seam.
- ``weld_seam``: the start of the circumferential butt seam on the pipe surface: x along the
  welding direction, y along the pipe axis, z the outward surface normal. The seam is the
  half circle ``centre + Ry(a) @ (0, 0, radius)`` with centre ``(0, 0, -radius)`` in
  ``weld_seam`` coordinates and travel angle ``a`` from 0 to pi, welded at constant travel
  speed over the 20 s.
- ``seam_point``: the weld point, moving along the seam over the 20 s at the constant travel
  speed (x travel direction, y pipe axis, z outward normal): a polyline of
  ``SEAM_POINT_COUNT`` points on the half circle, one per robot sample
  (``pinframes.Pose.along_curve``), within 0.04 micrometres of it.
- ``torch_target``: the torch pose the cell is designed for, a static frame under
  ``seam_point``: tip on the seam, 10 degree push angle, 90 degree work angle.
- ``torch_tcp``: the tool centre point of a torch with a 22 degree neck, a static frame under
  the robot's ``flange``.

The positioner turns the pipe (theta falls from -25 to -155 degrees) while the robot moves
the torch from 25 degrees before the top of the pipe to 25 degrees past it, so that the torch
keeps a fixed pose (10 degree push angle, 90 degree work angle) relative to the seam point
under it. The joint samples come from pinframes itself: ``FrameTree.solve_joints`` puts
``torch_tcp`` on ``torch_target`` (the design torch pose over ``seam_point``) in
``scene.yaml`` at every time of ``seam_point``, so ``pinframes solve scene.yaml --frame
torch_tcp --target torch_target`` gives the same motion.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import yaml

import pinframes
from pinframes import JointSolution
from pinframes.formats.atomic import atomic_write
from pinframes.formats.joint_trajectory import joint_trajectory_csv

HERE = Path(__file__).resolve().parent
URDF_PATH = HERE.parent / "welding_robot" / "welding_robot.urdf"
CELL_FILE = "cell_design.yaml"
MOTION_FILE = "robot_motion.csv"

DURATION_S = 20.0
SAMPLE_RATE_HZ = 100.0
KEYFRAME_STEP_S = 0.5
PIPE_RADIUS_M = 0.10955
SEAM_OFFSET_FROM_FACEPLATE_M = 0.30
TORCH_STRAIGHT_M = 0.25  # straight torch body along the flange z axis
TORCH_NECK_M = 0.16  # bent neck, contact tip and wire stick-out up to the TCP
TORCH_NECK_ANGLE_RAD = math.radians(22.0)
PUSH_ANGLE_RAD = math.radians(10.0)
TORCH_ANGLE_START_RAD = math.radians(-25.0)  # seam point under the torch, from the pipe top
TORCH_ANGLE_END_RAD = math.radians(25.0)
SEAM_POINT_COUNT = 2001  # seam_point: one point per robot sample; chords 0.17 mm, sagitta 0.034 um
ROBOT_PREFIX = "robot/"
JOINT_NAMES = [f"joint_{i}" for i in range(1, 7)]
IK_SEED = np.array([-0.4, 0.3, 0.2, 0.0, 1.0, 1.5])  # rad, elbow up, wrist bent down
IK_TOLERANCE = 1e-9  # m and rad: keeps the travel speed between samples within 1e-5
MOTION_DIGITS = 9  # significant digits of robot_motion.csv
SIGNIFICANT_DIGITS = 12  # of the numbers in cell_design.yaml


def _round(values) -> list:
    """Numbers rounded to ``SIGNIFICANT_DIGITS`` as plain (nested) Python floats."""
    array = np.asarray(values, dtype=float)
    if array.ndim == 0:
        return float(f"{float(array):.{SIGNIFICANT_DIGITS}g}")
    return [_round(item) for item in array]


def _quat_xyzw(rotation: np.ndarray) -> np.ndarray:
    """Unit quaternion (x, y, z, w) of a 3x3 rotation matrix, w >= 0."""
    quat = pin.Quaternion(rotation).coeffs().copy()
    return -quat if quat[3] < 0 else quat


def _static_frame(name: str, parent: str, xyz, rotation: np.ndarray) -> dict:
    return {
        "name": name,
        "parent": parent,
        "xyz": _round(xyz),
        "quat_xyzw": _round(_quat_xyzw(rotation)),
    }


def _positioner_angle(times_s: np.ndarray) -> np.ndarray:
    """Planned positioner angle theta (rad) about its axis at ``times_s``.

    The torch angle from the pipe top follows a smooth step from start to end, the seam
    angle grows linearly; theta is their difference.
    """
    u = times_s / DURATION_S
    torch_angle = TORCH_ANGLE_START_RAD + (TORCH_ANGLE_END_RAD - TORCH_ANGLE_START_RAD) * (
        3 * u**2 - 2 * u**3
    )
    return torch_angle - math.pi * u


def _torch_rotation_in_seam_point() -> np.ndarray:
    """Rotation of ``torch_tcp`` in the seam-point frame (x travel, y pipe axis, z normal).

    The wire (TCP z) points into the pipe, tilted forward by the push angle; the TCP y axis
    points along the travel direction, so the torch neck leans back against it.
    """
    return (
        pin.utils.rotate("y", -PUSH_ANGLE_RAD)
        @ pin.utils.rotate("x", math.pi)
        @ pin.utils.rotate("z", -math.pi / 2)
    )


def build_cell() -> dict:
    """The cell description written to ``cell_design.yaml`` (plain dicts, lists and floats)."""
    up_x_axis_along_y = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])
    seam_axes_in_workpiece = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    neck = TORCH_NECK_ANGLE_RAD
    tcp_in_flange = [
        0.0,
        -TORCH_NECK_M * math.sin(neck),
        TORCH_STRAIGHT_M + TORCH_NECK_M * math.cos(neck),
    ]
    key_times = np.arange(0.0, DURATION_S + KEYFRAME_STEP_S / 2, KEYFRAME_STEP_S)
    half_theta = _positioner_angle(key_times) / 2
    zeros = np.zeros_like(half_theta)
    key_quats = np.stack([zeros, zeros, np.sin(half_theta), np.cos(half_theta)], axis=1)
    frames = [
        _static_frame("robot_base", "world", [0.0, 0.40, 0.30], np.eye(3)),
        _static_frame("positioner_base", "world", [1.0, -0.30, 0.85], up_x_axis_along_y),
        {
            "name": "positioner",
            "parent": "positioner_base",
            "xyz": [0.0, 0.0, 0.0],
            "keyframes": {"times_s": _round(key_times), "quat_xyzw": _round(key_quats)},
        },
        _static_frame(
            "workpiece", "positioner", [0.0, 0.0, SEAM_OFFSET_FROM_FACEPLATE_M], np.eye(3)
        ),
        _static_frame("weld_seam", "workpiece", [PIPE_RADIUS_M, 0.0, 0.0], seam_axes_in_workpiece),
        {
            "name": "seam_point",
            "parent": "weld_seam",
            "curve": {
                "arc": {
                    "centre_xyz": _round([0.0, 0.0, -PIPE_RADIUS_M]),
                    "axis_xyz": [0.0, 1.0, 0.0],
                    "start_xyz": [0.0, 0.0, 0.0],
                    "angle": _round(math.pi),
                    "count": SEAM_POINT_COUNT,
                },
                "duration_s": DURATION_S,
            },
        },
        _static_frame("torch_target", "seam_point", [0.0, 0.0, 0.0],
                      _torch_rotation_in_seam_point()),
        _static_frame(
            "torch_tcp", ROBOT_PREFIX + "flange", tcp_in_flange, pin.utils.rotate("x", neck)
        ),
    ]
    seam_length = PIPE_RADIUS_M * math.pi
    return {
        "format": "pinframes-welding-cell",
        "version": 1,
        "units": {"length": "m", "angle": "rad", "time": "s", "quaternion": "xyzw"},
        "root": "world",
        "frames": frames,
        "robot": {
            "urdf": "../welding_robot/welding_robot.urdf",
            "mount_frame": "robot_base",
            "prefix": ROBOT_PREFIX,
            "joint_trajectory": MOTION_FILE,
            "joint_names": JOINT_NAMES,
        },
        "seam": {
            "frame": "weld_seam",
            "shape": "circular_arc",
            "radius": _round(PIPE_RADIUS_M),
            "centre_xyz": _round([0.0, 0.0, -PIPE_RADIUS_M]),
            "axis_xyz": [0.0, 1.0, 0.0],
            "start_angle": 0.0,
            "end_angle": _round(math.pi),
            "length": _round(seam_length),
            "start_time_s": 0.0,
            "end_time_s": DURATION_S,
            "travel_speed_m_per_s": _round(seam_length / DURATION_S),
        },
        "torch": {
            "tcp_frame": "torch_tcp",
            "neck_angle": _round(neck),
            "push_angle": _round(PUSH_ANGLE_RAD),
            "work_angle": _round(math.pi / 2),
            "tcp_quat_xyzw_in_seam_point": _round(_quat_xyzw(_torch_rotation_in_seam_point())),
        },
    }


def compute_motion() -> JointSolution:
    """The robot's joint values at every time of ``seam_point`` (100 Hz): pinframes'
    ``solve_joints`` putting ``torch_tcp`` on ``torch_target`` in ``scene.yaml``, from
    ``IK_SEED``, within ``IK_TOLERANCE`` (else it stops)."""
    tree = pinframes.read(HERE / "scene.yaml")
    seed = {ROBOT_PREFIX + name: value for name, value in zip(JOINT_NAMES, IK_SEED, strict=True)}
    return tree.solve_joints("torch_tcp", "torch_target", seed=seed,
                             position_tolerance=IK_TOLERANCE, orientation_tolerance=IK_TOLERANCE,
                             strict=True)


def _cell_yaml(cell: dict) -> str:
    header = (
        "# Design data of the welding cell (frames, positioner keyframes, seam, torch) that\n"
        "# make_motion.py computes the robot motion from. Not a pinframes tree file: the\n"
        "# commands read scene.yaml beside it.\n"
        "# Generated by models/welding_cell/make_motion.py; described in models/README.md.\n"
        "# Lengths m, angles rad, times s, quaternions x y z w; a pose maps child to parent.\n"
    )
    return header + yaml.safe_dump(cell, sort_keys=False, default_flow_style=None, width=100)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=HERE, help="folder to write into")
    out = parser.parse_args().out
    cell = build_cell()
    solution = compute_motion()
    samples = solution.positions
    with atomic_write(out / CELL_FILE, "w") as handle:
        handle.write(_cell_yaml(cell))
    with atomic_write(out / MOTION_FILE, "w") as handle:
        handle.write(joint_trajectory_csv(solution.seconds, samples, JOINT_NAMES,
                                          significant_digits=MOTION_DIGITS))
    speeds = np.abs(np.diff(samples, axis=0)) * SAMPLE_RATE_HZ
    print(f"{len(solution)} samples over {DURATION_S} s, all reached; largest errors "
          f"{solution.position_error.max():.2g} m, {solution.orientation_error.max():.2g} rad")
    print("joint range (rad):", np.round(samples.min(0), 3), np.round(samples.max(0), 3))
    print("max joint speed (rad/s):", np.round(speeds.max(0), 4))


if __name__ == "__main__":
    main()
