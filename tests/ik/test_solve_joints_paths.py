"""``solve_joints`` along paths that redundant arms, singular configurations, long gaps and
missing seeds make hard: on the UR5 and Panda of example-robot-data, UFACTORY's xArm7 and
ROS-Industrial's Motoman SIA10D (tests/data).

Targets come from joint trajectories the robots can follow (every sample is reachable);
every answer is checked with Pinocchio called directly on the URDF (:mod:`ik_paths`).
"""

from __future__ import annotations

import warnings

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import (
    POSITIONER,
    TOLERANCE,
    arm,
    as_pose,
    errors,
    frame_poses,
    largest_step,
    on_target,
    serial_urdf,
    swinging,
    within_limits,
)
from pinframes import FrameTree, Pose
from pinframes.errors import FileFormatError, InvalidDataError

ARMS = ["UR5", "Panda", "xArm7", "SIA10D"]
REDUNDANT = ["Panda", "xArm7", "SIA10D"]


def configurations(model: pin.Model, robot_home: tuple[float, ...], solved: np.ndarray
                   ) -> np.ndarray:
    """Pinocchio's ``q`` per sample: the solved joints, the others (the Panda's fingers) at
    home."""
    q = np.tile(np.asarray(robot_home), (solved.shape[0], 1))
    q[:, :solved.shape[1]] = solved
    return q


# -- every reachable sample, on every arm -----------------------------------------------------
@pytest.mark.parametrize("name", ARMS)
@pytest.mark.parametrize("rate_hz", [100.0, 30.0])
def test_every_sample_of_a_followable_path_is_reached_in_small_steps(name, rate_hz):
    """300 samples at 100 Hz and at 30 Hz (steps of up to 0.05 rad): all reached, steps
    within twice the trajectory's own, limits held. Of all the joint motions that put the
    tool on its targets, a redundant arm (7 axes) takes the smallest from sample to sample:
    its joints travel less than along the trajectory the targets came from (one of those
    motions)."""
    robot = arm(name)
    model = robot.model()
    times = np.arange(300) / rate_hz
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times),
                                         seed=trajectory[0, :robot.solved])
    solved = configurations(model, robot.home, solution.positions)
    assert on_target(model, robot.tool, solved, targets).all()
    assert solution.all_reached
    assert within_limits(model, solution.positions)
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory[:, :robot.solved])
    travel = np.linalg.norm(np.diff(solution.positions, axis=0), axis=1).sum()
    own = np.linalg.norm(np.diff(trajectory[:, :robot.solved], axis=0), axis=1).sum()
    assert travel < own if name in REDUNDANT else travel == pytest.approx(own, rel=1e-6)


@pytest.mark.parametrize("name", REDUNDANT)
def test_a_redundant_arm_on_a_target_that_stops_stands_still(name):
    """The targets follow the trajectory for 1 s and then stay (1 s): the joints stop with
    them, no self-motion carried on."""
    robot = arm(name)
    model = robot.model()
    times = np.arange(200) / 100.0
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing),
                          np.minimum(times, 1.0))
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times),
                                         seed=trajectory[0, :robot.solved])
    solved = configurations(model, robot.home, solution.positions)
    assert on_target(model, robot.tool, solved, targets).all()
    stopped = solution.positions[times >= 1.0]
    np.testing.assert_array_equal(stopped, np.tile(stopped[0], (stopped.shape[0], 1)))


# -- free axis: the smallest motion -----------------------------------------------------------
@pytest.mark.parametrize("name", ["UR5", "xArm7"])
def test_a_free_axis_costs_no_more_motion_than_the_spin_free_path(name):
    """The targets spin about the tool's z axis (3 rad/s) along a trajectory: with z free,
    the joints travel no further than that trajectory, whose spin was never asked for."""
    robot = arm(name)
    model = robot.model()
    times = np.arange(300) / 100.0
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    targets = frame_poses(model, robot.tool, trajectory)
    spun = [target * pin.SE3(pin.utils.rotate("z", 3.0 * time), np.zeros(3))
            for target, time in zip(targets, times, strict=True)]
    solution = robot.tree().solve_joints(robot.tool, as_pose(spun, times), free_axis="z",
                                         seed=trajectory[0, :robot.solved])
    placements = frame_poses(model, robot.tool,
                             configurations(model, robot.home, solution.positions))
    position, _ = errors(placements, targets)
    axes = np.array([p.rotation[:, 2] for p in placements])
    wanted = np.array([t.rotation[:, 2] for t in targets])
    angle = np.arctan2(np.linalg.norm(np.cross(axes, wanted), axis=1),
                       np.sum(axes * wanted, axis=1))
    assert position.max() <= TOLERANCE and angle.max() <= TOLERANCE
    travel = np.abs(np.diff(solution.positions, axis=0)).sum()
    assert travel <= np.abs(np.diff(trajectory[:, :robot.solved], axis=0)).sum()




