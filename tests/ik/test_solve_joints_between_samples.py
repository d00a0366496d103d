"""``solve_joints`` between its samples: without times the samples are dense enough that the
joints moving linearly from one to the next keep the tool on its target (``path_tolerance``),
and ``JointSolution.path_deviation`` says how far it strays at given times. Every number is
checked with Pinocchio called directly on the URDF, on a fine grid of joint-interpolated
configurations."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pinocchio as pin
import pytest

from ik_paths import arm, as_pose, errors, frame_poses, swinging
from pinframes import FrameTree, Pose
from pinframes.errors import ArgumentTypeError, InvalidDataError

SEAM_TIMES = np.array([0.0, 31.0, 62.0])  # s: a straight seam given by its 3 keyframes
FINE = np.linspace(0.0, 62.0, 3101)  # s, every 20 ms


@pytest.fixture(scope="module")
def ur5_seam() -> tuple[pin.Model, FrameTree, Pose, pin.SE3, np.ndarray]:
    """The UR5 and a straight seam of 0.5 m along y in 62 s, the tool's axes fixed."""
    ur5 = arm("UR5")
    model = ur5.model()
    home = np.asarray(ur5.home)
    start = frame_poses(model, ur5.tool, home[None])[0]
    origins = start.translation + np.outer([-0.5, 0.0, 0.5], [0.0, 0.5, 0.0])
    target = Pose(origins, np.repeat(start.rotation[None], 3, axis=0), times=SEAM_TIMES)
    return model, ur5.tree(), target, start, home


