"""FrameTree.clearance on primitives against distances derived by hand, and its errors.

The meshes of a real robot are checked against Pinocchio + coal called directly in
tests/urdf/test_clearance_against_pinocchio.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from pinframes import FrameNotFoundError, FrameTree, GeometryError, Pose
from pinframes.kinematics.collision import clearance as clearance_module


def link(name: str, *shapes: str) -> str:
    """A URDF of one link ``name`` with the given ``<collision>`` bodies."""
    body = "".join(f"<collision>{shape}</collision>" for shape in shapes)
    return f'<robot name="{name}"><link name="{name}">{body}</link></robot>'


def sphere(radius: float, xyz: str = "0 0 0") -> str:
    return f'<origin xyz="{xyz}"/><geometry><sphere radius="{radius}"/></geometry>'


def box(size: str, xyz: str = "0 0 0", rpy: str = "0 0 0") -> str:
    return f'<origin xyz="{xyz}" rpy="{rpy}"/><geometry><box size="{size}"/></geometry>'


def arm_with_ball() -> FrameTree:
    """A revolute joint about z at the origin; a ball of radius 0.1 on its link at x = 0.5."""
    tree = FrameTree()
    tree.attach_urdf("""<robot name="arm">
      <link name="base"/>
      <link name="tip"><collision>
        <origin xyz="0.5 0 0"/><geometry><sphere radius="0.1"/></geometry></collision></link>
      <joint name="turn" type="revolute"><parent link="base"/><child link="tip"/>
        <axis xyz="0 0 1"/><limit lower="-4" upper="4" effort="1" velocity="1"/></joint>
    </robot>""", "world", prefix="arm/")
    return tree


def test_a_ball_on_a_joint_against_a_fixed_ball():
    tree = arm_with_ball()
    tree.add("post", "world", Pose([0.0, 1.0, 0.2]))
    tree.attach_urdf(link("ball", sphere(0.05)), "post")
    times = np.linspace(0.0, 2.0, 9)
    angles = np.linspace(0.0, np.pi, 9)
    tree.set_joint_trajectory(times, angles[:, None], ["arm/turn"])
    result = tree.clearance("arm/tip", "ball")
    centre = np.stack([0.5 * np.cos(angles), 0.5 * np.sin(angles), 0 * angles], axis=1)
    other = np.array([0.0, 1.0, 0.2])
    apart = other - centre
    gap = np.linalg.norm(apart, axis=1)
    np.testing.assert_allclose(result.seconds, times)
    np.testing.assert_allclose(result.distance, gap - 0.15, atol=1e-9)
    direction = apart / gap[:, None]
    np.testing.assert_allclose(result.point_a, centre + 0.1 * direction, atol=1e-9)
    np.testing.assert_allclose(result.point_b, other - 0.05 * direction, atol=1e-9)
    assert result.closest.tolist() == [["arm/tip", "ball"]] * 9
    assert result.first_contact is None and not result.in_contact.any()
    assert result.smallest == 4  # at 90 degrees the ball passes under the post


def test_boxes_on_keyframed_frames_close_in_overlap_and_the_first_contact():
    """A 0.2 m cube slides along x into a fixed 0.4 m cube: the gap is 1.0 - x - 0.3, then
    the overlap depth is the shortest way out (along -x, +x, or 0.3 m sideways)."""
    tree = FrameTree()
    tree.add("slider", "world", Pose(translation=[[0.0, 0, 0], [1.2, 0, 0]], times=[0.0, 12.0]))
    tree.attach_urdf(link("cube", box("0.2 0.2 0.2")), "slider")
    tree.add("wall", "world", Pose([1.0, 0.0, 0.0]))
    tree.attach_urdf(link("block", box("0.4 0.4 0.4")), "wall")
    result = tree.clearance("cube", ["block"], times=np.arange(0.0, 12.5, 0.5))
    x = 0.1 * result.seconds
    gap = 1.0 - x - 0.3  # faces at x + 0.1 and 1.0 - 0.2
    depth = np.minimum.reduce([(x + 0.1) - 0.8, 1.2 - (x - 0.1), np.full_like(x, 0.3)])
    expected = np.where(gap >= 0, gap, -depth)
    np.testing.assert_allclose(result.distance, expected, atol=1e-9)
    assert result.first_contact == pytest.approx(7.0)  # the first sample with a gap <= 0
    assert result.in_contact.tolist() == (expected <= 1e-12).tolist()
    apart = result.seconds < 7.0
    np.testing.assert_allclose(result.point_a[apart, 0], x[apart] + 0.1, atol=1e-9)
    np.testing.assert_allclose(result.point_b[apart, 0], 0.8, atol=1e-9)


def test_a_rotated_box_against_a_sphere_and_the_nearest_of_several_shapes():
    """A box turned 45 degrees about z shows an edge to the sphere; of the link's two
    shapes the nearer one counts."""
    tree = FrameTree()
    tree.attach_urdf(link("diamond", box("0.2 0.2 0.2", rpy="0 0 0.7853981633974483"),
                          sphere(0.01, xyz="-3 0 0")), "world")
    tree.add("probe_mount", "world", Pose(translation=[[0.5, 0, 0], [0.5, 0, 0.3]],
                                          times=[0.0, 1.0]))
    tree.attach_urdf(link("probe", sphere(0.05)), "probe_mount")
    result = tree.clearance("probe", "diamond", times=[0.0, 1.0])
    edge = 0.1 * np.sqrt(2.0)
    # at z = 0.3 the nearest point of the box is the top of its edge, at (edge, 0, 0.1)
    expected = [0.5 - edge - 0.05, np.hypot(0.5 - edge, 0.2) - 0.05]
    np.testing.assert_allclose(result.distance, expected, atol=1e-9)
    np.testing.assert_allclose(result.point_b[0], [edge, 0, 0], atol=1e-9)
    assert result.closest[:, 1].tolist() == ["diamond", "diamond"]


@pytest.mark.parametrize("chunk", [16, 1 << 14])
def test_same_answers_with_and_without_the_sphere_bounds(rng, monkeypatch, chunk):
    """Many spheres moving at random: the smallest pair distance computed over all pairs
    with numpy equals the query, which skips pairs by their bounding spheres (evaluated in
    one chunk of samples, and in three)."""
    monkeypatch.setattr(clearance_module, "CLEARANCE_CHUNK", chunk)
    tree = FrameTree()
    times = np.linspace(0.0, 1.0, 40)
    centres = {}
    for name in [f"a{i}" for i in range(5)] + [f"b{i}" for i in range(6)]:
        path = rng.uniform(-1.0, 1.0, size=(2, 3))
        tree.add(name + "_mount", "world", Pose(translation=path, times=[0.0, 1.0]))
        radius = rng.uniform(0.02, 0.2)
        tree.attach_urdf(link(name, sphere(radius)), name + "_mount")
        centres[name] = (path[0] + np.outer(times, path[1] - path[0]), radius)
    result = tree.clearance("a*", "b*", times=times)
    gaps = np.array([[np.linalg.norm(centres[a][0][k] - centres[b][0][k]) - centres[a][1]
                      - centres[b][1] for a in centres if a[0] == "a" for b in centres
                      if b[0] == "b"] for k in range(times.size)])
    np.testing.assert_allclose(result.distance, gaps.min(axis=1), atol=1e-9)
    assert set(result.frames_a) == {f"a{i}" for i in range(5)}


def test_time_rules_follow_pose():
    """Default times: every sample time of the joint and of a keyframed obstacle (what
    pose() takes between the two); reference times as pose() gives them."""
    tree = arm_with_ball()
    start = np.datetime64("2026-01-01T08:00:01")
    tree.set_joint_trajectory([start, start + np.timedelta64(2, "s")], [[0.0], [1.0]],
                              ["arm/turn"])
    lift = Pose(translation=[[0, 0, -0.3], [0, 0, -0.2], [0, 0, -0.25]], times=[0, 1.5, 4],
                reference_time="2026-01-01T08:00:00")
    tree.add("floor_mount", "world", lift)
    tree.attach_urdf(link("floor", box("4 4 0.1")), "floor_mount")
    result = tree.clearance("arm/tip", "floor")
    pose = tree.pose("arm/tip", "floor")
    np.testing.assert_array_equal(result.times, pose.times)
    assert result.reference_time == pose.reference_time == np.datetime64("2026-01-01T08:00:00")
    np.testing.assert_allclose(result.distance, pose.translation[:, 2] - 0.05 - 0.1,
                               atol=1e-9)
    at = ["2026-01-01T08:00:02", "2026-01-01T08:00:03.5"]
    for time_ref in (None, "2026-01-01T07:00:00"):
        result = tree.clearance("arm/tip", "floor", times=at, time_ref=time_ref)
        pose = tree.pose("arm/tip", "floor", times=at, time_ref=time_ref)
        np.testing.assert_array_equal(result.times, pose.times)
        assert result.reference_time == pose.reference_time
        np.testing.assert_allclose(result.distance, pose.translation[:, 2] - 0.15, atol=1e-9)


def test_a_static_scene_gives_one_sample_without_times():
    tree = FrameTree()
    tree.attach_urdf(link("floor", box("1 1 0.2")), "world")
    tree.add("up", "world", Pose([0.0, 0.0, 0.1]))
    tree.attach_urdf(link("cup", sphere(0.05, xyz="0 0 0.02")), "up")
    result = tree.clearance("cup", "floor")
    assert len(result) == 1 and result.times is None and result.seconds is None
    np.testing.assert_allclose(result.distance, [-0.03], atol=1e-9)
    assert result.first_contact == 0.0


@pytest.mark.filterwarnings("ignore::pinframes.JointWithoutSamplesWarning")
def test_patterns_exclusions_and_the_same_link_on_both_sides():
    tree = arm_with_ball()
    tree.attach_urdf(link("near", sphere(0.1, xyz="0.8 0 0")), "world")
    tree.attach_urdf(link("far", sphere(0.1, xyz="3 0 0")), "world")
    # "arm/*" matches arm/base too, which has no geometry: a pattern leaves it out
    result = tree.clearance("arm/*", ["near", "far", "arm/tip"])
    assert result.frames_a == ("arm/tip",)
    np.testing.assert_allclose(result.distance, [0.1], atol=1e-9)  # arm/tip never with itself
    without = tree.clearance("arm/*", ["near", "far"], exclude=[("near", "arm/t*")])
    np.testing.assert_allclose(without.distance, [2.3], atol=1e-9)
    assert without.closest.tolist() == [["arm/tip", "far"]]
    assert without.excluded == (("near", "arm/tip"),)


@pytest.mark.filterwarnings("ignore::pinframes.JointWithoutSamplesWarning")
def test_names_without_geometry_are_errors_naming_them():
    tree = arm_with_ball()
    tree.attach_urdf(link("near", sphere(0.1, xyz="0.8 0 0")), "world")
    with pytest.raises(GeometryError, match="only the links of attached URDFs") as info:
        tree.clearance("world", "near")
    assert info.value.frame == "world"
    with pytest.raises(GeometryError, match="has no <collision> geometry") as info:
        tree.clearance("arm/base", "near")
    assert info.value.frame == "arm/base"
    with pytest.raises(GeometryError, match="no <visual> geometry"):
        tree.clearance("arm/tip", "near", geometry="visual")
    with pytest.raises(GeometryError, match="match no frame with collision geometry"):
        tree.clearance("arm/b*", "near")
    with pytest.raises(FrameNotFoundError, match="did you mean"):
        tree.clearance("arm/tipp", "near")
    with pytest.raises(FrameNotFoundError, match="pattern 'robot/\\*' names no frame"):
        tree.clearance("robot/*", "near")
    with pytest.raises(GeometryError, match="expected one of collision, visual"):
        tree.clearance("arm/tip", "near", geometry="inertial")
    with pytest.raises(GeometryError, match="no pair of two different frames"):
        tree.clearance("arm/tip", "arm/*")
    with pytest.raises(GeometryError, match="no pair of two different frames"):
        tree.clearance("arm/tip", "near", exclude=[("near", "arm/tip")])


def test_missing_unreadable_and_malformed_geometry_are_errors_naming_frame_and_file(tmp_path):
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "bad.stl").write_text("not a mesh at all")
    urdf = tmp_path / "parts.urdf"
    urdf.write_text("""<robot name="parts">
      <link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision></link>
      <link name="lost"><collision><geometry><mesh filename="package://gone/x.stl"/>
        </geometry></collision></link>
      <link name="broken"><collision><geometry><mesh filename="meshes/bad.stl"/></geometry>
        </collision></link>
      <link name="odd"><collision><geometry><box size="1 1"/></geometry></collision></link>
      <joint name="j1" type="fixed"><parent link="base"/><child link="lost"/></joint>
      <joint name="j2" type="fixed"><parent link="base"/><child link="broken"/></joint>
      <joint name="j3" type="fixed"><parent link="base"/><child link="odd"/></joint>
    </robot>""")
    tree = FrameTree()
    tree.attach_urdf(urdf, "world", prefix="p/")
    with pytest.raises(GeometryError, match=r"'package://gone/x\.stl' not found") as info:
        tree.clearance("p/lost", "p/base")
    assert (info.value.frame, info.value.field) == ("p/lost", "collision[0].mesh")
    assert info.value.file == str(urdf) and "package_dirs" in str(info.value)
    with pytest.raises(GeometryError, match="cannot be read") as info:
        tree.clearance("p/base", "p/broken")
    assert info.value.file == str(tmp_path / "meshes" / "bad.stl")
    assert info.value.frame == "p/broken"
    with pytest.raises(GeometryError, match="three finite numbers") as info:
        tree.clearance("p/o*", "p/base")  # a pattern keeps a link whose shape is malformed
    assert info.value.frame == "p/odd" and info.value.field == "collision[0].geometry.box.size"
    assert info.value.file == str(urdf)