FLIPPER = serial_urdf("flipper", [("lift", "prismatic", "arm", "0 0 0", -1.0, 1.0),
                                  ("roll_x", "revolute", "tool", "0 0 0", -3.5, 3.5)])


def test_a_free_axis_target_pointing_exactly_against_the_tool_is_reached(tmp_path):
    """Issue 36 item 11: at the seed the tool's z axis is exactly opposite the target's (a
    half turn away, no direction of turning preferred); a half turn of the roll joint
    reaches it."""
    urdf = tmp_path / "flipper.urdf"
    urdf.write_text(FLIPPER)
    model = pin.buildModelFromUrdf(str(urdf))
    target = pin.SE3(np.diag([1.0, -1.0, -1.0]), np.array([0.0, 0.0, 0.2]))
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    solution = tree.solve_joints("tool", Pose(target.translation, target.rotation),
                                 free_axis="z", seed=[0.0, 0.0])
    assert solution.all_reached
    placement = frame_poses(model, "tool", solution.positions)[0]
    assert np.linalg.norm(placement.translation - target.translation) <= TOLERANCE
    assert placement.rotation[:, 2] @ target.rotation[:, 2] >= np.cos(TOLERANCE)


# -- static targets ---------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["UR5", "SIA10D"])
def test_a_robot_and_positioner_on_a_seam_that_does_not_move_stand_still(tmp_path, name):
    """Solving the robot and the positioner's turn together (one joint more than the pose
    needs) for a seam point fixed on the faceplate: every sample reached, nothing moves."""
    robot = arm(name)
    model = robot.model()
    urdf = tmp_path / "positioner.urdf"
    urdf.write_text(POSITIONER)
    tool = frame_poses(model, robot.tool, np.asarray(robot.home)[None])[0]
    tree = robot.tree()
    tree.add("positioner_base", "floor", Pose(tool.translation - [0.1, 0.0, 0.4]))
    tree.attach_urdf(urdf, "positioner_base", prefix="positioner/")
    tree.add("seam", "positioner/faceplate", Pose([0.1, 0.0, 0.0], tool.rotation))
    names = [model.names[joint] for joint in range(1, robot.solved + 1)]
    solution = tree.solve_joints(robot.tool, "seam", times=np.linspace(0.0, 4.0, 201),
                                 joints=[*names, "positioner/turn"],
                                 seed=[*np.asarray(robot.home)[:robot.solved] + 0.02, 0.1])
    assert solution.all_reached
    np.testing.assert_array_equal(solution.positions[1:], np.tile(solution.positions[1],
                                                                  (200, 1)))
    turn = solution.positions[0, -1]
    faceplate = pin.SE3(pin.utils.rotate("z", turn), tool.translation - [0.1, 0.0, 0.0])
    seam = faceplate * pin.SE3(tool.rotation, np.array([0.1, 0.0, 0.0]))
    solved = configurations(model, robot.home, solution.positions[:1, :-1])
    assert on_target(model, robot.tool, solved, [seam]).all()


# -- singular configurations ------------------------------------------------------------------
def test_a_ur5_resting_in_its_wrist_singularity_is_tracked_through_and_out():
    """Wrist 2 at zero (wrist 1 and 3 in line) reached in 1 s, held 2 s with the tool
    still, left in 1 s: all 201 samples reached, the wrist holds still while it rests."""
    robot = arm("UR5")
    model = robot.model()
    times = np.arange(201) / 50.0
    progress = np.clip(times, 0.0, 1.0) + np.clip(times - 3.0, 0.0, 1.0) - 1.0
    trajectory = (np.array([0.3, -1.2, 1.5, -1.8, 0.0, 0.2])
                  + np.outer(progress, [0.3, 0.2, -0.2, 0.3, 0.5, 0.4]))
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times), times=times,
                                         seed=trajectory[0])
    assert on_target(model, robot.tool, solution.positions, targets).all()
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory)
    resting = (times >= 1.0) & (times <= 3.0)
    assert np.ptp(solution.positions[resting], axis=0).max() <= 1e-6


SHOULDER_SINGULAR_LIFT = -2.387223881901276
"""Shoulder lift (rad) of the UR5 at which the Jacobian of tool0 is singular when the
elbow is at 1.6 rad and wrist 2 at -1.4 (neither the elbow's nor the wrist's singularity):
a root of its determinant, found with Pinocchio's Jacobian and a bracketing root finder."""


