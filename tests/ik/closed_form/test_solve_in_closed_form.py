"""``solve_joints`` on arms of a closed-form family: a whole path kept on a requested branch
(flags or a KUKA Status), the default branch of the seed, ``JointSolution.configurations``,
an arm riding on a moving frame with a tool on its flange; checked with Pinocchio."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from closed_form_arms import (
    KR6R900,
    arm_model,
    arm_tree,
    pose_errors,
    targets_pose,
    tool_pose,
    ur_description_tree,
    ur_description_urdf,
)
from ik_paths import example_robot
from pinframes import ArgumentTypeError, FrameTree, JointError, Pose

HOME = np.array([0.3, -1.2, 1.5, 0.4, 0.8, 0.2])
TIMES = np.linspace(0.0, 4.0, 201)


def path_configurations(home: np.ndarray) -> np.ndarray:
    return home + 0.3 * np.sin(np.outer(TIMES, [0.3, 0.5, 0.7, 0.9, 1.1, 1.3]))


def path_targets(urdf, home):
    model = arm_model(urdf)
    configurations = path_configurations(home)
    placements = [tool_pose(model, q) for q in configurations]
    pose = Pose(np.array([p.translation for p in placements]),
                np.array([p.rotation for p in placements]), times=TIMES)
    return model, configurations, placements, pose


def assert_on_targets(model, positions, placements, tolerance=1e-9):
    for q, target in zip(positions, placements, strict=True):
        position, orientation = pose_errors(model, q, target)
        assert position <= tolerance and orientation <= tolerance


def test_the_seed_s_branch_is_tracked_in_closed_form():
    model, configurations, placements, pose = path_targets(KR6R900, HOME)
    solution = arm_tree(KR6R900).solve_joints("tool0", pose, relative_to="floor",
                                              seed=configurations[0])
    assert solution.all_reached
    np.testing.assert_allclose(solution.positions, configurations, atol=1e-9)
    assert_on_targets(model, solution.positions, placements)
    assert solution.configurations is not None and len(set(solution.configurations)) == 1


@pytest.mark.parametrize("configuration", ["front,up,flip", "flip , UP,front"])
def test_a_requested_configuration_is_kept_along_the_whole_path(configuration):
    model, configurations, placements, pose = path_targets(KR6R900, HOME)
    solution = arm_tree(KR6R900).solve_joints("tool0", pose, relative_to="floor",
                                              configuration=configuration)
    assert solution.all_reached
    assert_on_targets(model, solution.positions, placements)
    assert set(solution.configurations) == {"front,up,flip"}  # the path's own: noflip
    assert np.abs(solution.positions - configurations).max() > 0.5  # not the path's own
    # continuous: no joint steps further than a few times the path's own steps
    assert np.abs(np.diff(solution.positions, axis=0)).max() <= 0.1


def test_a_kuka_status_is_kept_along_the_whole_path():
    model, configurations, placements, pose = path_targets(KR6R900, HOME)
    tree = arm_tree(KR6R900)
    solutions = tree.ik_solutions("tool0", pose, relative_to="floor", whole_turns=False)
    status = solutions.kuka_status
    own = status[0][np.argmin(np.abs(solutions.positions[0] - configurations[0]).max(axis=1))]
    everywhere = [value for value in range(8) if value != own
                  and (status == value).any(axis=1).all()]
    assert everywhere
    solution = tree.solve_joints("tool0", pose, relative_to="floor",
                                 configuration=everywhere[0])
    assert solution.all_reached
    assert_on_targets(model, solution.positions, placements)
    back = np.char.startswith(solution.configurations.astype(str), "back")
    assert (back == bool(everywhere[0] & 1)).all()
    assert ((solution.positions[:, 4] <= 0) == bool(everywhere[0] & 4)).all()


def test_a_configuration_the_path_leaves_holds_and_is_not_reached():
    """Joint 2 of the KR6 stops at 45 degrees: the back branches of poses in front of
    the robot need it further, so some samples of the back branch cannot be reached."""
    model, _, placements, pose = path_targets(KR6R900, HOME)
    solutions = arm_tree(KR6R900).ik_solutions("tool0", pose, relative_to="floor",
                                               whole_turns=False)
    missing = [name for column, name in enumerate(solutions.configurations)
               if not solutions.valid[:, column].all()]
    assert missing
    solution = arm_tree(KR6R900).solve_joints("tool0", pose, relative_to="floor",
                                              configuration=missing[0])
    reached = solution.reached
    column = list(solutions.configurations).index(missing[0])
    np.testing.assert_array_equal(reached, solutions.valid[:, column])
    assert_on_targets(model, solution.positions[reached],
                      [placement for placement, hit in zip(placements, reached, strict=True)
                       if hit])


def test_configuration_errors():
    _, _, _, pose = path_targets(KR6R900, HOME)
    tree = arm_tree(KR6R900)
    with pytest.raises(ArgumentTypeError, match=r"one of up / down"):
        tree.solve_joints("tool0", pose, relative_to="floor", configuration="front,noflip")
    with pytest.raises(ArgumentTypeError, match=r"0\.\.7"):
        tree.solve_joints("tool0", pose, relative_to="floor", configuration=9)
    with pytest.raises(ArgumentTypeError, match="free_axis="):
        tree.solve_joints("tool0", pose, relative_to="floor", configuration="front,up,flip",
                          free_axis="z")
    panda = example_robot("panda.urdf")
    with pytest.raises(JointError, match="six joints"):
        arm_tree(panda).solve_joints("panda_hand", "floor", configuration="front,up,flip")


def test_an_arm_on_a_moving_carriage_with_a_torch_on_its_flange():
    """The UR5 rides a carriage that moves 0.4 m and turns 30 degrees; a torch sits 0.15 m
    out from tool0, tilted. Every solution of ik_solutions puts the torch on its target,
    checked with Pinocchio: carriage pose by hand, times the URDF's tool0, times the torch."""
    urdf = example_robot("ur5_robot.urdf")
    model = arm_model(urdf)
    torch = pin.SE3(pin.utils.rotate("y", 0.4), np.array([0.0, 0.05, 0.15]))
    tree = arm_tree_on(urdf, torch)
    home = np.array([0.0, -1.2, 1.5, -1.8, -1.571, 0.3])
    configurations = path_configurations(home)
    carriage = [pin.SE3(pin.utils.rotate("z", np.pi / 6 * t / 4.0),
                        np.array([0.4 * t / 4.0, 0.0, 0.0])) for t in TIMES]
    targets = [c * tool_pose(model, q) * torch for c, q in zip(carriage, configurations,
                                                                   strict=True)]
    pose = Pose(np.array([p.translation for p in targets]),
                np.array([p.rotation for p in targets]), times=TIMES)
    solutions = tree.ik_solutions("torch", pose, relative_to="floor")
    assert solutions.arm.family == "ur"
    for index in range(0, 201, 40):
        valid = np.flatnonzero(solutions.valid[index])
        assert valid.shape[0] >= 8
        for branch in valid:
            placed = carriage[index] * tool_pose(model, solutions.positions[index, branch]) \
                * torch
            error = pin.log6(placed.inverse() * targets[index]).vector
            assert np.linalg.norm(error) <= 1e-9
    solution = tree.solve_joints("torch", pose, relative_to="floor", seed=configurations[0])
    assert solution.all_reached
    np.testing.assert_allclose(solution.positions, configurations, atol=1e-8)


