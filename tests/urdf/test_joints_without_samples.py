"""Robot joints without samples hold their rest value and warn once per tree."""

import warnings

import numpy as np
import pinocchio as pin
import pytest

from pinframes import FrameTree, JointWithoutSamplesWarning
from urdf.test_robots_against_pinocchio import ROBOTS

pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")


def test_panda_without_samples_sits_at_the_value_nearest_zero_within_its_limits():
    urdf = ROBOTS / "panda_description/urdf/panda.urdf"
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    model = pin.buildModelFromUrdf(str(urdf))
    # joint 4's limits [-3.0718, -0.0698] exclude 0: it holds -0.0698, the others 0
    q = np.clip(np.zeros(model.nq), model.lowerPositionLimit, model.upperPositionLimit)
    assert q[3] == pytest.approx(-0.0698) and np.count_nonzero(q) == 1
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    with pytest.warns(JointWithoutSamplesWarning) as caught:
        hand = tree.pose("panda_hand", relative_to="world")
        tree.pose("panda_link4", relative_to="world")  # a second query: no second warning
    assert len(caught) == 1
    message = str(caught[0].message)
    assert "'panda_joint1'" in message and "set_joint_trajectory" in message
    expected = data.oMf[model.getFrameId("panda_hand")].homogeneous
    np.testing.assert_allclose(hand.matrix, expected, atol=1e-12)
    assert tree.joints["panda_joint4"].rest_value == pytest.approx(-0.0698)


def test_driven_joints_do_not_warn():
    urdf = ROBOTS / "panda_description/urdf/panda.urdf"
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    actuated = [name for name, joint in tree.joints.items() if joint.is_actuated]
    rest = [tree.joints[name].rest_value for name in actuated]
    tree.set_joint_trajectory([0.0, 1.0], [rest, rest], actuated)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tree.pose("panda_hand", relative_to="world")