def test_a_ur5_crossing_its_shoulder_singularity_stays_on_its_branch():
    """The shoulder lift passes exactly through its singular value at sample 100 while the
    other joints move: every sample reached, on the trajectory's own branch."""
    robot = arm("UR5")
    model = robot.model()
    data = model.createData()
    crossing = np.array([0.0, SHOULDER_SINGULAR_LIFT, 1.6, -2.0, -1.4, 0.3])
    jacobian = pin.computeFrameJacobian(model, data, crossing, model.getFrameId("tool0"),
                                        pin.LOCAL)
    assert abs(np.linalg.det(jacobian)) < 1e-12  # singular indeed
    times = np.arange(201) / 50.0
    trajectory = crossing + np.outer(times - 2.0, [0.2, 0.15, 0.1, -0.1, 0.1, 0.3])
    trajectory[100] = crossing
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times), times=times,
                                         seed=trajectory[0])
    assert on_target(model, robot.tool, solution.positions, targets).all()
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory)
    np.testing.assert_allclose(solution.positions[-50:], trajectory[-50:], atol=1e-5)


# -- gaps and repeated times ------------------------------------------------------------------
def test_a_long_gap_between_samples_keeps_the_branch():
    """Samples 0.21 s apart, then one 7.4 s later, the joints moving at up to 0.8 rad/s: the
    last step carried on over the gap would land half a turn away; the bridge keeps the
    trajectory's branch."""
    robot = arm("UR5")
    model = robot.model()
    times = np.append(np.arange(20) * 0.21, 19 * 0.21 + 7.4)
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times), times=times,
                                         seed=trajectory[0])
    assert on_target(model, robot.tool, solution.positions, targets).all()
    np.testing.assert_allclose(solution.positions, trajectory, atol=1e-5)


def test_repeated_times_give_the_same_joints_without_warnings():
    """Issue 36 item 9: times 1, 1, 2 (as pose() takes them)."""
    robot = arm("UR5")
    model = robot.model()
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing),
                          np.array([0.0, 2.0]))
    targets = frame_poses(model, robot.tool, trajectory)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solution = robot.tree().solve_joints(robot.tool, as_pose(targets, [0.0, 2.0]),
                                             times=[1.0, 1.0, 2.0], seed=trajectory[0])
    assert solution.all_reached and np.all(np.isfinite(solution.positions))
    np.testing.assert_array_equal(solution.positions[0], solution.positions[1])
    np.testing.assert_allclose(solution.positions[2], trajectory[1], atol=1e-5)


# -- the first sample without a seed ----------------------------------------------------------
@pytest.mark.parametrize("name", ARMS)
def test_without_a_seed_a_followable_path_is_followed(name):
    """No seed: the rest values (all zero: the UR5 stretched, a singular configuration) are
    only the first of several starts; the path is reached from one of them."""
    robot = arm(name)
    model = robot.model()
    times = np.arange(300) / 30.0
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    targets = frame_poses(model, robot.tool, trajectory)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints have no samples: they warn so
        solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times))
    solved = configurations(model, robot.home, solution.positions)
    assert on_target(model, robot.tool, solved, targets).all()
    assert within_limits(model, solution.positions)
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory[:, :robot.solved])


def test_a_given_seed_is_honoured():
    """The UR5 reaches its first target on two elbow branches: the seed picks the branch."""
    robot = arm("UR5")
    model = robot.model()
    up = np.array([0.0, -1.2, 1.5, -1.8, -1.571, 0.0])
    target = frame_poses(model, robot.tool, up[None])[0]
    tree = robot.tree()
    solution = tree.solve_joints(robot.tool, Pose(target.translation, target.rotation),
                                 seed=up + 0.05)
    np.testing.assert_allclose(solution.positions[0], up, atol=1e-5)
    elbow_down = tree.solve_joints(robot.tool, Pose(target.translation, target.rotation),
                                   seed=[0.0, -2.4, -1.5, 0.3, -1.571, 0.0])
    assert elbow_down.all_reached and elbow_down.positions[0, 2] < 0.0
    assert on_target(model, robot.tool, elbow_down.positions, [target]).all()


# -- one joint, far targets, tiny tolerances, bad limits --------------------------------------
TURNTABLE = serial_urdf("turntable", [("turn", "revolute", "plate", "0 0 0", -3.0, 3.0)],
                        tool=("mark", "0.5 0 0"))


@pytest.mark.parametrize("free_axis", [None, "z"])
def test_a_single_joint_path_is_solved(tmp_path, free_axis):
    """Issue 36 item 8: a one-axis turntable."""
    urdf = tmp_path / "turntable.urdf"
    urdf.write_text(TURNTABLE)
    model = pin.buildModelFromUrdf(str(urdf))
    target = frame_poses(model, "mark", np.array([[0.7]]))[0]
    tree = FrameTree("floor")
    tree.attach_urdf(urdf, "floor")
    solution = tree.solve_joints("mark", Pose(target.translation, target.rotation),
                                 free_axis=free_axis, seed=[0.0])
    assert solution.joint_names == ("turn",) and solution.all_reached
    assert on_target(model, "mark", solution.positions, [target]).all()


