"""Every URDF of example-robot-data that Pinocchio loads, attached and driven at random joint
values, against Pinocchio's framesForwardKinematics on every link.

Mimic joints follow their primaries in pinframes; Pinocchio (built without mimic support)
gets the mimic's value written into its own joint. A mimic whose primary is missing from
the file (alex_psyonic_hands.urdf) stays an independent joint, with one warning each.
"""

import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

from pinframes import BrokenMimicWarning, FileFormatError, FrameTree, read_urdf
from pinframes.kinematics._one_time import FEW_TIMES
from urdf.test_robots_against_pinocchio import ROBOTS, pinocchio_configuration

needs_robots = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")
URDFS = sorted(ROBOTS.rglob("*.urdf")) if ROBOTS is not None else []


def pinocchio_model(urdf):
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return pin.buildModelFromUrdf(str(urdf))
    except (RuntimeError, ValueError):
        return None


def missing_primaries(urdf):
    """Names of the joints whose <mimic> names a joint the file does not have."""
    joints = ET.parse(urdf).getroot().findall("joint")
    names = {joint.get("name") for joint in joints}
    return sorted(joint.get("name") for joint in joints
                  if joint.find("mimic") is not None
                  and joint.find("mimic").get("joint") not in names)


@needs_robots
@pytest.mark.parametrize("urdf", URDFS, ids=[str(p.relative_to(ROBOTS)) for p in URDFS])
def test_every_link_matches_pinocchio(urdf, rng):
    model = pinocchio_model(urdf)
    if model is None:
        pytest.skip("Pinocchio does not load this file")
    tree = FrameTree()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        links = tree.attach_urdf(urdf, "world", prefix="r/")
    broken = [w for w in caught if issubclass(w.category, BrokenMimicWarning)]
    assert sorted(str(w.message).split("'")[1] for w in broken) == missing_primaries(urdf)
    actuated = [name for name, joint in tree.joints.items() if joint.is_actuated]
    values = {}
    for name in actuated:
        joint = tree.joints[name]
        low = -1.0 if joint.lower is None else joint.lower
        high = 1.0 if joint.upper is None else joint.upper
        values[name] = float(rng.uniform(low, high))
    if actuated:
        tree.set_joint_trajectory([0.0], [[values[name] for name in actuated]], actuated)
    data = model.createData()
    pin.framesForwardKinematics(model, data, pinocchio_configuration(model, tree, "r/", values))
    checked = [link for link in links if model.existFrame(link[2:], pin.BODY)]
    assert len(checked) == len(links)
    # one time takes Pinocchio's own kinematics; many times the batched numpy kernels (the
    # joints hold their one sample at every time)
    many_times = np.linspace(-1.0, 1.0, FEW_TIMES + 1)
    for link in checked:
        expected = data.oMf[model.getFrameId(link[2:], pin.BODY)].homogeneous
        np.testing.assert_allclose(tree.pose(link, "world", times=[0.0]).matrix[0], expected,
                                   atol=1e-12, err_msg=link)
        batched = tree.pose(link, "world", times=many_times).matrix
        np.testing.assert_allclose(batched, np.broadcast_to(expected, batched.shape),
                                   atol=1e-12, err_msg=f"{link}, {many_times.size} times")


def test_a_mimic_of_an_unknown_joint_warns_once_and_moves_on_its_own():
    urdf = """<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="x"/></joint>
    </robot>"""
    with pytest.warns(BrokenMimicWarning, match="joint 'j1' mimics joint 'x'") as caught:
        tree = read_urdf(urdf)
    assert len(caught) == 1
    assert tree.joints["j1"].mimic is None
    tree.set_joint_trajectory([0.0], [[0.5]], ["j1"])  # driven like any joint
    rotation = tree.pose("b", relative_to="a", times=[0.0]).rotation[0]
    np.testing.assert_allclose(rotation[:2, :2], [[np.cos(0.5), -np.sin(0.5)],
                                                  [np.sin(0.5), np.cos(0.5)]], atol=1e-15)
    with pytest.raises(FileFormatError, match="mimics unknown joint 'x'") as info:
        read_urdf(urdf, strict=True)
    assert (info.value.joint, info.value.field) == ("j1", "mimic.joint")


@needs_robots
def test_a_missing_mimic_primary_is_an_error_when_strict():
    urdf = ROBOTS / "alex_description/urdf/alex_psyonic_hands.urdf"
    with pytest.raises(FileFormatError, match="mimics unknown joint 'index_q1'") as info:
        FrameTree().attach_urdf(urdf, "world", strict=True)
    assert info.value.joint == "Left_index_q2"
    assert info.value.file == str(urdf)
