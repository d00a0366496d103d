"""Which arms are recognised, the OPW parameters derived from their URDFs against those
opw_kinematics publishes, and the error naming what breaks a shape."""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from closed_form_arms import (
    HC10,
    IRB2400,
    IRB2600,
    KR6R700,
    arm_model,
    arm_tree,
    joint_axes,
    meeting_point,
    ros_industrial_arms,
    targets_pose,
    tool_pose,
    universal_robots,
    ur_description_urdf,
)
from ik_paths import example_robot
from pinframes import FrameTree, JointError
from urdf.ros_packages import UR_DESCRIPTION, UR_XACRO

# opw_kinematics (Jmeyer1292/opw_kinematics), include/opw_kinematics/opw_parameters_examples.h:
# makeKukaKR6_R700_sixx, makeIrb2400_10, makeIrb2600_12_165 (a1, a2, b, c1, c2, c3, c4)
PUBLISHED = {
    KR6R700: (0.025, -0.035, 0.000, 0.400, 0.315, 0.365, 0.080),
    IRB2400: (0.100, -0.135, 0.000, 0.615, 0.705, 0.755, 0.085),
    IRB2600: (0.150, -0.115, 0.000, 0.445, 0.700, 0.795, 0.085),
}


def _solutions(urdf):
    model = arm_model(urdf)
    middle = 0.5 * (np.maximum(model.lowerPositionLimit, -1.0)
                    + np.minimum(model.upperPositionLimit, 1.0))
    return arm_tree(urdf).ik_solutions("tool0", targets_pose([tool_pose(model, middle)]),
                                       relative_to="floor")


@pytest.mark.parametrize("urdf", list(PUBLISHED), ids=lambda path: path.stem)
def test_the_parameters_are_those_opw_kinematics_publishes(urdf):
    parameters = _solutions(urdf).opw_parameters
    derived = (parameters.a1, parameters.a2, parameters.b, parameters.c1, parameters.c2,
               parameters.c3, parameters.c4)
    np.testing.assert_allclose(derived, PUBLISHED[urdf], atol=1e-12)


@pytest.mark.slow
def test_every_ros_industrial_arm_is_opw_and_every_universal_robot_ur_type():
    for urdf in ros_industrial_arms():
        assert _solutions(urdf).arm.family == "opw", urdf.name
    for urdf in universal_robots():
        assert _solutions(urdf).arm.family == "ur", urdf.name


def test_a_ur5_is_ur_type_and_has_no_opw_parameters():
    solutions = _solutions(example_robot("ur5_robot.urdf"))
    assert solutions.arm.family == "ur"
    assert solutions.arm.joint_names == ("shoulder_pan_joint", "shoulder_lift_joint",
                                         "elbow_joint", "wrist_1_joint", "wrist_2_joint",
                                         "wrist_3_joint")
    with pytest.raises(JointError, match="OPW parameters are those of an OPW arm"):
        solutions.opw_parameters  # noqa: B018


def test_an_offset_wrist_is_neither_family_and_the_error_says_why():
    """Yaskawa's HC10: axis 6 misses the point where axes 4 and 5 meet (by as much as
    Pinocchio's joint axes say), and axis 4 is at right angles to axis 3."""
    model = arm_model(HC10)
    directions, points = joint_axes(model, np.zeros(6))
    centre = meeting_point(directions[3], points[3], directions[4], points[4])
    apart = np.linalg.norm(np.cross(centre - points[5], directions[5]))
    with pytest.raises(JointError) as caught:
        arm_tree(HC10).ik_solutions("tool0", targets_pose([tool_pose(model, np.zeros(6))]),
                                    relative_to="floor")
    message = str(caught.value)
    assert "joint_1_s, joint_2_l, joint_3_u, joint_4_r, joint_5_b, joint_6_t" in message
    assert ("joint 6 (joint_6_t) axis misses the point where joint 4 and joint 5 axes meet: "
            f"{apart:.3g} m apart") in message and f"{apart:.3g}" == "0.162"
    assert "joint 4 (joint_4_r) axis is not parallel to joint 3 (joint_3_u) axis" in message


def test_a_calibration_that_tilts_an_axis_breaks_the_ur_shape(tmp_path):
    """Universal Robots' description takes a robot's calibration as ``kinematics_params``;
    one that tilts the elbow axis by 0.2 mrad (pitch of the forearm's origin) leaves the
    arm of neither family, and the error says by how much."""
    nominal = yaml.safe_load((UR_DESCRIPTION / "config" / "ur5e" / "default_kinematics.yaml"
                              ).read_text())
    nominal["kinematics"]["forearm"]["pitch"] = 2e-4
    calibration = tmp_path / "calibration.yaml"
    calibration.write_text(yaml.safe_dump(nominal))
    tree = FrameTree("floor")
    tree.attach_urdf(UR_XACRO, "floor", xacro_args={"name": "ur", "ur_type": "ur5e",
                                                    "kinematics_params": str(calibration)})
    target = tool_pose(arm_model(ur_description_urdf("ur5e", tmp_path)), np.full(6, 0.3))
    with pytest.raises(JointError, match=r"nor a UR-type arm \(three parallel axes, offset "
                       r"wrist\): joint 3 \(elbow_joint\) axis is not parallel to joint 2 "
                       r"\(shoulder_lift_joint\) axis: 0\.0002 rad apart"):
        tree.ik_solutions("tool0", targets_pose([target]), relative_to="floor")


def test_seven_joints_are_not_a_closed_form_arm():
    panda = example_robot("panda.urdf")
    tree = arm_tree(panda)
    target = tool_pose(arm_model(panda), np.array([0, -0.785, 0, -2.356, 0, 1.571, 0.785,
                                                   0.02, 0.02]), "panda_hand")
    with pytest.raises(JointError, match="six joints in a chain; got 7"):
        tree.ik_solutions("panda_hand", targets_pose([target]), relative_to="floor")
