"""The bundled welding robot URDF: both parsers read it and agree on its kinematics.

Uses Pinocchio and yourdfpy directly, never pinframes.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import yourdfpy

URDF_PATH = Path(__file__).resolve().parents[2] / "models" / "welding_robot" / "welding_robot.urdf"
JOINTS = [f"joint_{i}" for i in range(1, 7)]
LINKS = ["base_link", *(f"link_{i}" for i in range(1, 7)), "flange"]


@pytest.fixture(scope="module")
def pin_model() -> pin.Model:
    return pin.buildModelFromUrdf(str(URDF_PATH))


@pytest.fixture(scope="module")
def urdf() -> yourdfpy.URDF:
    return yourdfpy.URDF.load(str(URDF_PATH), load_meshes=False)


def test_structure_is_six_revolute_joints_and_a_fixed_flange(urdf):
    joints = {joint.name: joint for joint in urdf.robot.joints}
    assert urdf.actuated_joint_names == JOINTS
    assert all(joints[name].type == "revolute" for name in JOINTS)
    assert joints["flange_joint"].type == "fixed"
    assert joints["flange_joint"].parent == "link_6"
    assert joints["flange_joint"].child == "flange"
    assert sorted(link.name for link in urdf.robot.links) == sorted(LINKS)
    assert urdf.base_link == "base_link"


def test_limits_are_plausible_for_a_six_kg_welding_robot(urdf):
    for joint in urdf.robot.joints:
        if joint.type != "revolute":
            continue
        limit = joint.limit
        assert limit.lower < 0.0 < limit.upper, joint.name
        assert np.radians(90) <= limit.upper - limit.lower <= np.radians(720), joint.name
        assert np.radians(100) <= limit.velocity <= np.radians(720), joint.name
        assert limit.effort > 0, joint.name
    masses = [link.inertial.mass for link in urdf.robot.links if link.inertial is not None]
    assert 100.0 <= sum(masses) <= 250.0


def test_every_inertia_is_physically_valid(urdf):
    for link in urdf.robot.links:
        if link.inertial is None:
            continue
        eig = np.linalg.eigvalsh(link.inertial.inertia)
        assert link.inertial.mass > 0, link.name
        assert eig.min() > 0, link.name
        # triangle inequality of principal moments
        assert eig[0] + eig[1] >= eig[2] * (1 - 1e-9), link.name


def test_reach_to_the_wrist_centre_is_about_1_4_m(pin_model):
    # arm stretched forward: upper arm horizontal, forearm in line with it
    data = pin_model.createData()
    q = np.zeros(6)
    q[1] = np.pi / 2
    q[2] = -np.arctan2(0.62, 0.10)
    pin.forwardKinematics(pin_model, data, q)
    wrist_centre = data.oMi[pin_model.getJointId("joint_5")].translation
    reach = np.hypot(wrist_centre[0], wrist_centre[1])
    assert reach == pytest.approx(0.16 + 0.62 + np.hypot(0.62, 0.10), abs=1e-12)
    assert 1.35 <= reach <= 1.45


def test_flange_z_points_out_of_the_flange_and_x_down_at_zero(pin_model):
    data = pin_model.createData()
    pin.framesForwardKinematics(pin_model, data, np.zeros(6))
    flange = data.oMf[pin_model.getFrameId("flange")]
    np.testing.assert_allclose(flange.rotation[:, 2], [1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(flange.rotation[:, 0], [0.0, 0.0, -1.0], atol=1e-15)
    # hand-derived from the joint origins: x 0.16 + 0.25 + 0.37 + 0.09, z 0.2 + 0.25 + 0.62 + 0.1
    np.testing.assert_allclose(flange.translation, [0.87, 0.0, 1.17], atol=1e-15)


def test_pinocchio_and_yourdfpy_agree_at_random_configurations(pin_model, urdf, rng):
    data = pin_model.createData()
    lower, upper = pin_model.lowerPositionLimit, pin_model.upperPositionLimit
    assert [pin_model.names[i] for i in range(1, pin_model.njoints)] == JOINTS
    for _ in range(50):
        q = rng.uniform(lower, upper)
        pin.framesForwardKinematics(pin_model, data, q)
        urdf.update_cfg(q)
        for link in LINKS:
            link_in_base_pin = data.oMf[pin_model.getFrameId(link, pin.FrameType.BODY)]
            link_in_base_yourdfpy = urdf.get_transform(link, "base_link")
            np.testing.assert_allclose(
                link_in_base_pin.homogeneous, link_in_base_yourdfpy, rtol=0, atol=1e-12
            )
