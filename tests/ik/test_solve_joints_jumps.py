"""No silent jumps: ``JointSolution.jumps`` lists the steps far past the path's usual one,
``strict=True`` raises at the first, and a path that rests in a singular configuration keeps
its way out of it (the jump bridged). Every solution is checked with Pinocchio called
directly on the URDF; the jumps by plain numpy on the returned joints."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import DATA, Arm, arm, as_pose, frame_poses, on_target, swinging, within_limits
from pinframes import JointJumpError

EXTRA = DATA / "ros_industrial_extra"
TIMES = np.linspace(0.0, 4.0, 41)  # s


def numpy_jumps(positions: np.ndarray, factor: float = 10.0) -> np.ndarray:
    """The samples whose largest joint change passes factor x the median one and 0.1."""
    steps = np.abs(np.diff(positions, axis=0)).max(axis=1)
    return np.flatnonzero(steps > max(factor * np.median(steps), 0.1)) + 1


def resting_in_the_wrist_singularity(wrist_1: float, wrist_3: float) -> np.ndarray:
    """UR5 joints (41, 6): wrist 2 comes down to 0 in the first second, rests there while
    wrists 1 and 3 turn at ``wrist_1`` and ``wrist_3`` rad/s for 2 s, then leaves."""
    joints = np.tile([0.3, -1.2, 1.5, -1.8, 0.0, 0.0], (TIMES.shape[0], 1))
    joints[:, 4] = np.where(TIMES < 1, 0.4 * (1 - TIMES), np.where(TIMES > 3, 0.4 * (TIMES - 3),
                                                                    0.0))
    turning = np.clip(TIMES - 1, 0, 2)
    joints[:, 3] += wrist_1 * turning
    joints[:, 5] += wrist_3 * turning
    return joints


@pytest.mark.parametrize(("wrist_1", "wrist_3"), [(0.5, 0.0), (0.0, 0.5), (0.5, -0.5)])
def test_resting_in_the_wrist_singularity_keeps_the_way_out(wrist_1, wrist_3):
    """While wrist 2 is 0 the turn may be split between wrists 1 and 3 in any way, and only
    the trajectory's split leaves the singularity where it does: solved forward alone, the
    path ended with one 0.53-1.19 rad step (13-30x its median)."""
    robot = arm("UR5")
    model = robot.model()
    trajectory = resting_in_the_wrist_singularity(wrist_1, wrist_3)
    targets = frame_poses(model, robot.tool, trajectory)
    solution = robot.tree().solve_joints(robot.tool, as_pose(targets, TIMES), times=TIMES,
                                         seed=trajectory[0])
    assert on_target(model, robot.tool, solution.positions, targets).all()
    assert solution.jumps is not None and solution.jumps.shape[0] == 0
    assert numpy_jumps(solution.positions).shape[0] == 0
    assert np.abs(np.diff(solution.positions, axis=0)).max() < 0.25


def far_paths_through_the_wrist(robot: Arm, count: int) -> list[np.ndarray]:
    """``count`` trajectories (101 samples at 50 Hz) inside the limits whose joint 5 starts
    within 0.05 rad of 0 (the wrist singularity); the same on every run."""
    model = robot.model()
    lower = np.maximum(model.lowerPositionLimit, -np.pi)
    upper = np.minimum(model.upperPositionLimit, np.pi)
    swing = np.minimum(robot.swing, (upper - lower) / 4)
    generator = np.random.default_rng(20261127)
    paths = []
    for _ in range(count):
        home = generator.uniform(lower + swing, upper - swing)
        home[4] = generator.uniform(-0.05, 0.05)
        paths.append(swinging(home, swing, np.arange(101) / 50.0))
    return paths


def fanuc(name: str) -> Arm:
    return Arm(name, EXTRA / "fanuc" / f"{name}.urdf", "tool0", 6, (0.0,) * 6,
               (0.4, 0.3, 0.3, 0.5, 0.4, 0.8))


@pytest.mark.parametrize("name", ["lrmate200id4s", "m430ia2p"])
def test_fanuc_seeded_near_the_wrist_singularity_reach_every_sample(name):
    """Seeded with the path's own first configuration, next to the wrist singularity (the
    LR Mate 200iD/4S and M-430iA/2P of ROS-Industrial): every sample on its target, the
    trajectory's branch kept, no jump."""
    robot = fanuc(name)
    model = robot.model()
    times = np.arange(101) / 50.0
    for trajectory in far_paths_through_the_wrist(robot, 6):
        targets = frame_poses(model, robot.tool, trajectory)
        solution = robot.tree().solve_joints(robot.tool, as_pose(targets, times), times=times,
                                             seed=trajectory[0])
        assert on_target(model, robot.tool, solution.positions, targets).all()
        assert within_limits(model, solution.positions)
        assert solution.jumps is not None and solution.jumps.shape[0] == 0


