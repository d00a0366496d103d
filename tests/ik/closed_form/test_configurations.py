"""The configuration flags of every solution against their geometric definitions, measured
with Pinocchio's joint axes on the URDF, and KUKA's Status from KUKA's own definition."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from closed_form_arms import (
    ARMS,
    IRB2400,
    IRB2600,
    KR6R900,
    UR_TYPES,
    arm_model,
    arm_tree,
    joint_axes,
    meeting_point,
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
from pinframes.kinematics.closed_form.configurations import abb_cfx


def wrist_point(model: pin.Model, q: np.ndarray, family: str) -> np.ndarray:
    """OPW: where axes 4 and 5 meet (the wrist centre); UR-type: axes 5 and 6."""
    directions, points = joint_axes(model, q)
    first = 3 if family == "opw" else 4
    return meeting_point(directions[first], points[first], directions[first + 1],
                         points[first + 1])


def geometric_flags(model: pin.Model, q: np.ndarray, family: str) -> str:
    """The flags of ``q`` by their definitions (docs/closed-form-ik.md)."""
    zero = np.zeros(6)
    directions0, points0 = joint_axes(model, zero)
    across0 = np.cross(directions0[1], directions0[0])
    reach = float(np.dot(wrist_point(model, zero, family) - points0[0], across0))
    sign = 1.0 if reach >= 0.0 else -1.0
    directions, points = joint_axes(model, q)
    forward = sign * np.cross(directions[1], directions[0])
    forward /= np.linalg.norm(forward)
    wrist = wrist_point(model, q, family)
    back = np.dot(wrist - points[0], forward) < 0.0
    carried = wrist if family == "opw" else points[3]  # a UR-type arm: axis 4
    data = model.createData()
    pin.forwardKinematics(model, data, q)
    up_axis = data.oMi[1].rotation[:, 2]  # the z of the frame joint 1 turns in
    up = directions[0] if np.dot(up_axis, directions[0]) >= 0 else -directions[0]
    above = np.cross(forward, up)
    up = np.dot(np.cross(carried - points[1], points[2] - points[1]), above) > 0.0
    flip = q[4] <= 0.0
    return ",".join(["back" if back else "front", "up" if up else "down",
                     "flip" if flip else "noflip"])


def check_flags(urdf: Path, poses: int, tree: FrameTree | None = None) -> None:
    """The flags of ``tree``'s solutions (default: ``urdf`` attached), measured with
    Pinocchio on ``urdf``."""
    model = arm_model(urdf)
    rng = np.random.default_rng(3)
    configurations = random_configurations(model, poses, rng)
    solutions = (tree or arm_tree(urdf)).ik_solutions(
        "tool0", targets_pose([tool_pose(model, q) for q in configurations]),
        relative_to="floor", whole_turns=False)
    family = solutions.arm.family
    # on these arms the wrist is straight at joint 5 zero: axis 6 along axis 4 (UR: 2)
    directions, _ = joint_axes(model, np.zeros(6))
    assert abs(abs(np.dot(directions[5], directions[3 if family == "opw" else 1])) - 1) < 1e-12
    for index in range(poses):
        for branch in np.flatnonzero(solutions.valid[index]):
            expected = geometric_flags(model, solutions.positions[index, branch], family)
            assert solutions.configurations[branch] == expected, (urdf.name, branch)


@pytest.mark.parametrize("urdf", [KR6R900, IRB2400, "ur5"], ids=["kr6r900sixx", "irb2400",
                                                               "ur5"])
def test_the_flags_are_their_geometric_definitions(urdf):
    check_flags(example_robot("ur5_robot.urdf") if urdf == "ur5" else urdf, poses=3)


@pytest.mark.slow
@pytest.mark.parametrize("urdf", ros_industrial_arms() + universal_robots(),
                         ids=lambda path: path.stem)
def test_the_flags_of_every_arm(urdf):
    check_flags(urdf, poses=6)


@pytest.mark.slow
@pytest.mark.parametrize("ur_type", UR_TYPES)
def test_the_flags_of_every_type_of_universal_robots_own_description(ur_type, tmp_path):
    check_flags(ur_description_urdf(ur_type, tmp_path), poses=6,
                tree=ur_description_tree(ur_type))


def stretched_angle(model: pin.Model) -> float:
    """KUKA's angle of A3 at which the wrist centre lies on the extension of the line from
    A2 to A3: the farthest from axis 2 (a grid, then golden sections, with Pinocchio)."""
    def reach(angle: float) -> float:
        q = np.zeros(6)
        q[2] = angle
        directions, points = joint_axes(model, q)
        offset = wrist_point(model, q, "opw") - points[1]
        return float(np.linalg.norm(np.cross(offset, directions[1])))

    grid = np.linspace(-np.pi, np.pi, 721)
    best = grid[int(np.argmax([reach(angle) for angle in grid]))]
    low, high = best - 0.01, best + 0.01
    ratio = (np.sqrt(5) - 1) / 2
    for _ in range(60):
        a, b = high - ratio * (high - low), low + ratio * (high - low)
        if reach(a) > reach(b):
            high = b
        else:
            low = a
    return 0.5 * (low + high)


def test_kuka_status_is_kukas_definition():
    """Bit 0: the wrist centre at negative x in the A1 coordinate system (link_1's axes);
    bit 1: A3 at or above its stretched angle; bit 2: A5 at or below 0."""
    model = arm_model(KR6R900)
    data = model.createData()
    rng = np.random.default_rng(11)
    configurations = random_configurations(model, 4, rng)
    solutions = arm_tree(KR6R900).ik_solutions(
        "tool0", targets_pose([tool_pose(model, q) for q in configurations]),
        relative_to="floor")
    phi = stretched_angle(model)
    status = solutions.kuka_status
    checked = 0
    for index in range(4):
        for branch in np.flatnonzero(solutions.valid[index]):
            q = solutions.positions[index, branch]
            pin.forwardKinematics(model, data, q)
            centre = data.oMi[1].actInv(wrist_point(model, q, "opw"))
            expected = (int(centre[0] < 0) + 2 * int(q[2] >= phi) + 4 * int(q[4] <= 0))
            assert status[index, branch] == expected
            checked += 1
    assert checked > 8 and (status[~solutions.valid] == -1).all()


def test_kuka_turn_and_abb_quadrants_are_the_signs_and_quadrants_of_the_joints():
    model = arm_model(KR6R900)
    target = tool_pose(model, np.array([0.3, -1.2, 1.5, 0.4, 0.8, 0.2]))
    solutions = arm_tree(KR6R900).ik_solutions("tool0", targets_pose([target]),
                                               relative_to="floor")
    valid = solutions.valid[0]
    positions = solutions.positions[0][valid]
    turn = sum((positions[:, joint] < 0).astype(int) << joint for joint in range(6))
    np.testing.assert_array_equal(solutions.kuka_turn[0][valid], turn)
    assert (solutions.kuka_turn[0][~valid] == -1).all()
    degrees = np.degrees(positions[:, [0, 3, 5]])
    np.testing.assert_array_equal(solutions.abb_quadrants[0][valid], degrees // 90)


def abb_cfx_by_definition(model: pin.Model, q: np.ndarray) -> int:
    """ABB's cfx of ``q`` by its table, measured with Pinocchio: 4 where the wrist centre is
    behind axis 1 (at negative x in link_1's axes, which turn with axis 1), 2 where it is
    behind the lower arm (the line from axis 2 to axis 3, upright at joint 2 zero: behind
    is link_1's -x side there, turned with joint 2), 1 where axis 5 is negative."""
    def measured(q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The wrist centre in link_1's axes, and across the lower arm: the wrist centre's
        offset and link_1's x (both in the world)."""
        directions, points = joint_axes(model, q)
        data = model.createData()
        pin.forwardKinematics(model, data, q)
        wrist = wrist_point(model, q, "opw")
        across = np.cross(directions[1], points[2] - points[1])
        return (data.oMi[1].actInv(wrist), (wrist - points[1]) @ across,
                data.oMi[1].rotation[:, 0] @ across)

    _, _, forward_at_zero = measured(np.zeros(6))  # the lower arm upright
    in_link_1, across_lower_arm, _ = measured(q)
    return (4 * int(in_link_1[0] < 0.0) + 2 * int(across_lower_arm * forward_at_zero < 0.0)
            + int(q[4] < 0.0))


def check_abb_cfx(urdf: Path, poses: int) -> None:
    model = arm_model(urdf)
    directions, points = joint_axes(model, np.zeros(6))
    lower_arm = points[2] - points[1]
    # ABB's premise: at zero the lower arm stands upright, along axis 1, the wrist centre
    # in front of axis 1 and of the lower arm
    assert np.linalg.norm(np.cross(lower_arm, directions[0])) < 1e-9, urdf.name
    assert abb_cfx_by_definition(model, np.zeros(6)) == 0, urdf.name
    rng = np.random.default_rng(5)
    configurations = random_configurations(model, poses, rng)
    solutions = arm_tree(urdf).ik_solutions(
        "tool0", targets_pose([tool_pose(model, q) for q in configurations]),
        relative_to="floor", whole_turns=False)
    cfx = solutions.abb_cfx
    for index in range(poses):
        for branch in np.flatnonzero(solutions.valid[index]):
            q = solutions.positions[index, branch]
            assert cfx[index, branch] == abb_cfx_by_definition(model, q), (urdf.name, q)
    assert (cfx[~solutions.valid] == -1).all()
    # beyond the limits too (an ABB's joint 3 range keeps the wrist in front of the lower
    # arm), over every joint's whole turn
    anywhere = rng.uniform(-np.pi, np.pi, size=(64, 6))
    values = abb_cfx(solutions.arm, anywhere)
    assert [int(value) for value in values] == [abb_cfx_by_definition(model, q)
                                                for q in anywhere], urdf.name
    assert set(values) == set(range(8))


@pytest.mark.parametrize("urdf", [IRB2400, IRB2600], ids=lambda path: path.stem)
def test_abb_cfx_is_abbs_definition(urdf):
    check_abb_cfx(urdf, poses=4)


@pytest.mark.slow
@pytest.mark.parametrize("urdf", sorted(ARMS.glob("abb*/*.urdf")), ids=lambda path: path.stem)
def test_abb_cfx_of_every_abb_arm(urdf):
    check_abb_cfx(urdf, poses=8)


def test_abb_cfx_counts_a_straight_wrist_as_positive_where_the_flags_say_flip():
    model = arm_model(IRB2400)
    solutions = arm_tree(IRB2400).ik_solutions(
        "tool0", targets_pose([tool_pose(model, np.array([0.3, 0.2, 0.1, 0.4, 0.6, 0.2]))]),
        relative_to="floor", whole_turns=False)
    straight = np.array([0.3, 0.2, 0.1, 0.0, 0.0, 0.6])
    assert geometric_flags(model, straight, "opw") == "front,up,flip"
    assert abb_cfx(solutions.arm, straight) == 0 == abb_cfx_by_definition(model, straight)
    bent = straight.copy()
    bent[4] = -1e-12  # just negative: flip, and cfx 1
    assert geometric_flags(model, bent, "opw") == "front,up,flip"
    assert abb_cfx(solutions.arm, bent) == 1 == abb_cfx_by_definition(model, bent)
