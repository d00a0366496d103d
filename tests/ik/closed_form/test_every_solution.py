"""Every solution of ``FrameTree.ik_solutions`` on the arms of ROS-Industrial and Universal
Robots (example-robot-data's and every type of Universal Robots' own xacro description):
each checked with Pinocchio's forward kinematics on the URDF, and none missed against a
damped least-squares solver started from many random configurations."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from closed_form_arms import (
    KR6R900,
    UR_TYPES,
    arm_model,
    arm_tree,
    lowest_in_range,
    numeric_solutions,
    pose_errors,
    random_configurations,
    ros_industrial_arms,
    targets_pose,
    tool_pose,
    universal_robots,
    ur_description_tree,
    ur_description_urdf,
)
from ik_paths import example_robot
from pinframes import FrameTree

EXACT = 1e-9  # metres and radians: every closed-form solution reaches its pose this close
SAME = 1e-6  # radians: a numeric solution and a closed-form one are the same solution


def check_every_solution(urdf: Path, poses: int, starts: int, seed: int = 7,
                         tree: FrameTree | None = None) -> str:
    """Check ``tree``'s solutions (default: ``urdf`` attached) with Pinocchio on ``urdf``;
    the family the arm is recognised as."""
    model = arm_model(urdf)
    rng = np.random.default_rng(seed)
    configurations = random_configurations(model, poses, rng)
    targets = [tool_pose(model, q) for q in configurations]
    solutions = (tree or arm_tree(urdf)).ik_solutions("tool0", targets_pose(targets),
                                                      relative_to="floor")
    lower, upper = model.lowerPositionLimit, model.upperPositionLimit
    assert solutions.positions.shape[0] == poses
    assert solutions.configurations.shape == (solutions.positions.shape[1],)
    for index, (q, target) in enumerate(zip(configurations, targets, strict=True)):
        found = solutions.positions[index][solutions.valid[index]]
        assert np.isnan(solutions.positions[index][~solutions.valid[index]]).all()
        for positions in found:
            position, orientation = pose_errors(model, positions, target)
            assert position <= EXACT and orientation <= EXACT, (urdf.name, positions)
            assert np.all(positions >= lower - 1e-12) and np.all(positions <= upper + 1e-12)
        distinct = np.unique(np.round(found, 6), axis=0)
        # the pose's own configuration is among them
        assert np.abs(found - q).max(axis=1).min() <= SAME, urdf.name
        # and every solution a numeric solver finds from many starts
        numeric = numeric_solutions(model, target,
                                    random_configurations(model, starts, rng))
        assert numeric, urdf.name
        for solution in numeric:
            gaps = np.abs(lowest_in_range(model, found) - lowest_in_range(model,
                                                                          solution[None]))
            gaps = np.minimum(gaps, 2 * np.pi - gaps)
            assert gaps.max(axis=1).min() <= SAME, (urdf.name, solution)
        assert distinct.shape[0] == found.shape[0]  # no branch repeats another
    return str(solutions.arm.family)


@pytest.mark.parametrize("urdf", [KR6R900, "ur5"], ids=["kr6r900sixx", "ur5"])
def test_every_solution_reaches_its_pose_and_none_is_missed(urdf):
    path = example_robot("ur5_robot.urdf") if urdf == "ur5" else urdf
    check_every_solution(path, poses=2, starts=40)


@pytest.mark.slow
@pytest.mark.parametrize("urdf", ros_industrial_arms(), ids=lambda path: path.stem)
def test_every_ros_industrial_arm(urdf):
    check_every_solution(urdf, poses=4, starts=150)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ur3", "ur5", "ur10"])
def test_every_universal_robot(name):
    urdf = {path.stem.split("_")[0]: path for path in universal_robots()}[name]
    check_every_solution(urdf, poses=4, starts=150)


def test_universal_robots_own_ur20_description(tmp_path):
    assert check_every_solution(ur_description_urdf("ur20", tmp_path), poses=2, starts=40,
                                tree=ur_description_tree("ur20")) == "ur"


@pytest.mark.slow
@pytest.mark.parametrize("ur_type", UR_TYPES)
def test_every_type_of_universal_robots_own_description(ur_type, tmp_path):
    """Each type's nominal kinematics (config/<type>/default_kinematics.yaml) expanded from
    ``ur.urdf.xacro``: UR-type, every solution on its pose, none missed."""
    assert check_every_solution(ur_description_urdf(ur_type, tmp_path), poses=4, starts=150,
                                tree=ur_description_tree(ur_type)) == "ur"


def test_a_pose_out_of_reach_has_no_solution():
    model = arm_model(KR6R900)
    far = tool_pose(model, np.zeros(6))
    far.translation = far.translation + np.array([5.0, 0.0, 0.0])
    solutions = arm_tree(KR6R900).ik_solutions("tool0", targets_pose([far]),
                                               relative_to="floor")
    assert not solutions.valid.any() and np.isnan(solutions.positions).all()


def test_without_whole_turns_each_branch_appears_once():
    model = arm_model(KR6R900)
    target = tool_pose(model, np.array([0.3, -1.2, 1.5, 0.4, 0.8, 0.2]))
    tree = arm_tree(KR6R900)
    every = tree.ik_solutions("tool0", targets_pose([target]), relative_to="floor")
    once = tree.ik_solutions("tool0", targets_pose([target]), relative_to="floor",
                             whole_turns=False)
    assert once.positions.shape[1] == 8 and list(once.configurations[:2]) == [
        "front,up,noflip", "front,up,flip"]
    # joints 4 and 6 turn +-350 degrees: two values each within the range
    assert every.positions.shape[1] == 32 and every.configurations[1] == "front,up,noflip/01"
    assert every.valid.sum() > once.valid.sum()


def test_the_columns_follow_the_joints_as_named():
    model = arm_model(KR6R900)
    target = targets_pose([tool_pose(model, np.array([0.3, -1.2, 1.5, 0.4, 0.8, 0.2]))])
    tree = arm_tree(KR6R900)
    names = [f"joint_a{index}" for index in range(6, 0, -1)]
    reversed_order = tree.ik_solutions("tool0", target, relative_to="floor", joints=names)
    plain = tree.ik_solutions("tool0", target, relative_to="floor")
    assert reversed_order.joint_names == tuple(names)
    np.testing.assert_array_equal(reversed_order.positions[..., ::-1], plain.positions)
    np.testing.assert_array_equal(reversed_order.configurations, plain.configurations)