def seam_strays(model: pin.Model, start: pin.SE3, seconds: np.ndarray, positions: np.ndarray,
                times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per time of ``times``, the distance (m) and angle (rad) of the tool0 from the seam,
    the joints linear between the solution's samples, by Pinocchio."""
    between = np.stack([np.interp(times, seconds, column) for column in positions.T], axis=1)
    tools = frame_poses(model, "tool0", between)
    wanted = start.translation + np.outer(times / 62.0 - 0.5, [0.0, 0.5, 0.0])
    distances = np.linalg.norm([tool.translation for tool in tools] - wanted, axis=1)
    angles = np.array([np.linalg.norm(pin.log3(start.rotation.T @ tool.rotation))
                       for tool in tools])
    return distances, angles


def test_default_samples_keep_the_joint_interpolated_tool_on_the_seam(ur5_seam):
    model, tree, target, start, home = ur5_seam
    sparse = tree.solve_joints("tool0", target, seed=home[:6], path_tolerance=None)
    dense = tree.solve_joints("tool0", target, seed=home[:6])
    assert len(sparse) == 3 and sparse.all_reached and dense.all_reached
    before, _ = seam_strays(model, start, sparse.seconds, sparse.positions, FINE)
    after, turned = seam_strays(model, start, dense.seconds, dense.positions, FINE)
    assert before.max() > 0.01  # 14.6 mm off the seam between 3 samples
    assert after.max() <= 1e-4 and turned.max() <= math.radians(0.1)
    # the keyframes stay samples; what was added lies between them, each sample on target
    assert set(SEAM_TIMES).issubset(dense.seconds) and 3 < len(dense) < 100
    on_seam, _ = seam_strays(model, start, dense.seconds, dense.positions, dense.seconds)
    assert on_seam.max() <= 1e-6
    # the deviation it reports is the one Pinocchio measures (the fine grid's is at most a
    # little larger than at the midpoints and quarter points)
    assert dense.path_deviation.max() == pytest.approx(after.max(), rel=0.05)
    assert sparse.path_deviation[0] == 0.0
    assert sparse.path_deviation.max() == pytest.approx(before.max(), rel=0.05)


def test_given_times_are_kept_and_their_deviation_reported(ur5_seam):
    model, tree, target, start, home = ur5_seam
    times = np.linspace(0.0, 62.0, 7)
    solution = tree.solve_joints("tool0", target, times=times, seed=home[:6])
    np.testing.assert_allclose(solution.seconds, times)
    for index in range(1, 7):  # each interval measured alone, on a fine grid
        inside = np.linspace(times[index - 1], times[index], 41)
        distances, angles = seam_strays(model, start, solution.seconds, solution.positions,
                                        inside)
        assert solution.path_deviation[index] == pytest.approx(distances.max(), rel=0.05)
        assert solution.path_angle_deviation[index] <= angles.max() * 1.05 + 1e-9


def test_a_coarser_tolerance_needs_fewer_samples(ur5_seam):
    model, tree, target, start, home = ur5_seam
    coarse = tree.solve_joints("tool0", target, seed=home[:6], path_tolerance=(1e-3, 0.01))
    fine = tree.solve_joints("tool0", target, seed=home[:6], path_tolerance=1e-5)
    assert len(coarse) < len(fine)
    for solution, length in ((coarse, 1e-3), (fine, 1e-5)):
        distances, _ = seam_strays(model, start, solution.seconds, solution.positions, FINE)
        assert distances.max() <= length


def test_process_and_clearance_sample_the_dense_trajectory(ur5_seam):
    """A tree moving by the solution: its queries' default times are the solution's."""
    _, tree, target, _, home = ur5_seam
    solution = tree.solve_joints("tool0", target, seed=home[:6])
    moving = tree.copy()
    moving.set_joint_trajectory(solution.seconds, solution.positions,
                                joint_names=solution.joint_names)
    moving.add("seam", "floor", target)
    process = moving.weld_process("tool0", "seam")
    np.testing.assert_allclose(process.seconds, solution.seconds)
    clearance = moving.clearance("wrist_3_link", "base_link")
    assert len(clearance.distance) == len(solution)


@pytest.mark.parametrize("bad", [0.0, -1e-4, "0.1", (1e-4,), (1e-4, math.inf), True])
def test_a_bad_path_tolerance_names_the_field(ur5_seam, bad):
    _, tree, target, _, home = ur5_seam
    with pytest.raises((InvalidDataError, ArgumentTypeError), match="path_tolerance"):
        tree.solve_joints("tool0", target, seed=home[:6], path_tolerance=bad)


def test_the_deviation_reported_is_pinocchio_s_at_midpoints_and_quarter_points():
    """A moving, turning target at given times: each interval's deviation is the one
    Pinocchio measures at its midpoint, the joints linear between the solution's samples
    and the target interpolated as the pose is (linear, slerp); where the midpoint strays
    past a quarter of the default tolerance (0.1 mm, 0.1 degree), the largest of the
    midpoint and the quarter points."""
    ur5 = arm("UR5")
    model = ur5.model()
    times = np.array([0.0, 0.01, 0.02, 0.4, 0.8, 0.81, 1.2, 1.6, 1.61])  # s: short, long
    trajectory = swinging(np.asarray(ur5.home), np.asarray(ur5.swing), times)
    keyframes = frame_poses(model, ur5.tool, trajectory)
    solution = ur5.tree().solve_joints(ur5.tool, as_pose(keyframes, times), times=times,
                                       seed=trajectory[0])
    assert solution.all_reached

    def strays(share: float) -> tuple[np.ndarray, np.ndarray]:
        """Per interval, Pinocchio's position and orientation error at ``share`` of it."""
        between = (1 - share) * solution.positions[:-1] + share * solution.positions[1:]
        wanted = [pin.SE3(start.rotation @ pin.exp3(share * pin.log3(
                              start.rotation.T @ end.rotation)),
                          (1 - share) * start.translation + share * end.translation)
                  for start, end in itertools.pairwise(keyframes)]
        return errors(frame_poses(model, ur5.tool, between), wanted)

    position, orientation = strays(0.5)
    near = (position > 0.25e-4) | (orientation > 0.25 * math.radians(0.1))
    assert near.any() and not near.all()  # both rules are exercised
    for share in (0.25, 0.75):
        apart, turned = strays(share)
        position[near] = np.maximum(position[near], apart[near])
        orientation[near] = np.maximum(orientation[near], turned[near])
    np.testing.assert_allclose(solution.path_deviation, np.append(0.0, position),
                               rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(solution.path_angle_deviation, np.append(0.0, orientation),
                               rtol=1e-9, atol=1e-15)
