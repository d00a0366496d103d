"""Robots of example-robot-data mounted on moving frames, against Pinocchio called directly."""

from importlib import metadata
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from pinframes import FrameTree, JointLimitWarning, Pose
from pinframes.kinematics._one_time import FEW_TIMES


def robot_data_dir() -> Path | None:
    try:
        files = metadata.files("example-robot-data") or []
    except metadata.PackageNotFoundError:
        return None
    for file in files:
        if file.name == "panda.urdf":
            return Path(file.locate()).parents[2]
    return None


ROBOTS = robot_data_dir()
CASES = [
    "panda_description/urdf/panda.urdf",
    "ur_description/urdf/ur5_robot.urdf",
    "talos_data/robots/talos_left_arm.urdf",
    "kinova_description/robots/kinova.urdf",
    "pr2_description/urdf/pr2.urdf",
]
pytestmark = pytest.mark.skipif(ROBOTS is None, reason="example-robot-data is not installed")


def pinocchio_configuration(model, tree, prefix, values_by_joint):
    """q for Pinocchio's model (mimic joints are plain joints there) from joint values."""
    q = pin.neutral(model)
    for joint_id in range(1, model.njoints):
        name = prefix + model.names[joint_id]
        joint = tree.joints.get(name)
        if joint is None:
            continue
        value = values_by_joint.get(name, 0.0)
        if joint.mimic is not None:
            primary = tree.joints[joint.mimic.joint]
            primary_value = values_by_joint.get(primary.name, 0.0)
            value = joint.mimic.multiplier * primary_value + joint.mimic.offset
        index = model.joints[joint_id].idx_q
        if model.joints[joint_id].nq == 2:
            q[index:index + 2] = np.cos(value), np.sin(value)
        else:
            q[index] = value
    return q


@pytest.mark.parametrize(
    "sample_times", [[0.25, 1.5], list(np.linspace(0.1, 1.9, FEW_TIMES + 3))],
    ids=["two times (Pinocchio per time)", "more than FEW_TIMES (numpy kernels)"])
@pytest.mark.parametrize("relative_path", CASES)
def test_link_poses_on_a_moving_mount_match_pinocchio(relative_path, sample_times, rng):
    urdf = ROBOTS / relative_path
    tree = FrameTree()
    mount_translations = rng.normal(size=(3, 3))
    mount_rotations = [pin.exp3(rng.normal(size=3) * 0.3) for _ in range(3)]
    tree.add("mount", "world", Pose(mount_translations, mount_rotations, times=[0, 1, 2]))
    prefix = "r/"
    links = tree.attach_urdf(urdf, "mount", prefix=prefix)
    actuated = [name for name, joint in tree.joints.items() if joint.is_actuated]
    times = np.array([0.0, 0.5, 1.0, 2.0])
    positions = rng.uniform(-1, 1, size=(4, len(actuated)))
    for column, name in enumerate(actuated):
        joint = tree.joints[name]
        if joint.lower is not None and joint.upper is not None:
            positions[:, column] = rng.uniform(joint.lower, joint.upper, size=4)
    tree.set_joint_trajectory(times, positions, actuated)

    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    checked = [link for link in links if model.existFrame(link[len(prefix):])]
    results = {link: tree.pose(link, "world", times=sample_times).matrix for link in checked}
    for row, t in enumerate(sample_times):
        # Continuous joints move the short way round between samples.
        values = {name: float(np.interp(t, times, np.unwrap(positions[:, c])
                                        if tree.joints[name].kind == "continuous"
                                        else positions[:, c]))
                  for c, name in enumerate(actuated)}
        pin.framesForwardKinematics(model, data,
                                    pinocchio_configuration(model, tree, prefix, values))
        mount = tree.pose("mount", "world", times=[t]).matrix[0]
        for link in checked:
            expected = mount @ data.oMf[model.getFrameId(link[len(prefix):])].homogeneous
            np.testing.assert_allclose(results[link][row], expected, atol=1e-12,
                                       err_msg=f"{relative_path}: {link} at t={t}")


def test_whole_tree_configurations_drive_pinocchio_like_the_queries(rng):
    """to_pinocchio(): free-flyers from moving frames, continuous joints as (cos, sin)."""
    tree = FrameTree()
    tree.add("mount", "world", Pose(rng.normal(size=(2, 3)),
                                    [pin.exp3(rng.normal(size=3)) for _ in range(2)],
                                    times=[0, 1]))
    tree.attach_urdf(ROBOTS / "kinova_description/robots/kinova.urdf", "mount", prefix="k/")
    actuated = [name for name, joint in tree.joints.items() if joint.is_actuated]
    positions = rng.uniform(-3, 3, size=(2, len(actuated)))
    with pytest.warns(JointLimitWarning):  # values outside limits still drive the joints
        tree.set_joint_trajectory([0.0, 1.0], positions, actuated)
    compiled = tree.to_pinocchio()
    data = compiled.model.createData()
    for t, q in zip([0.3, 0.8], compiled.configurations([0.3, 0.8]), strict=True):
        pin.framesForwardKinematics(compiled.model, data, q)
        for frame in tree.frames[::3]:
            np.testing.assert_allclose(
                data.oMf[compiled.frame_ids[frame]].homogeneous,
                tree.pose(frame, "world", times=[t]).matrix[0], atol=1e-12)


def test_joints_driven_in_groups_on_different_times_match_pinocchio(rng):
    """Three calls drive the Panda's arm: two on equal times (one segment search serves
    both), one on its own times; every joint is interpolated on its own samples."""
    urdf = ROBOTS / "panda_description/urdf/panda.urdf"
    tree = FrameTree()
    tree.attach_urdf(urdf, "world")
    arm = [f"panda_joint{i}" for i in range(1, 8)]
    groups = [(arm[:3], np.array([0.0, 0.4, 1.3, 2.0])), (arm[3:5], np.array([0.0, 0.4, 1.3, 2.0])),
              (arm[5:], np.array([-0.5, 0.7, 1.1, 1.9, 3.0]))]
    samples = {}
    for names, times in groups:
        positions = np.column_stack([
            rng.uniform(tree.joints[name].lower, tree.joints[name].upper, size=times.size)
            for name in names])
        tree.set_joint_trajectory(times, positions, names)
        samples.update({name: (times, positions[:, column])
                        for column, name in enumerate(names)})
    query_times = np.linspace(-1.0, 3.5, 37)
    result = tree.pose("panda_hand", "world", times=query_times).matrix
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    hand = model.getFrameId("panda_hand")
    for row, t in enumerate(query_times):
        values = {name: float(np.interp(t, *samples[name])) for name in arm}
        pin.framesForwardKinematics(model, data, pinocchio_configuration(model, tree, "", values))
        np.testing.assert_allclose(result[row], data.oMf[hand].homogeneous, atol=1e-12,
                                   err_msg=f"t={t}")
