"""read_scene and write_scene: poses against hand-derived numbers, and malformed scenes."""

import textwrap

import numpy as np
import pytest

from pinframes import read_scene, write_scene
from pinframes.errors import FileFormatError, PinframesError, UnsupportedFeatureError

from geometry import rot_x, rot_z

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/><link name="link1"/><link name="link2"/>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="link1"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
    <limit lower="-4" upper="4" effort="1" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="link1"/><child link="link2"/><origin xyz="0.5 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"""


def scene_file(tmp_path, text, name="scene.yaml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


@pytest.fixture
def cell(tmp_path):
    """A turntable, a robot on a stand with a CSV trajectory, and a tool on its last link."""
    (tmp_path / "robots").mkdir()
    (tmp_path / "robots" / "arm.urdf").write_text(ARM)
    (tmp_path / "motion.csv").write_text("time_s,turn,slide\n0,0,0\n1,0.5,0.1\n2,1,0.2\n")
    return scene_file(tmp_path, """\
        pinframes_scene: 1
        name: cell
        tools:                       # listed before the robot that makes its parent
          - {name: tool, parent: r/link2, xyz: [0, 0, 0.1]}
        robots:
          - name: arm
            urdf: robots/arm.urdf
            parent: stand
            xyz: [1, 0, 0]
            rpy: [0, 0, 1.5707963267948966]
            prefix: r/
            trajectory: motion.csv
        frames:
          - {name: stand, parent: world, xyz: [0, 2, 0]}
          - name: table
            parent: world
            xyz: [3, 0, 0.5]
            keyframes:
              - {time: 0, rpy: [0, 0, 0]}
              - {time: 4, quaternion: [0, 0, 0.7071067811865476, 0.7071067811865476]}
          - {name: seam, parent: table, xyz: [0.2, 0, 0], quaternion: [1, 0, 0, 0]}
        """)


def test_inline_frames_and_keyframes(cell):
    tree = read_scene(cell)
    assert tree.name == "cell"
    seam = tree.pose("seam", relative_to="world", times=[0.0, 2.0, 4.0, 6.0])
    for index, time in enumerate([0.0, 2.0, 4.0, 6.0]):
        # SLERP about z is linear in the angle; held after the last keyframe at 4 s
        angle = np.pi / 2 * min(time, 4.0) / 4.0
        np.testing.assert_allclose(seam.translation[index],
                                   [3 + 0.2 * np.cos(angle), 0.2 * np.sin(angle), 0.5],
                                   atol=1e-12)
        np.testing.assert_allclose(seam.rotation[index], rot_z(angle) @ rot_x(np.pi),
                                   atol=1e-12)


def test_robot_with_trajectory_and_tool(cell):
    tree = read_scene(cell)
    assert set(tree.joints) == {"r/turn", "r/slide"}
    tool = tree.pose("tool", relative_to="world", times=[0.5, 2.0])
    for index, (theta, slide) in enumerate([(0.25, 0.05), (1.0, 0.2)]):
        # world -> stand (0, 2, 0) -> robot base (1, 0, 0) turned 90 deg about z
        # -> (0, 0, 1) -> turn about z -> (0.5 + slide, 0, 0) -> tool (0, 0, 0.1)
        in_base = np.array([0.0, 0.0, 1.0]) + rot_z(theta) @ [0.5 + slide, 0.0, 0.0]
        expected = np.array([1.0, 2.0, 0.0]) + rot_z(np.pi / 2) @ (in_base + np.array([0, 0, 0.1]))
        np.testing.assert_allclose(tool.translation[index], expected, atol=1e-12)
        np.testing.assert_allclose(tool.rotation[index], rot_z(np.pi / 2 + theta), atol=1e-12)


def test_npz_trajectory(tmp_path, cell):
    np.savez(tmp_path / "motion.npz", times=np.array([0.0, 2.0]),
             positions=np.array([[0.0, 0.0], [1.0, 0.2]]),
             joint_names=np.array(["turn", "slide"]))
    cell.write_text(cell.read_text().replace("motion.csv", "motion.npz"))
    tool = read_scene(cell).pose("r/link2", relative_to="r/base", times=[1.0])
    np.testing.assert_allclose(tool.translation[0],
                               [0.6 * np.cos(0.5), 0.6 * np.sin(0.5), 1.0], atol=1e-12)


def test_write_scene_round_trip(tmp_path, cell):
    tree = read_scene(cell)
    copy_path = tmp_path / "copy.yaml"
    write_scene(tree, copy_path)
    copy = read_scene(copy_path)
    assert copy.frames == tree.frames
    times = np.linspace(-1.0, 5.0, 25)  # between keyframes and samples, and outside them
    for frame in ("seam", "tool", "r/link1"):
        expected = tree.pose(frame, relative_to="world", times=times)
        actual = copy.pose(frame, relative_to="world", times=times)
        np.testing.assert_allclose(actual.matrix, expected.matrix, atol=1e-12)
    snapshot_path = tmp_path / "snapshot.yaml"
    write_scene(tree, snapshot_path, time=1.0)
    snapshot = read_scene(snapshot_path)
    assert not any(snapshot.is_moving(frame) for frame in snapshot.frames[1:])
    np.testing.assert_allclose(snapshot.pose("tool", relative_to="world").matrix,
                               tree.pose("tool", relative_to="world", times=[1.0]).matrix[0],
                               atol=1e-12)


def test_write_scene_refuses_half_turn_joint_steps(tmp_path, cell):
    (tmp_path / "motion.csv").write_text("time_s,turn,slide\n0,0,0\n1,3.2,0\n")
    with pytest.raises(UnsupportedFeatureError, match="half a turn"):
        write_scene(read_scene(cell), tmp_path / "out.yaml")
    assert not (tmp_path / "out.yaml").exists()


def test_reference_times(tmp_path):
    path = scene_file(tmp_path, """\
        pinframes_scene: 1
        reference_time: 2024-03-01T08:00:00
        frames:
          - name: cart
            parent: world
            keyframes:
              - {time: 2024-03-01T08:00:10, xyz: [0, 0, 0]}
              - {time: 20s, xyz: [1, 0, 0]}
        """)
    with pytest.raises(FileFormatError, match=r"keyframes\.time"):
        read_scene(path)  # absolute and relative keyframe times mixed
    path.write_text(path.read_text().replace("2024-03-01T08:00:10", "10s"))
    tree = read_scene(path)
    assert tree.reference_time == np.datetime64("2024-03-01T08:00:00")
    cart = tree.pose("cart", times=[np.datetime64("2024-03-01T08:00:15")])
    np.testing.assert_allclose(cart.translation, [[0.5, 0.0, 0.0]], atol=1e-12)


def test_curve_frames_from_points_and_from_an_arc(tmp_path):
    """A curve entry is Pose.along_curve: points with normals, or an arc's points with normals
    away from its centre; timed by speed, duration or times."""
    path = scene_file(tmp_path, """\
        pinframes_scene: 1
        reference_time: 2024-03-01T08:00:00
        frames:
          - name: bend
            parent: world
            curve:
              points: [[0, 0, 0], [3, 4, 0], [3, 4, 12]]
              normals: [[0, 0, 1], [0, 0, 1], [1, 0, 0]]
              speed: 2.0
          - name: flat
            parent: world
            reference_time: 2024-03-01T08:00:10
            curve: {points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], times: [0, 4s]}
          - name: girth
            parent: world
            curve:
              arc: {centre: [1, 0, 0], axis: [0, 0, 2], start: [1, -2, 5], angle: 1.5,
                    count: 4}
              duration: 3
        """)
    tree = read_scene(path)
    bend = tree.local_pose("bend")
    np.testing.assert_allclose(bend.seconds, [0.0, 2.5, 8.5], atol=1e-12)
    # chords of 5 and 12 m: 12 (3, 4, 0) / 5 + 5 (0, 0, 1), made unit
    np.testing.assert_allclose(bend.rotation[1, :, 0], np.array([36, 48, 25]) / 65, atol=1e-15)
    flat = tree.pose("flat", times=[np.datetime64("2024-03-01T08:00:11")])
    np.testing.assert_allclose(flat.translation, [[0.25, 0.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(flat.rotation[0], np.eye(3), atol=1e-15)
    # a circle of radius 2 about the line x = 1, y = 0 in the plane z = 5: angles -90 deg,
    # -60, -30, 0 at 0, 1, 2, 3 s; equal chords, so one second each
    girth = tree.local_pose("girth")
    angles = -np.pi / 2 + np.array([0.0, 0.5, 1.0, 1.5])
    outward = np.column_stack([np.cos(angles), np.sin(angles), np.zeros(4)])
    np.testing.assert_allclose(girth.seconds, [0.0, 1.0, 2.0, 3.0], atol=1e-9)
    np.testing.assert_allclose(girth.translation, [1, 0, 5] + 2 * outward, atol=1e-15)
    np.testing.assert_allclose(girth.rotation[1:3, :, 2], outward[1:3], atol=1e-15)
    tangent = np.column_stack([-np.sin(angles), np.cos(angles), np.zeros(4)])
    np.testing.assert_allclose(girth.rotation[1:3, :, 0], tangent[1:3], atol=1e-15)


_CURVE = "pinframes_scene: 1\nframes:\n- name: c\n  parent: world\n  curve: "


@pytest.mark.parametrize(
    ("curve", "expected"),
    [
        ("{points: [[0, 0, 0], [1, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: 1}",
         "field 'frames[0].curve.points[2]': point 2 repeats point 1"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [[0, 0, 1], [1, 0, 0]], speed: 1}",
         "field 'frames[0].curve.normals[1]': the normal of point 1 is parallel"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], times: [1, 0]}",
         "field 'frames[0].curve.times[1]'"),
        ("{points: [[0, 0, 0], [1, 0, 0]], speed: 1}", "field 'frames[0].curve.normals': "
         "missing"),
        ("{points: [[0, 0, 0], [1, 0]], normals: [0, 0, 1], speed: 1}",
         "field 'frames[0].curve.points[1]': expected a list of 3 numbers"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1]}",
         "field 'frames[0].curve': give one of speed"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: 1, duration: 1}",
         "field 'frames[0].curve': give one of speed"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: -1}",
         "field 'frames[0].curve.speed': expected a positive number"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], duration: .inf}",
         "field 'frames[0].curve.duration': the value must be finite"),
        ("{speed: 1}", "field 'frames[0].curve': give either points (with normals) or arc"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 1], start: [1, 0, 0], angle: 1, count: 1}, "
         "speed: 1}", "field 'frames[0].curve.arc.count': expected a whole number"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 1], start: [0, 0, 1], angle: 1, count: 9}, "
         "speed: 1}", "field 'frames[0].curve.arc': the arc has no length"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 0], start: [1, 0, 0], angle: 1, count: 9}, "
         "speed: 1}", "field 'frames[0].curve.arc.axis': the axis must not be zero"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 1], angle: 1, count: 9}, speed: 1}",
         "field 'frames[0].curve.arc.start': missing"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 1], start: [1, 0, 0], angle: x, count: 9}, "
         "speed: 1}", "field 'frames[0].curve.arc.angle': expected a number"),
        ("{arc: {centre: [0, 0, 0], axis: [0, 0, 1], start: [1, 0, 0], angle: 1, count: 9}, "
         "normals: [0, 0, 1], speed: 1}", "field 'frames[0].curve.normals': an arc's normals"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: 1, tilt: 2}",
         "field 'frames[0].curve': unknown key(s) tilt"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: 1}\n  xyz: [0, 0, 1]",
         "field 'frames[0].curve': a curve frame takes its pose from the curve"),
        ("{points: [[0, 0, 0], [1, 0, 0]], normals: [0, 0, 1], speed: 1}\n  keyframes: "
         "[{time: 0}]", "field 'frames[0].curve': give either keyframes or curve"),
    ],
)
def test_malformed_curves_name_the_entry_the_field_and_the_point(tmp_path, curve, expected):
    path = scene_file(tmp_path, _CURVE + curve + "\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(path)
    message = str(caught.value)
    assert message.startswith(f"{path}: frame 'c': "), message
    assert expected in message, message


@pytest.mark.parametrize(
    ("text", "error", "expected"),
    [
        ("name: x\n", FileFormatError, "not a pinframes scene"),
        ("pinframes_scene: 2\n", UnsupportedFeatureError, "field 'pinframes_scene': scene "
         "format version 2"),
        ("pinframes_scene: 1\nframe: []\n", FileFormatError, "unknown key(s) frame"),
        ("pinframes_scene: 1\nframes: {a: 1}\n", FileFormatError,
         "field 'frames': expected a list"),
        ("pinframes_scene: 1\nframes:\n- {parent: world}\n", FileFormatError,
         "field 'frames[0].name': missing"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world, xyz: [1, 2]}\n",
         FileFormatError, "frame 'a': field 'frames[0].xyz': expected a list of 3 numbers"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world, xyz: [1, 2, x]}\n",
         FileFormatError, "field 'frames[0].xyz'"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world, rpy: [0, 0, 0], "
         "quaternion: [0, 0, 0, 1]}\n", FileFormatError, "either rpy or quaternion"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world, quaternion: [0, 0, 0, 2]}\n",
         FileFormatError, "field 'frames[0].quaternion': quaternion (x, y, z, w) must have unit"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: nowhere}\n", FileFormatError,
         "frame 'a': field 'frames[0].parent': frame 'nowhere' is neither in the scene"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world}\n- {name: a, parent: world}\n",
         PinframesError, "frame 'a'"),
        ("pinframes_scene: 1\nframes:\n- name: a\n  parent: world\n  name: b\n", FileFormatError,
         "duplicate key 'name'"),
        ("pinframes_scene: 1\nframes:\n- {name: a, parent: world, keyframes: []}\n",
         FileFormatError, "field 'frames[0].keyframes': expected a non-empty list"),
        ("pinframes_scene: 1\nframes:\n- name: a\n  parent: world\n  keyframes:\n"
         "  - {time: 1}\n  - {time: 0}\n", FileFormatError, "strictly increasing"),
        ("pinframes_scene: 1\nframes:\n- name: a\n  parent: world\n  keyframes:\n"
         "  - {xyz: [0, 0, 0]}\n", FileFormatError, "field 'frames[0].keyframes[0].time'"),
        ("pinframes_scene: 1\nrobots:\n- {urdf: missing.urdf}\n", FileFormatError,
         "field 'robots[0].urdf': no such file"),
        ("pinframes_scene: 1\nlayers:\n- {file: cell.txt, mount: world}\n", FileFormatError,
         "field 'layers[0].file': no such file"),
    ],
)
def test_malformed_scenes_name_file_entry_and_field(tmp_path, text, error, expected):
    path = scene_file(tmp_path, text)
    with pytest.raises(error) as caught:
        read_scene(path)
    message = str(caught.value)
    assert message.startswith(str(path)), message
    assert expected in message, message