def arm_tree_on(urdf, torch: pin.SE3) -> FrameTree:
    """The arm attached to a carriage moving on the floor, a torch fixed to tool0."""
    tree = FrameTree("floor")
    tree.add("carriage", "floor", Pose([[0.0, 0.0, 0.0], [0.4, 0.0, 0.0]],
                                       [[0, 0, 0, 1], [0, 0, np.sin(np.pi / 12),
                                                       np.cos(np.pi / 12)]], times=[0.0, 4.0]))
    tree.attach_urdf(urdf, "carriage")
    quaternion = pin.Quaternion(torch.rotation).coeffs()
    tree.add("torch", "tool0", Pose(torch.translation, quaternion))
    return tree


STRAIGHT = 1e-7
"""The sine of joint 5 below which the wrist counts as straight (docs/closed-form-ik.md)."""


def straight_wrist_arm(arm: str, scratch: Path) -> tuple[pin.Model, FrameTree, np.ndarray, int]:
    """Pinocchio's model, the tree, a configuration with joint 5 at 0 (the wrist straight:
    axis 6 in line with axis 4, on a UR-type arm with axes 2 to 4) and the wrist joint the
    closed form takes as given there (joint 4; UR-type: joint 6)."""
    if arm == "ur5e":
        return (arm_model(ur_description_urdf("ur5e", scratch)), ur_description_tree("ur5e"),
                np.array([0.3, -1.2, 1.5, -1.8, 0.0, 0.5]), 5)
    return arm_model(KR6R900), arm_tree(KR6R900), np.array([0.3, -1.2, 1.5, 0.4, 0.0, 0.2]), 3