def test_a_target_1e155_m_away_is_reported_unreached():
    """Issue 36 item 9: out of reach by far: not reached, finite errors, no exception."""
    robot = arm("UR5")
    solution = robot.tree().solve_joints(robot.tool, Pose([1e155, 0.0, 0.0]),
                                         seed=np.asarray(robot.home))
    assert not solution.reached[0]
    assert np.isfinite(solution.position_error[0]) and solution.position_error[0] > 1e154
    assert within_limits(robot.model(), solution.positions)


@pytest.mark.parametrize("field", ["position_tolerance", "orientation_tolerance"])
def test_a_tolerance_below_double_precision_is_refused(field):
    """Issue 36 item 9: a tolerance of 1e-160 is an error naming the field."""
    robot = arm("UR5")
    with pytest.raises(InvalidDataError, match="1e-160") as raised:
        robot.tree().solve_joints(robot.tool, Pose([0.4, 0.1, 0.4]), **{field: 1e-160})
    assert raised.value.field == field and raised.value.frame == robot.tool


def test_urdf_limits_with_lower_above_upper_are_an_error_naming_the_joint(tmp_path):
    """Issue 36 item 12: refused when the URDF is read, not swapped by the solver."""
    urdf = tmp_path / "turntable.urdf"
    urdf.write_text(TURNTABLE.replace('lower="-3" upper="3"', 'lower="3" upper="-3"'))
    with pytest.raises(FileFormatError, match=r"lower limit 3 is above the upper limit -3"
                       ) as raised:
        FrameTree("floor").attach_urdf(urdf, "floor")
    assert raised.value.joint == "turn" and raised.value.field == "limit"
    assert str(urdf) in str(raised.value)


# -- the secondary objective ------------------------------------------------------------------
def test_the_null_space_motion_is_the_exact_projection(rng):
    """Against numpy's pseudo-inverse: ``m - pinv(A) @ A @ m``, which the task's rows do not
    feel; nothing without redundancy."""
    from pinframes.kinematics.ik._bounded_step import LeastSquares
    from pinframes.kinematics.ik._null_space import null_space_motion

    rows = rng.normal(size=(6, 7))
    motion = rng.normal(size=7)
    projected = null_space_motion(LeastSquares(), rows, motion)
    np.testing.assert_allclose(projected, motion - np.linalg.pinv(rows) @ rows @ motion,
                               atol=1e-12)
    np.testing.assert_allclose(rows @ projected, 0.0, atol=1e-12)
    square = rng.normal(size=(6, 6))
    np.testing.assert_array_equal(null_space_motion(LeastSquares(), square, motion[:6]), 0.0)


def test_joints_near_a_limit_are_moved_away_without_losing_a_sample():
    """The Panda's third joint swings about 0.15 rad below its upper limit (2.8973 rad),
    inside the band the solver keeps joints out of (0.2 rad): every sample is still
    reached, and the joint is moved away from its limit through the seventh axis's freedom
    (the elbow, joint 4, could not be: the wrist's position fixes it)."""
    robot = arm("Panda")
    model = robot.model()
    home = np.asarray(robot.home)
    home[2], swing = 2.75, np.asarray(robot.swing)
    swing[2] = 0.03
    times = np.arange(300) / 100.0
    trajectory = swinging(home, swing, times)
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times),
                                         seed=trajectory[0, :7])
    assert on_target(model, robot.tool, configurations(model, home, solution.positions),
                     targets).all()
    margin = model.upperPositionLimit[2] - solution.positions[:, 2]
    assert margin[-50:].min() > model.upperPositionLimit[2] - trajectory[0, 2] + 0.015
    assert within_limits(model, solution.positions)
    assert largest_step(solution.positions) <= 2 * largest_step(trajectory[:, :7])


def test_a_target_that_stands_still_near_a_limit_keeps_the_joints_still():
    """A static target reached from a seed a little off it with the Panda's third joint
    inside the band along its limit: the first sample is moved out a little, and then the
    joints do not creep further while nothing moves."""
    robot = arm("Panda")
    model = robot.model()
    home = np.asarray(robot.home)
    home[2] = 2.8
    target = frame_poses(model, robot.tool, home[None])[0]
    solution = robot.tree().solve_joints(robot.tool, as_pose([target] * 100,
                                                             np.arange(100) / 100.0),
                                         seed=home[:7] + 0.01)
    assert on_target(model, robot.tool, configurations(model, home, solution.positions),
                     [target] * 100).all()
    np.testing.assert_array_equal(solution.positions[1:], np.tile(solution.positions[0],
                                                                  (99, 1)))