def test_errors_in_referenced_files_name_that_file_and_the_entry(tmp_path, cell):
    (tmp_path / "motion.csv").write_text("time_s,turn,elbow\n0,0,0\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(cell)
    message = str(caught.value)
    assert message.startswith(str(tmp_path / "motion.csv"))
    assert "no joint 'r/elbow'" in message
    assert f"referenced by {cell}: robots[0].trajectory" in message
    (tmp_path / "motion.csv").write_text("time_s,turn\n0,x\n")
    with pytest.raises(FileFormatError, match="field 'line 2': expected a number"):
        read_scene(cell)
    (tmp_path / "motion.csv").write_text("time_s,turn\n0,0\n")
    (tmp_path / "robots" / "arm.urdf").write_text("<robot name='arm'><link name='a'>")
    with pytest.raises(PinframesError) as caught:
        read_scene(cell)
    assert "robots[0].urdf" in str(caught.value)


def test_frames_yaml_layer_mounted_with_prefix(tmp_path):
    (tmp_path / "layers").mkdir()
    (tmp_path / "layers" / "frames.yaml").write_text(textwrap.dedent("""\
        version: 1.0
        frames:
          desk:
            relative_to: ~
            pose: {x: 1, y: 0, z: 0, roll: 0, pitch: 0, yaw: 1.5707963267948966}
          desk/lamp:
            relative_to: ~
            pose: {x: 0.5, y: 0, z: 0.2, roll: 0, pitch: 0, yaw: 0}
        """))
    path = scene_file(tmp_path, """\
        pinframes_scene: 1
        layers:
          - {file: layers/frames.yaml, mount: room, prefix: "L/"}
        frames:
          - {name: room, parent: world, xyz: [10, 0, 0], rpy: [0, 0, 3.141592653589793]}
        """)
    tree = read_scene(path)
    assert tree.parent("L/desk") == "room"
    assert tree.parent("L/desk/lamp") == "L/desk"
    # world -> room (10, 0, 0) turned 180 deg -> desk (1, 0, 0) turned 90 deg -> lamp
    expected = (np.array([10.0, 0, 0]) + rot_z(np.pi) @ (
        np.array([1.0, 0, 0]) + rot_z(np.pi / 2) @ np.array([0.5, 0, 0.2])))
    lamp = tree.pose("L/desk/lamp", relative_to="world")
    np.testing.assert_allclose(lamp.translation, expected, atol=1e-12)
    np.testing.assert_allclose(lamp.rotation, rot_z(3 * np.pi / 2), atol=1e-12)


def test_two_frames_yaml_layers_without_prefix_and_no_layer_file_details(tmp_path):
    """Each layer's reader keeps its file's top-level keys in tree metadata; the scene keeps
    neither (docs/scene-format.md), so two layers never clash over them."""
    (tmp_path / "a.yaml").write_text("version: 1.0\nframes:\n"
                                     "  desk: {relative_to: ~, pose: {x: 1}}\n")
    (tmp_path / "b.yaml").write_text("version: 1.0\nframes:\n"
                                     "  shelf: {relative_to: ~, pose: {y: 2}}\n")
    path = scene_file(tmp_path, """\
        pinframes_scene: 1
        layers:
          - {file: a.yaml, mount: world}
          - {file: b.yaml, mount: world}
        """)
    tree = read_scene(path)
    assert tree.frames == ["world", "desk", "shelf"]
    np.testing.assert_allclose(tree.pose("shelf", "world").translation, [0, 2, 0])
    assert tree.metadata == {}

def test_errors_inside_a_layer_name_the_layer_file(tmp_path):
    (tmp_path / "frames.yaml").write_text("frames:\n  a: {pose: {x: oops}}\n")
    path = scene_file(tmp_path, "pinframes_scene: 1\nlayers:\n- {file: frames.yaml}\n")
    with pytest.raises(FileFormatError) as caught:
        read_scene(path)
    message = str(caught.value)
    assert message.startswith(str(tmp_path / "frames.yaml"))
    assert f"(referenced by {path}: layers[0].file)" in message