def straight_wrist_bound(model: pin.Model, q: np.ndarray) -> tuple[float, float]:
    """Metres and radians by which a solution at a straight wrist may miss its pose: pi
    times :data:`STRAIGHT` radians, times the tool's distance from axis 5 in metres."""
    data = model.createData()
    pin.forwardKinematics(model, data, q)
    reach = np.linalg.norm(tool_pose(model, q).translation - data.oMi[5].translation)
    return float(reach) * np.pi * STRAIGHT + 1e-9, np.pi * STRAIGHT


@pytest.mark.parametrize("arm", ["kr6r900sixx", "ur5e"])
def test_ik_solutions_give_the_free_wrist_joint_0_at_a_straight_wrist(arm, tmp_path):
    """Only the sum of joints 4 and 6 (UR-type: of 6 and the parallel joints) is fixed at a
    straight wrist: each solution there has joint 4 (UR-type: joint 6) at 0 and reaches the
    pose (Pinocchio's forward kinematics)."""
    model, tree, q, free = straight_wrist_arm(arm, tmp_path)
    target = tool_pose(model, q)
    solutions = tree.ik_solutions("tool0", targets_pose([target]), relative_to="floor",
                                  whole_turns=False)
    found = solutions.positions[0][solutions.valid[0]]
    straight = found[np.abs(np.sin(found[:, 4])) < STRAIGHT]
    assert straight.shape[0] >= 2
    metres, radians = straight_wrist_bound(model, q)
    for positions in straight:
        assert positions[free] == 0.0
        position, orientation = pose_errors(model, positions, target)
        assert position <= metres and orientation <= radians, (positions, position, orientation)
    if arm == "kr6r900sixx":  # axes 4 and 6 in line, the same way: joint 6 takes the sum
        np.testing.assert_allclose(np.cos(straight[:, 5] - q[3] - q[5]), 1.0, atol=1e-12)


@pytest.mark.parametrize("arm", ["kr6r900sixx", "ur5e"])
def test_solve_joints_holds_the_free_wrist_joint_along_a_straight_wrist(arm, tmp_path):
    """A path whose wrist stays straight: joint 4 (UR-type: 6) keeps the seed's value at
    every sample (each sample holds it where the one before left it), the others follow."""
    model, tree, home, free = straight_wrist_arm(arm, tmp_path)
    configurations = home + 0.2 * np.sin(np.outer(TIMES, [0.3, 0.5, 0.7, 0.9, 0.0, 1.3]))
    placements = [tool_pose(model, q) for q in configurations]
    pose = Pose(np.array([p.translation for p in placements]),
                np.array([p.rotation for p in placements]), times=TIMES)
    seed = configurations[0] + np.where(np.arange(6) == free, 0.7, 0.0)
    solution = tree.solve_joints("tool0", pose, relative_to="floor", seed=seed)
    assert solution.all_reached
    np.testing.assert_array_equal(solution.positions[:, free], seed[free])
    assert (np.abs(np.sin(solution.positions[:, 4])) < STRAIGHT).all()
    for q, target in zip(solution.positions, placements, strict=True):
        metres, radians = straight_wrist_bound(model, q)
        position, orientation = pose_errors(model, q, target)
        assert position <= metres and orientation <= radians