def test_jumps_are_reported_and_strict_names_the_first():
    """Without a seed the M-430iA/2P takes the other wrist branch on one of these paths,
    whose way past the singularity turns joints 4 and 6 by large steps: every sample is on
    its target, and the steps are the jumps numpy finds."""
    robot = fanuc("m430ia2p")
    model = robot.model()
    times = np.arange(101) / 50.0
    found = 0
    for trajectory in far_paths_through_the_wrist(robot, 40)[31:33]:
        targets = frame_poses(model, robot.tool, trajectory)
        target = as_pose(targets, times)
        solution = robot.tree().solve_joints(robot.tool, target, times=times)
        assert on_target(model, robot.tool, solution.positions, targets).all()
        assert solution.jumps is not None
        np.testing.assert_array_equal(solution.jumps, numpy_jumps(solution.positions))
        if not solution.jumps.shape[0]:
            continue
        found += 1
        first = int(solution.jumps[0])
        change = np.abs(solution.positions[first] - solution.positions[first - 1])
        with pytest.raises(JointJumpError, match=f"at {times[first]:.9g} s") as raised:
            robot.tree().solve_joints(robot.tool, target, times=times, strict=True)
        assert raised.value.joint == solution.joint_names[int(np.argmax(change))]
        # a looser threshold lets them pass
        loose = robot.tree().solve_joints(robot.tool, target, times=times, jump_threshold=1e3)
        assert loose.jumps is not None and loose.jumps.shape[0] == 0
    assert found


def test_a_long_gap_by_default_keeps_the_branch_between_samples():
    """The long gap of tests/test_solve_joints_paths.py without times: samples are added in
    the gap until the joint-interpolated tool stays within 0.1 mm of the target, and every
    given sample keeps the trajectory's branch."""
    robot = arm("UR5")
    model = robot.model()
    times = np.append(np.arange(20) * 0.21, 19 * 0.21 + 7.4)
    trajectory = swinging(np.asarray(robot.home), np.asarray(robot.swing), times)
    targets = frame_poses(model, robot.tool, trajectory)
    target = as_pose(targets, times)
    solution = robot.tree().solve_joints(robot.tool, target, seed=trajectory[0])
    given = np.abs(solution.seconds[:, None] - times[None, :]).min(axis=1) < 1e-9
    assert given.sum() == times.shape[0] and len(solution) > times.shape[0]
    np.testing.assert_allclose(solution.positions[given], trajectory, atol=1e-5)
    assert solution.all_reached and solution.jumps is not None and not solution.jumps.shape[0]
    # between samples, by Pinocchio: the target interpolated as the pose is (linear, slerp)
    fine = np.linspace(times[-2], times[-1], 400)
    between = np.stack([np.interp(fine, solution.seconds, column)
                        for column in solution.positions.T], axis=1)
    tools = frame_poses(model, robot.tool, between)
    start, end = targets[-2], targets[-1]
    for tool, moment in zip(tools, fine, strict=True):
        share = (moment - times[-2]) / (times[-1] - times[-2])
        point = (1 - share) * start.translation + share * end.translation
        turn = start.rotation @ pin.exp3(share * pin.log3(start.rotation.T @ end.rotation))
        assert np.linalg.norm(tool.translation - point) <= 1.01e-4
        assert np.linalg.norm(pin.log3(turn.T @ tool.rotation)) <= np.radians(0.1) * 1.01


def test_iiwa_seeded_near_its_joint_7_limit_reaches_every_sample():
    """The LBR iiwa 14 (ROS-Industrial) swinging with joint 7 up to 0.01 rad from its
    limit: tracked forward alone, the smallest motion walked it onto the limit and lost a
    sample; solved backwards from where the solver found its way back, none is lost."""
    iiwa = Arm("LBR iiwa 14", EXTRA / "kuka_experimental" / "lbr_iiwa_14_r820.urdf", "tool0",
               7, (0.0,) * 7, (0.4, 0.3, 0.3, 0.5, 0.4, 0.8, 0.6))
    model = iiwa.model()
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    swing = np.asarray(iiwa.swing)
    generator = np.random.default_rng(5)
    for _ in range(3):
        generator.uniform(lower + swing, upper - swing)
    home = generator.uniform(lower + swing, upper - swing)
    home[6] = upper[6] - swing[6] - 0.01
    times = np.arange(201) / 50.0
    trajectory = swinging(home, swing, times)
    targets = frame_poses(model, iiwa.tool, trajectory)
    solution = iiwa.tree().solve_joints(iiwa.tool, as_pose(targets, times), times=times,
                                        seed=trajectory[0])
    assert on_target(model, iiwa.tool, solution.positions, targets).all()
    assert within_limits(model, solution.positions)


