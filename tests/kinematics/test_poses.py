"""``FrameTree.poses``: many frames or pairs in one call equal the one-at-a-time queries."""

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from pinframes import FrameTree, InvalidTimeError, Pose, TreeStructureError

ROBOT = Path(__file__).parents[2] / "models" / "welding_robot" / "welding_robot.urdf"


def random_tree(rng, size=40):
    """Static and moving frames (own keyframe grids) and a robot with a joint trajectory."""
    tree = FrameTree(root="world")
    names = ["world"]
    for index in range(size):
        parent = names[int(rng.integers(len(names)))]
        rotation = pin.exp3(rng.normal(size=3))
        if rng.random() < 0.3:
            count = int(rng.integers(2, 6))
            keyframe_times = np.sort(rng.choice(np.arange(0.0, 10.0, 0.25), count,
                                                replace=False))
            rotations = np.array([pin.exp3(rng.normal(size=3)) for _ in range(count)])
            pose = Pose(rng.normal(size=(count, 3)), rotations, times=keyframe_times)
        else:
            pose = Pose(rng.normal(size=3), rotation)
        names.append(f"n{index}")
        tree.add(names[-1], parent, pose)
    mount = names[int(rng.integers(len(names)))]
    tree.attach_urdf(ROBOT, mount, prefix="robot/")
    joints = [name for name in tree.joints if tree.joints[name].mimic is None]
    trajectory_times = np.linspace(0.0, 10.0, 21)
    tree.set_joint_trajectory(trajectory_times,
                              rng.uniform(-1, 1, size=(21, len(joints))), joints)
    return tree, [name for name in tree.frames]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_pairs_at_times_equal_one_query_per_pair(seed):
    rng = np.random.default_rng(seed)
    tree, names = random_tree(rng)
    frames = list(rng.choice(names, 60))
    relative_to = list(rng.choice(names, 60))
    times = np.sort(rng.uniform(-1.0, 11.0, size=17))
    stack = tree.poses(frames, relative_to=relative_to, times=times)
    assert stack.translation.shape == (60, 17, 3) and len(stack) == 60
    for i, (frame, reference) in enumerate(zip(frames, relative_to, strict=True)):
        single = tree.pose(frame, reference, times=times)
        np.testing.assert_allclose(stack.matrix[i], single.matrix, rtol=0, atol=1e-12)
        np.testing.assert_array_equal(stack[i].times, single.times)


def test_every_frame_relative_to_one_frame_at_one_time():
    rng = np.random.default_rng(5)
    tree, names = random_tree(rng)
    reference = names[7]
    stack = tree.poses(names, relative_to=reference, times=[4.2])
    for i, frame in enumerate(names):
        np.testing.assert_allclose(stack.rotation[i], tree.pose(frame, reference,
                                                                 times=[4.2]).rotation,
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(stack.translation[i], tree.pose(frame, reference,
                                                                    times=[4.2]).translation,
                                   rtol=0, atol=1e-12)


def test_static_pairs_without_times_are_static_poses():
    rng = np.random.default_rng(9)
    tree = FrameTree()
    names = ["world"]
    for index in range(50):
        names.append(f"s{index}")
        tree.add(names[-1], names[int(rng.integers(len(names) - 1))],
                 Pose(rng.normal(size=3), pin.exp3(rng.normal(size=3))))
    frames, relative_to = list(rng.choice(names, 200)), list(rng.choice(names, 200))
    stack = tree.poses(frames, relative_to=relative_to)
    assert stack.translation.shape == (200, 3) and stack.times is None
    for i, (frame, reference) in enumerate(zip(frames, relative_to, strict=True)):
        np.testing.assert_allclose(stack.matrix[i], tree.pose(frame, reference).matrix,
                                   rtol=0, atol=1e-12)
    parents = tree.poses(names[1:])  # relative_to=None: each frame's parent
    for i, name in enumerate(names[1:]):
        np.testing.assert_allclose(parents.matrix[i], tree.local_pose(name).matrix,
                                   rtol=0, atol=1e-12)


def test_default_times_shared_by_frames_on_one_moving_frame():
    tree = FrameTree()
    tree.add("car", "world", Pose([[0, 0, 0], [2, 0, 0], [2, 2, 0]], times=[0, 1, 3]))
    tree.add("lidar", "car", Pose([0.1, 0, 0.5]))
    tree.add("tile", "world", Pose([5, 5, 0]))
    stack = tree.poses(["lidar", "car", "tile"], relative_to="world")
    np.testing.assert_array_equal(stack.times, tree.pose("lidar", "world").times)
    np.testing.assert_allclose(stack.translation[0],
                               [[0.1, 0, 0.5], [2.1, 0, 0.5], [2.1, 2, 0.5]], atol=1e-15)
    np.testing.assert_allclose(stack.translation[2], np.tile([5, 5, 0], (3, 1)))


def test_pairs_on_different_default_timelines_ask_for_times():
    tree = FrameTree()
    tree.add("a", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0, 1]))
    tree.add("b", "world", Pose([[0, 0, 0], [1, 0, 0]], times=[0, 2]))
    with pytest.raises(InvalidTimeError, match="different timelines"):
        tree.poses(["a", "b"], relative_to="world")
    stack = tree.poses(["a", "b"], relative_to="world", times=[0.5])
    np.testing.assert_allclose(stack.translation[:, 0, 0], [0.5, 0.25])


def test_relative_to_must_name_one_frame_per_frame():
    tree = FrameTree()
    tree.add("a", "world", Pose())
    with pytest.raises(TreeStructureError, match="relative_to"):
        tree.poses(["a", "world"], relative_to=["world"])
    assert len(tree.poses([], relative_to="world")) == 0


def test_a_robot_whose_joints_have_no_samples_holds_still_beside_a_moving_frame():
    """Without times, a path through joints without samples is static: alone it gives
    static poses; beside a moving frame it repeats over that frame's timeline."""
    tree = FrameTree()
    tree.attach_urdf(ROBOT, "world", prefix="robot/")
    with pytest.warns(UserWarning, match="no samples"):
        alone = tree.poses(["robot/flange", "robot/link_2"], relative_to="world")
    assert alone.translation.shape == (2, 3) and alone.times is None
    np.testing.assert_allclose(alone.matrix[0], tree.pose("robot/flange", "world").matrix,
                               rtol=0, atol=1e-12)
    tree.add("car", "world", Pose([[0, 0, 0], [2, 0, 0]], times=[0, 1]))
    with pytest.warns(UserWarning, match="no samples"):
        both = tree.poses(["robot/flange", "car"], relative_to="world")
    np.testing.assert_array_equal(both.times, tree.pose("car", "world").times)
    np.testing.assert_allclose(both.matrix[0], np.repeat(alone.matrix[:1], 2, axis=0),
                               rtol=0, atol=1e-12)
