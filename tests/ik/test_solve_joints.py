"""``FrameTree.solve_joints``: inverse kinematics along a path.

Every solution is checked with Pinocchio called directly on the URDF
(``pin.buildModelFromUrdf`` + ``framesForwardKinematics``), never with pinframes' own
kinematics; targets are made the same way (or by hand), from joint trajectories the robots can
follow.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import POSITIONER, as_pose, errors, example_robot, frame_poses
from pinframes import FrameTree, JointSolution, Pose, TargetNotReachedError
from pinframes.errors import (
    ArgumentTypeError,
    FrameNotFoundError,
    InvalidDataError,
    JointError,
    JointWithoutSamplesWarning,
    PinframesError,
)

ROBOT = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
ARM = [f"robot/joint_{index}" for index in range(1, 7)]
HOME = np.array([0.2, 0.4, -0.6, 0.1, 0.9, 0.3])  # rad: elbow up, wrist bent, inside limits
SWING = np.array([0.5, 0.3, 0.3, 0.6, 0.4, 0.8])
RATE_HZ = 100.0
TOLERANCE = 1e-6


def swinging(home: np.ndarray, swing: np.ndarray, count: int) -> np.ndarray:
    """A smooth joint trajectory (count, n) at 100 Hz: each joint swings about ``home``."""
    times = np.arange(count)[:, None] / RATE_HZ
    joint = np.arange(home.shape[0])[None, :]
    return home + swing * np.sin(0.6 * times * (1 + 0.2 * joint) + joint)


def robot_tree() -> FrameTree:
    tree = FrameTree("floor")
    tree.attach_urdf(ROBOT, "floor", prefix="robot/")
    return tree


def welding_robot() -> pin.Model:
    return pin.buildModelFromUrdf(str(ROBOT))


# -- tracking a trajectory the arm can follow ------------------------------------------------
def test_a_six_axis_arm_returns_its_own_trajectory():
    model = welding_robot()
    trajectory = swinging(HOME, SWING, 600)
    targets = frame_poses(model, "flange", trajectory)
    tree = robot_tree()
    solution = tree.solve_joints("robot/flange", as_pose(targets, np.arange(600) / RATE_HZ),
                                 seed=dict(zip(ARM, trajectory[0], strict=True)))
    assert isinstance(solution, JointSolution)
    assert solution.joint_names == tuple(ARM)
    assert solution.positions.shape == (600, 6) and solution.all_reached
    np.testing.assert_allclose(solution.positions, trajectory, atol=1e-5)
    position, orientation = errors(frame_poses(model, "flange", solution.positions), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE
    # the reported errors are the true ones
    np.testing.assert_allclose(solution.position_error, position, atol=1e-12)
    np.testing.assert_allclose(solution.orientation_error, orientation, atol=1e-9)
    np.testing.assert_allclose(solution.seconds, np.arange(600) / RATE_HZ, atol=1e-12)
    assert solution.reference_time is None


def test_the_ur5_returns_its_own_trajectory():
    urdf = example_robot("ur5_robot.urdf")
    model = pin.buildModelFromUrdf(str(urdf))
    trajectory = swinging(np.array([0.0, -1.2, 1.5, -1.8, -1.571, 0.0]),
                          np.array([0.8, 0.3, 0.4, 0.4, 0.4, 0.8]), 400)
    targets = frame_poses(model, "tool0", trajectory)
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    names = [model.names[joint] for joint in range(1, 7)]
    solution = tree.solve_joints("tool0", as_pose(targets, np.arange(400) / RATE_HZ),
                                 seed=trajectory[0])
    assert solution.joint_names == tuple(names) and solution.all_reached
    np.testing.assert_allclose(solution.positions, trajectory, atol=1e-5)
    position, orientation = errors(frame_poses(model, "tool0", solution.positions), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE


def test_a_seven_axis_arm_stays_within_its_limits_and_continuous():
    urdf = example_robot("panda.urdf")
    model = pin.buildModelFromUrdf(str(urdf))
    home = np.array([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785, 0.02, 0.02])
    swing = np.array([0.6, 0.4, 0.6, 0.4, 0.6, 0.4, 0.6, 0.0, 0.0])
    trajectory = swinging(home, swing, 1500)
    targets = frame_poses(model, "panda_hand", trajectory)
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    solution = tree.solve_joints("panda_hand", as_pose(targets, np.arange(1500) / RATE_HZ),
                                 seed=trajectory[0, :7])
    assert solution.joint_names == tuple(f"panda_joint{index}" for index in range(1, 8))
    assert solution.all_reached
    lower, upper = model.lowerPositionLimit[:7], model.upperPositionLimit[:7]
    assert np.all(solution.positions >= lower) and np.all(solution.positions <= upper)
    largest_step = np.abs(np.diff(solution.positions, axis=0)).max()
    assert largest_step <= 3 * np.abs(np.diff(trajectory[:, :7], axis=0)).max()
    configurations = trajectory.copy()
    configurations[:, :7] = solution.positions
    position, orientation = errors(frame_poses(model, "panda_hand", configurations), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE


def test_a_motion_tracked_into_a_limit_stops_on_it():
    """Joint 3 ramps past its upper limit (1.1345 rad) while the others swing: the samples
    before are tracked (the limits checked by the margin carried from sample to sample),
    the joint then stays on its limit and those samples are not reached."""
    model = welding_robot()
    upper = model.upperPositionLimit[2]
    trajectory = swinging(HOME, SWING * 0.3, 300)
    trajectory[:, 2] = np.linspace(0.5, 1.5, 300)
    targets = frame_poses(model, "flange", trajectory)
    solution = robot_tree().solve_joints("robot/flange", as_pose(targets, np.arange(300) / RATE_HZ),
                                         seed=trajectory[0])
    assert np.all(solution.positions >= model.lowerPositionLimit)
    assert np.all(solution.positions <= model.upperPositionLimit)
    inside = trajectory[:, 2] <= upper - 0.05
    assert solution.reached[inside].all()
    np.testing.assert_allclose(solution.positions[inside], trajectory[inside], atol=1e-5)
    beyond = trajectory[:, 2] >= upper + 0.05
    assert not solution.reached[beyond].any()
    np.testing.assert_allclose(solution.positions[beyond, 2], upper, atol=1e-9)


def test_samples_taken_as_solved_unmeasured_are_measured_and_mended(monkeypatch):
    """With the curvature bound set far too low, the loop takes large full Newton steps as
    landing within the tolerances; the batched measurement finds those that did not, and
    they are solved again: every sample still ends within the tolerances."""
    from pinframes.kinematics.ik import _newton_tracking

    monkeypatch.setattr(_newton_tracking, "CURVATURE", 1e-9)
    model = welding_robot()
    trajectory = swinging(HOME, SWING, 200)[::4]  # 25 Hz: larger steps between samples
    targets = frame_poses(model, "flange", trajectory)
    solution = robot_tree().solve_joints("robot/flange", as_pose(targets, np.arange(50) / 25.0),
                                         seed=trajectory[0])
    assert solution.all_reached
    position, orientation = errors(frame_poses(model, "flange", solution.positions), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE
    np.testing.assert_allclose(solution.position_error, position, atol=1e-12)


# -- out of reach ----------------------------------------------------------------------------
def unreachable_stretch() -> tuple[list[pin.SE3], np.ndarray, slice]:
    """Targets from a trajectory, moved 3 m up (beyond the arm's reach) from 1 s to 2 s."""
    trajectory = swinging(HOME, SWING, 300)
    targets = frame_poses(welding_robot(), "flange", trajectory)
    away = slice(100, 200)
    for index in range(away.start, away.stop):
        targets[index] = pin.SE3(targets[index].rotation,
                                 targets[index].translation + np.array([0.0, 0.0, 3.0]))
    return targets, trajectory, away


def test_an_unreachable_stretch_is_reported_and_left():
    targets, trajectory, away = unreachable_stretch()
    tree = robot_tree()
    solution = tree.solve_joints("robot/flange", as_pose(targets, np.arange(300) / RATE_HZ),
                                 seed=trajectory[0])
    assert not solution.reached[away].any()
    assert solution.reached[:away.start].all() and solution.reached[away.stop + 20:].all()
    model = welding_robot()
    assert np.all(solution.positions >= model.lowerPositionLimit)
    assert np.all(solution.positions <= model.upperPositionLimit)
    position, orientation = errors(frame_poses(model, "flange", solution.positions), targets)
    np.testing.assert_allclose(solution.position_error, position, atol=1e-9)
    np.testing.assert_allclose(solution.orientation_error, orientation, atol=1e-9)
    # the closest it gets: the target is 3 m up, the arm reaches out towards it
    reach = np.linalg.norm([t.translation for t in targets[away]], axis=1)
    assert np.all(position[away] < reach) and np.all(position[away] > 1.0)
    # back on the trajectory once the targets come back
    np.testing.assert_allclose(solution.positions[away.stop + 20:],
                               trajectory[away.stop + 20:], atol=1e-5)


def test_strict_names_the_first_unreachable_time_and_its_residual():
    targets, trajectory, _ = unreachable_stretch()
    tree = robot_tree()
    with pytest.raises(TargetNotReachedError) as raised:
        tree.solve_joints("robot/flange", as_pose(targets, np.arange(300) / RATE_HZ),
                          seed=trajectory[0], strict=True)
    message = str(raised.value)
    assert "robot/flange" in message and "1 s" in message and "sample 101 of 300" in message
    assert "position error" in message and "orientation error" in message
    assert raised.value.field == "target"


# -- targets that are frames of the tree -----------------------------------------------------
def test_a_target_frame_on_a_turning_table():
    """The table turns 30 degrees about its vertical axis in 5 s; the target rides on it."""
    model = welding_robot()
    start = HOME
    tool_at_start = frame_poses(model, "flange", start[None])[0]
    centre = tool_at_start.translation + np.array([0.15, 0.0, 0.0])
    angles = np.radians([0.0, 30.0])
    tree = robot_tree()
    tree.add("table", "floor", Pose(np.tile(centre, (2, 1)),
                                    [[0, 0, np.sin(a / 2), np.cos(a / 2)] for a in angles],
                                    times=[0.0, 5.0]))
    seam_in_table = pin.SE3(tool_at_start.rotation, tool_at_start.translation - centre)
    tree.add("seam", "table", Pose(seam_in_table.translation, seam_in_table.rotation))
    times = np.linspace(0.0, 5.0, 251)
    solution = tree.solve_joints("robot/flange", "seam", times=times,
                                 seed=dict(zip(ARM, start, strict=True)))
    assert solution.all_reached and len(solution) == 251
    targets = [pin.SE3(pin.utils.rotate("z", angle), centre) * seam_in_table
               for angle in np.radians(30.0) * times / 5.0]
    position, orientation = errors(frame_poses(model, "flange", solution.positions), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE
    # applying the solution puts the tool on the seam (pinframes' own pose query agrees)
    tree.set_joint_trajectory(solution.seconds, solution.positions,
                              joint_names=solution.joint_names)
    offset = tree.pose("robot/flange", "seam", times=times)
    assert np.abs(offset.translation).max() <= 1e-6


def test_the_default_times_are_the_target_path_s_not_the_solved_joints():
    tree = robot_tree()
    tree.set_joint_trajectory([0.0, 7.0], np.tile(HOME, (2, 1)), joint_names=ARM)
    tool = frame_poses(welding_robot(), "flange", HOME[None])[0]
    tree.add("target", "floor", Pose(np.tile(tool.translation, (3, 1)),
                                     np.tile(tool.rotation, (3, 1, 1)), times=[0.0, 1.0, 2.5]))
    solution = tree.solve_joints("robot/flange", "target")
    np.testing.assert_allclose(solution.seconds, [0.0, 1.0, 2.5])
    # started from the joints' trajectory at the first time: already there
    np.testing.assert_array_equal(solution.positions[0], HOME)


def test_a_target_with_a_reference_time_gives_absolute_times():
    trajectory = swinging(HOME, SWING, 50)
    targets = frame_poses(welding_robot(), "flange", trajectory)
    start = np.datetime64("2024-03-01T08:00:00", "ns")
    target = Pose(np.array([p.translation for p in targets]),
                  np.array([p.rotation for p in targets]),
                  times=np.arange(50) / RATE_HZ, reference_time=start)
    tree = robot_tree()
    solution = tree.solve_joints("robot/flange", target, seed=trajectory[0])
    assert solution.reference_time == start
    assert solution.absolute_times[1] == start + np.timedelta64(10, "ms")
    tree.set_joint_trajectory(solution.absolute_times, solution.positions,
                              joint_names=solution.joint_names)
    np.testing.assert_allclose(tree.joint_trajectory("robot/joint_1").values, trajectory[:, 0],
                               atol=1e-5)


def test_a_static_target_is_one_sample():
    tool = frame_poses(welding_robot(), "flange", HOME[None])[0]
    tree = robot_tree()
    solution = tree.solve_joints("robot/flange", Pose(tool.translation, tool.rotation),
                                 seed=HOME + 0.05)
    assert len(solution) == 1 and solution.all_reached
    position, orientation = errors(frame_poses(welding_robot(), "flange", solution.positions),
                                   [tool])
    assert position[0] <= TOLERANCE and orientation[0] <= TOLERANCE


def test_a_pose_target_relative_to_another_frame():
    tree = robot_tree()
    tree.add("fixture", "floor", Pose([0.3, -0.2, 0.1], [0.0, 0.0, np.sin(0.2), np.cos(0.2)]))
    trajectory = swinging(HOME, SWING, 100)
    in_floor = frame_poses(welding_robot(), "flange", trajectory)
    fixture = pin.SE3(pin.utils.rotate("z", 0.4), np.array([0.3, -0.2, 0.1]))
    in_fixture = [fixture.actInv(placement) for placement in in_floor]
    solution = tree.solve_joints("robot/flange", as_pose(in_fixture, np.arange(100) / RATE_HZ),
                                 relative_to="fixture", seed=trajectory[0])
    np.testing.assert_allclose(solution.positions, trajectory, atol=1e-5)


# -- coordinated motion ----------------------------------------------------------------------


@pytest.mark.parametrize("named", [{"joints": [*ARM, "positioner/turn"]},
                                   {"add_joints": ["positioner/turn"]}],
                         ids=["joints", "add_joints"])
def test_robot_and_positioner_solved_together(tmp_path, named):
    """A seam point runs round the faceplate; solving the robot and the positioner's turn
    together (all named, or the turn added to the default set: the robot's joints), both
    move, and the torch stays on the seam."""
    urdf = tmp_path / "positioner.urdf"
    urdf.write_text(POSITIONER)
    robot_model, positioner_model = welding_robot(), pin.buildModelFromUrdf(str(urdf))
    tool_at_start = frame_poses(robot_model, "flange", HOME[None])[0]
    mount = pin.SE3(np.eye(3), tool_at_start.translation - [0.1, 0.0, 0.4])
    tree = robot_tree()
    tree.add("positioner_base", "floor", Pose(mount.translation))
    tree.attach_urdf(urdf, "positioner_base", prefix="positioner/")
    # the seam point: 0.1 m from the faceplate centre, a quarter turn round it in 4 s
    angles = np.linspace(0.0, np.pi / 2, 9)
    times = np.linspace(0.0, 4.0, 9)
    rotation = tool_at_start.rotation
    tree.add("seam", "positioner/faceplate",
             Pose(np.stack([0.1 * np.cos(angles), 0.1 * np.sin(angles), 0 * angles], axis=1),
                  np.tile(rotation, (9, 1, 1)), times=times))
    sample_times = np.linspace(0.0, 4.0, 201)
    solution = tree.solve_joints("robot/flange", "seam", times=sample_times, **named,
                                 seed=dict(zip(ARM, HOME, strict=True)))
    assert solution.joint_names == (*ARM, "positioner/turn") and solution.all_reached
    turn = solution.positions[:, 6]
    assert np.ptp(turn) > 0.05  # the positioner takes part
    assert np.abs(np.diff(solution.positions, axis=0)).max() < 0.05  # continuous
    # both robots by Pinocchio on their URDFs; the seam point by hand: its translation
    # linear between the keyframes (the chords of the quarter circle), its rotation fixed
    corners = np.stack([0.1 * np.cos(angles), 0.1 * np.sin(angles), 0 * angles], axis=1)
    points = np.stack([np.interp(sample_times, times, corners[:, axis]) for axis in range(3)],
                      axis=1)
    faceplates = frame_poses(positioner_model, "faceplate", turn[:, None])
    targets = [mount * faceplate * pin.SE3(rotation, point)
               for faceplate, point in zip(faceplates, points, strict=True)]
    position, orientation = errors(frame_poses(robot_model, "flange", solution.positions[:, :6]),
                                   targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE


# -- a free tool axis ------------------------------------------------------------------------
@pytest.mark.parametrize("axis", ["x", "z"])
def test_a_free_axis_matches_position_and_axis_and_ignores_the_spin(axis):
    """The tool spins about one of its axes at random from sample to sample: with that axis
    free the arm keeps its own smooth motion. For "z" the tool is a frame on the flange whose
    z axis is the flange's x axis (the last joint's), as a torch's wire is."""
    model = welding_robot()
    index = "xyz".index(axis)
    tool_in_flange = pin.SE3(np.eye(3) if axis == "x" else pin.utils.rotate("y", np.pi / 2),
                             np.array([0.0, 0.0, 0.1]))
    trajectory = swinging(HOME, SWING, 300)
    targets = [flange * tool_in_flange for flange in frame_poses(model, "flange", trajectory)]
    spins = np.random.default_rng(7).uniform(-np.pi, np.pi, 300)
    spun = [target * pin.SE3(pin.utils.rotate(axis, spin), np.zeros(3))
            for target, spin in zip(targets, spins, strict=True)]
    tree = robot_tree()
    tree.add("tool", "robot/flange", Pose(tool_in_flange.translation, tool_in_flange.rotation))
    # at the given times: between them the random spins make the target's axis wobble
    solution = tree.solve_joints("tool", as_pose(spun, np.arange(300) / RATE_HZ),
                                 times=np.arange(300) / RATE_HZ, free_axis=axis,
                                 seed=trajectory[0])
    assert solution.all_reached
    # without the spins the arm keeps its own smooth motion
    assert np.abs(np.diff(solution.positions, axis=0)).max() < 0.05
    placements = [flange * tool_in_flange
                  for flange in frame_poses(model, "flange", solution.positions)]
    position, _ = errors(placements, targets)
    axes = np.array([p.rotation[:, index] for p in placements])
    wanted = np.array([t.rotation[:, index] for t in spun])
    angle = np.arctan2(np.linalg.norm(np.cross(axes, wanted), axis=1),
                       np.sum(axes * wanted, axis=1))
    assert position.max() <= TOLERANCE and angle.max() <= TOLERANCE
    np.testing.assert_allclose(solution.orientation_error, angle, atol=1e-9)


# -- mimic joints and continuous joints ------------------------------------------------------
MIMIC_ARM = """<?xml version="1.0"?>
<robot name="mimic_arm">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <link name="tip"/>
  <joint name="pan" type="continuous">
    <parent link="base"/><child link="a"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="lift" type="revolute">
    <parent link="a"/><child link="b"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" velocity="1" effort="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="b"/><child link="c"/><origin xyz="0.4 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" velocity="1" effort="1"/>
  </joint>
  <joint name="wrist" type="revolute">
    <parent link="c"/><child link="d"/><origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" velocity="1" effort="1"/>
    <mimic joint="elbow" multiplier="-0.5" offset="0.1"/>
  </joint>
  <joint name="tip_joint" type="fixed">
    <parent link="d"/><child link="tip"/><origin xyz="0.1 0 0"/>
  </joint>
</robot>
"""


def mimic_arm_model(tmp_path: Path) -> tuple[Path, pin.Model]:
    urdf = tmp_path / "mimic_arm.urdf"
    urdf.write_text(MIMIC_ARM)
    return urdf, pin.buildModelFromUrdf(str(urdf))


def mimic_configurations(model: pin.Model, primaries: np.ndarray) -> np.ndarray:
    """Pinocchio configurations with the mimic joint set from its primary by hand."""
    configurations = np.zeros((primaries.shape[0], model.nq))
    for index, (pan, lift, elbow) in enumerate(primaries):
        q = configurations[index]
        q[model.idx_qs[model.getJointId("pan")]:][:2] = np.cos(pan), np.sin(pan)
        q[model.idx_qs[model.getJointId("lift")]] = lift
        q[model.idx_qs[model.getJointId("elbow")]] = elbow
        q[model.idx_qs[model.getJointId("wrist")]] = -0.5 * elbow + 0.1
    return configurations


def test_mimic_joints_follow_their_primaries_and_continuous_joints_turn_on(tmp_path):
    """The pan joint turns one and a half times round (continuous: no limit, and no numpy
    warning about its infinite limits); the wrist mimics the elbow."""
    urdf, model = mimic_arm_model(tmp_path)
    count = 300
    ramp = np.linspace(0.0, 1.0, count)
    primaries = np.stack([3 * np.pi * ramp, 0.3 + 0.2 * ramp, -0.8 + 0.4 * ramp], axis=1)
    targets = frame_poses(model, "tip", mimic_configurations(model, primaries))
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solution = tree.solve_joints("tip", as_pose(targets, ramp * 3.0), seed=primaries[0])
    assert solution.joint_names == ("pan", "lift", "elbow")
    assert solution.all_reached
    np.testing.assert_allclose(solution.positions, primaries, atol=1e-5)
    position, orientation = errors(
        frame_poses(model, "tip", mimic_configurations(model, solution.positions)), targets)
    assert position.max() <= TOLERANCE and orientation.max() <= TOLERANCE


def test_a_mimic_joint_s_limits_bound_its_primary(tmp_path):
    """The wrist follows the elbow at -0.5 * elbow + 0.1 within its limits +-1: the elbow
    may go up to 2.2 (its own limit is 2.5). A target that needs the elbow at 2.4 is left
    at 2.2, not reached; the pan joint, not solved for, holds its rest value (and warns)."""
    urdf, model = mimic_arm_model(tmp_path)
    beyond = np.array([[0.0, 0.3, 2.4]])
    target = frame_poses(model, "tip", mimic_configurations(model, beyond))[0]
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    with pytest.warns(JointWithoutSamplesWarning, match="'pan'"):
        solution = tree.solve_joints("tip", Pose(target.translation, target.rotation),
                                     joints=["lift", "elbow"], seed={"lift": 0.3, "elbow": 2.0})
    assert solution.joint_names == ("lift", "elbow")
    np.testing.assert_allclose(solution.positions[0, 1], 2.2, atol=1e-9)
    assert not solution.reached[0] and solution.position_error[0] > 1e-3


# -- bad input -------------------------------------------------------------------------------
@pytest.mark.parametrize(("arguments", "error", "field", "words"), [
    ({"frame": "robot/flang"}, FrameNotFoundError, None, "robot/flange"),
    ({"target": "nowhere"}, FrameNotFoundError, None, "nowhere"),
    ({"target": 3}, ArgumentTypeError, "target", "Pose"),
    ({"joints": ["robot/joint_9"]}, JointError, "joints", "robot/joint_9"),
    ({"joints": "robot/joint_1"}, ArgumentTypeError, "joints", "list"),
    ({"joints": ["robot/joint_1", "robot/joint_1"]}, JointError, "joints", "repeat"),
    ({"joints": []}, JointError, "joints", "no joints"),
    ({"free_axis": "w"}, ArgumentTypeError, "free_axis", "'w'"),
    ({"position_tolerance": 0.0}, InvalidDataError, "position_tolerance", "positive"),
    ({"orientation_tolerance": "tight"}, InvalidDataError, "orientation_tolerance", "tight"),
    ({"seed": [0.0, 0.0]}, InvalidDataError, "seed", "6 values"),
    ({"seed": {"robot/joint_7": 0.0}}, JointError, "seed", "robot/joint_7"),
    ({"seed": {"robot/joint_2": 3.0}}, JointError, "seed", "limits"),
    ({"seed": {"robot/joint_2": float("nan")}}, InvalidDataError, "seed", "finite"),
    ({"relative_to": "floor", "target": "here"}, ArgumentTypeError, "relative_to", "Pose"),
])
def test_bad_input_names_the_frame_joint_and_field(arguments, error, field, words):
    tree = robot_tree()
    tree.add("here", "floor", Pose([0.5, 0.0, 0.5]))
    call = {"frame": "robot/flange", "target": Pose([0.5, 0.0, 0.5])} | arguments
    with pytest.raises(error) as raised:
        tree.solve_joints(call.pop("frame"), call.pop("target"), **call)
    assert isinstance(raised.value, PinframesError)
    assert raised.value.field == field
    assert words in str(raised.value)


def test_joints_that_move_neither_frame_and_mimic_joints_are_refused(tmp_path):
    urdf, _ = mimic_arm_model(tmp_path)
    tree = robot_tree()
    tree.attach_urdf(urdf, "floor", prefix="other/")
    with pytest.raises(JointError, match="'other/lift' moves neither") as raised:
        tree.solve_joints("robot/flange", Pose([0.5, 0.0, 0.5]), joints=["other/lift"])
    assert raised.value.frame == "robot/flange"
    with pytest.raises(JointError, match="mimics 'other/elbow'"):
        tree.solve_joints("other/tip", Pose([0.5, 0.0, 0.5]), joints=["other/wrist"])
    tree.add("plate", "floor", Pose([1.0, 0.0, 0.0]))
    with pytest.raises(JointError, match="no robot joint moves 'plate'"):
        tree.solve_joints("plate", "floor")