def iiwa_near_its_joint_7_limit(seed: int) -> tuple[Arm, np.ndarray]:
    """The LBR iiwa 14 and a trajectory (201 samples at 50 Hz) swinging about a random home
    within its limits, joint 7 swinging up to within 0.05 rad of one of its limits (drawn
    by ``seed``)."""
    iiwa = Arm("LBR iiwa 14", EXTRA / "kuka_experimental" / "lbr_iiwa_14_r820.urdf", "tool0",
               7, (0.0,) * 7, (0.4, 0.3, 0.3, 0.5, 0.4, 0.8, 0.6))
    model = iiwa.model()
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    swing = np.asarray(iiwa.swing)
    generator = np.random.default_rng(seed)
    home = generator.uniform(lower + swing, upper - swing)
    side, gap = generator.integers(2), generator.uniform(0.0, 0.05)
    home[6] = upper[6] - swing[6] - gap if side else lower[6] + swing[6] + gap
    return iiwa, swinging(home, swing, np.arange(201) / 50.0)


@pytest.mark.parametrize(("seed", "jumps"), [(1778, 0), (2503, 0), (2581, 1), (2975, 1)])
def test_iiwa_reaches_the_samples_its_self_motion_lost_on_a_limit(seed, jumps):
    """Seeded with the trajectory's first configuration, the smallest motion took the iiwa
    along another self-motion than the trajectory's, onto a stretch that joint limits then
    closed: 64, 82, 85 and 85 samples were lost with joints on their limits. Solved again
    from the last solution moved along its self-motion, every sample is on its target
    (Pinocchio) within the limits; where that takes the other stretch, the step is a jump
    that ``jumps`` reports as numpy finds it."""
    iiwa, trajectory = iiwa_near_its_joint_7_limit(seed)
    model = iiwa.model()
    times = np.arange(201) / 50.0
    targets = frame_poses(model, iiwa.tool, trajectory)
    solution = iiwa.tree().solve_joints(iiwa.tool, as_pose(targets, times), times=times,
                                        seed=trajectory[0])
    assert on_target(model, iiwa.tool, solution.positions, targets).all()
    assert within_limits(model, solution.positions)
    assert solution.jumps is not None and solution.jumps.shape[0] == jumps
    np.testing.assert_array_equal(solution.jumps, numpy_jumps(solution.positions))


def m430_path(seed: int, narrow: bool) -> np.ndarray:
    """An M-430iA/2P trajectory (101 samples at 10 Hz) as ``far_paths_through_the_wrist``'s,
    its home drawn by ``seed``; ``narrow``: joint 5 within 0.01 rad of 0 there and swinging
    by 0.05 rad only."""
    robot = fanuc("m430ia2p")
    model = robot.model()
    lower = np.maximum(model.lowerPositionLimit, -np.pi)
    upper = np.minimum(model.upperPositionLimit, np.pi)
    swing = np.minimum(robot.swing, (upper - lower) / 4)
    generator = np.random.default_rng(seed)
    home = generator.uniform(lower + swing, upper - swing)
    home[4] = generator.uniform(-0.01, 0.01) if narrow else generator.uniform(-0.05, 0.05)
    if narrow:
        swing[4] = 0.05
    return swinging(home, swing, np.arange(101) / 10.0)


@pytest.mark.parametrize(("seed", "narrow"), [(249, False), (179, True)])
def test_m430_seeded_through_a_singular_crossing_keeps_its_branch(seed, narrow):
    """The seeded M-430iA/2P of issue 44: the path comes within a singular configuration away
    from the wrist's (the Jacobian's smallest singular value 1e-4 at samples 57 and 59, joint
    5 at -0.32 and -0.05 rad there), turning back from it (seed 249) or crossing it (179).
    Carried on along the line through the last two solutions, the prediction lay 0.01 rad
    from the path, past the gap to the other branch: the solver took it, which ran joint 1
    onto its limit and lost the last 28 and 19 samples. Every sample is on its target
    (Pinocchio) and on the trajectory's own branch, within 2e-3 rad of its joints (the other
    branch lay 3e-3 to 4e-3 rad away at the singular configuration, over 0.1 rad five samples
    on); without a seed every sample is reached too."""
    robot = fanuc("m430ia2p")
    model = robot.model()
    times = np.arange(101) / 10.0
    trajectory = m430_path(seed, narrow)
    targets = frame_poses(model, robot.tool, trajectory)
    target = as_pose(targets, times)
    unseeded = robot.tree().solve_joints(robot.tool, target, times=times)
    assert on_target(model, robot.tool, unseeded.positions, targets).all()
    solution = robot.tree().solve_joints(robot.tool, target, times=times, seed=trajectory[0])
    assert on_target(model, robot.tool, solution.positions, targets).all()
    np.testing.assert_allclose(solution.positions, trajectory, rtol=0.0, atol=2e-3)
