"""Reading frames.yaml: hierarchy, relative_to, units and metadata, against hand-derived poses."""

import textwrap
import warnings
from pathlib import Path

import numpy as np
import pytest

from pinframes import FramesYamlWarning, read_frames_yaml

from geometry import rot_x, rot_z

HALF_PI = np.pi / 2


def rot_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def layer(folder: Path, text: str, name: str = "frames.yaml") -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text))
    return path


def world_translation(tree, name):
    return tree.pose(name, tree.root).translation


def test_keys_make_the_hierarchy_and_names_are_keys(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        version: 1.0
        frames:
          map_0: {relative_to: ~, pose: {x: 1.0, y: 2.0, z: 0, roll: 0, pitch: 0, yaw: 0}}
          map_0/light: {relative_to: ~, pose: {x: 0.6, y: 0.6}}
          map_0/light/bulb: {relative_to: ~, pose: {z: 0.3}}
        """))
    assert tree.frames == ["world", "map_0", "map_0/light", "map_0/light/bulb"]
    assert tree.parent("map_0") == "world"
    assert tree.parent("map_0/light/bulb") == "map_0/light"
    np.testing.assert_allclose(world_translation(tree, "map_0/light/bulb"), [1.6, 2.6, 0.3],
                               atol=1e-15)


def test_root_name_is_chosen_by_the_caller(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, "frames: {a: {pose: {x: 1}}}\n"), root="city")
    assert tree.root == "city"
    assert tree.parent("a") == "city"


def test_roll_pitch_yaw_follow_urdf(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        frames:
          a: {pose: {x: 0.1, y: -0.2, z: 0.3, roll: 0.3, pitch: -0.2, yaw: 1.1}}
        """))
    pose = tree.local_pose("a")
    np.testing.assert_allclose(pose.rotation, rot_z(1.1) @ rot_y(-0.2) @ rot_x(0.3), atol=1e-15)
    np.testing.assert_allclose(pose.translation, [0.1, -0.2, 0.3], atol=0)


def test_partial_and_missing_poses_default_to_zero(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        frames:
          a: {relative_to: ~, pose: {y: 0.9}}
          b: {relative_to: ~}
          c: {}
        """))
    np.testing.assert_array_equal(tree.local_pose("a").matrix[:3, 3], [0.0, 0.9, 0.0])
    for name in "abc":
        np.testing.assert_array_equal(tree.local_pose(name).rotation, np.eye(3))
    np.testing.assert_array_equal(tree.local_pose("b").matrix, np.eye(4))
    np.testing.assert_array_equal(tree.local_pose("c").matrix, np.eye(4))


def test_relative_to_is_resolved_into_the_key_parent(tmp_path):
    # a at (1, 0, 0) turned 90 degrees; a/b 2 m along a's x: (1, 2, 0) in the world, turned
    # 90 degrees. c/d is given 1 m along b's x (the world's +y) and turned 90 degrees more:
    # (1, 3, 0) turned 180 degrees in the world, so (1, 4, 0) in c at (0, -1, 0).
    tree = read_frames_yaml(layer(tmp_path, f"""
        frames:
          a: {{pose: {{x: 1, yaw: {HALF_PI!r}}}}}
          a/b: {{relative_to: ~, pose: {{x: 2}}}}
          c: {{pose: {{y: -1}}}}
          c/d: {{relative_to: a/b, pose: {{x: 1, yaw: {HALF_PI!r}}}}}
        """))
    assert tree.parent("c/d") == "c"
    local = tree.local_pose("c/d")
    np.testing.assert_allclose(local.translation, [1.0, 4.0, 0.0], atol=1e-14)
    np.testing.assert_allclose(local.rotation, rot_z(np.pi), atol=1e-15)
    in_b = tree.pose("c/d", "a/b")
    np.testing.assert_allclose(in_b.translation, [1.0, 0.0, 0.0], atol=1e-14)
    np.testing.assert_allclose(in_b.rotation, rot_z(HALF_PI), atol=1e-15)
    kept = tree.frame_metadata("c/d")["frames_yaml"]
    assert kept["relative_to"] == "a/b"
    assert kept["entry"] == {"relative_to": "a/b", "pose": {"x": 1, "yaw": HALF_PI}}
    np.testing.assert_allclose(kept["pose_in_relative_to"].translation, [1.0, 0.0, 0.0])


def test_the_documentation_example(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        version: 1.0
        frames:
          map_0: {relative_to: ~, pose: {x: 0, y: 0, z: 0, roll: 0, pitch: 0, yaw: 0}}
          map_0/street_light_0:
            relative_to: ~
            pose: {x: 0.6, y: 0.6, z: 0, roll: 0, pitch: 0, yaw: 3.1415}
          map_0/vehicle_0:
            relative_to: map_0/street_light_0
            pose: {x: 1.0, y: 0, z: 0, roll: 0, pitch: 0, yaw: 0}
        """))
    expected = np.array([0.6 + np.cos(3.1415), 0.6 + np.sin(3.1415), 0.0])
    np.testing.assert_allclose(tree.local_pose("map_0/vehicle_0").translation, expected,
                               atol=1e-15)
    assert tree.parent("map_0/vehicle_0") == "map_0"


def test_empty_relative_to_means_the_key_parent(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        frames:
          m: {relative_to: '', pose: {x: 1, y: 1}}
          m/t: {relative_to: '', pose: {x: 0.5, yaw: 1.0}}
        """))
    np.testing.assert_array_equal(tree.local_pose("m/t").translation, [0.5, 0.0, 0.0])
    np.testing.assert_allclose(world_translation(tree, "m/t"), [1.5, 1.0, 0.0], atol=1e-15)
    assert tree.frame_metadata("m/t")["frames_yaml"]["relative_to"] is None


def test_a_child_may_come_before_its_parent(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, """
        frames:
          car/camera: {relative_to: ~, pose: {x: 0.1}}
          car: {relative_to: ~, pose: {x: 2.0}}
        """))
    assert tree.parent("car/camera") == "car"
    assert tree.frame_metadata("car")["frames_yaml"].get("dummy") is None
    np.testing.assert_allclose(world_translation(tree, "car/camera"), [2.1, 0.0, 0.0])
    assert [tree.frame_metadata(n)["frames_yaml"]["index"] for n in ("car/camera", "car")] == [
        0, 1]


def test_missing_ancestors_are_dummy_frames_at_the_identity(tmp_path):
    tree = read_frames_yaml(layer(tmp_path, "frames: {a/b/c: {pose: {x: 3}}}\n"))
    assert tree.frames == ["world", "a", "a/b", "a/b/c"]
    for dummy in ("a", "a/b"):
        np.testing.assert_array_equal(tree.local_pose(dummy).matrix, np.eye(4))
        assert tree.frame_metadata(dummy)["frames_yaml"] == {"key": dummy, "dummy": True}
    np.testing.assert_array_equal(world_translation(tree, "a/b/c"), [3.0, 0.0, 0.0])


def test_an_undeclared_relative_to_target_is_a_dummy_and_warns(tmp_path):
    path = layer(tmp_path, """
        frames:
          p: {pose: {x: 1}}
          s/t: {relative_to: p/q, pose: {y: 2}}
        """)
    with pytest.warns(FramesYamlWarning, match=r"'s/t'.*relative_to names 'p/q'"):
        tree = read_frames_yaml(path)
    assert tree.parent("p/q") == "p"
    assert tree.frame_metadata("p/q")["frames_yaml"]["dummy"] is True
    np.testing.assert_array_equal(tree.local_pose("p/q").matrix, np.eye(4))
    np.testing.assert_allclose(world_translation(tree, "s/t"), [1.0, 2.0, 0.0])


@pytest.mark.parametrize(("text", "version"), [
    ("version: 1.0\n", 1.0), ("version: '1.0'\n", "1.0"), ("", None)])
def test_version_may_be_a_float_a_string_or_missing(tmp_path, text, version):
    tree = read_frames_yaml(layer(tmp_path, text + "frames: {a: {}}\n"))
    top_level = tree.metadata["frames_yaml"]["top_level"]
    assert top_level.get("version") == version
    assert type(top_level.get("version")) is type(version)


def test_tiles_are_converted_with_the_nearest_listed_ancestor(tmp_path):
    layer(tmp_path, """
        tile_maps:
          m: {tile_size: {x: 0.5, y: 0.25}}
          m/inner: {tile_size: {x: 2.0, y: 4.0}}
        """, name="tile_maps.yaml")
    tree = read_frames_yaml(layer(tmp_path, """
        frames:
          m: {pose: {x: 10}}
          m/t: {relative_to: ~, unit: tiles, pose: {x: 2, y: 3, z: 0.1, yaw: 1.0}}
          m/sub/t: {unit: tiles, pose: {x: 1}}
          m/inner/t: {unit: tiles, pose: {x: 1, y: -1}}
          m/metres: {unit: meters, pose: {x: 1, y: 1}}
        """))
    local = tree.local_pose("m/t")
    np.testing.assert_allclose(local.translation, [2.5 * 0.5, 3.5 * 0.25, 0.1], atol=1e-15)
    np.testing.assert_allclose(local.rotation, rot_z(1.0), atol=1e-15)
    np.testing.assert_allclose(tree.local_pose("m/sub/t").translation, [0.75, 0.125, 0.0])
    np.testing.assert_allclose(tree.local_pose("m/inner/t").translation, [3.0, -2.0, 0.0])
    np.testing.assert_allclose(tree.local_pose("m/metres").translation, [1.0, 1.0, 0.0])
    assert tree.frame_metadata("m/t")["frames_yaml"]["tile_size"] == (0.5, 0.25)


def test_tiles_with_relative_to_convert_before_resolving(tmp_path):
    layer(tmp_path, "tile_maps: {m: {tile_size: {x: 1.0, y: 1.0}}}\n", name="tile_maps.yaml")
    tree = read_frames_yaml(layer(tmp_path, f"""
        frames:
          m: {{}}
          m/a: {{pose: {{x: 5, yaw: {HALF_PI!r}}}}}
          m/b: {{relative_to: m/a, unit: tiles, pose: {{x: 1, y: 0}}}}
        """))
    # (1.5, 0.5) tiles-to-metres in a, whose x axis is m's +y: m/a + (-0.5, 1.5).
    np.testing.assert_allclose(tree.local_pose("m/b").translation, [4.5, 1.5, 0.0], atol=1e-14)


def test_twist_and_unknown_fields_are_kept(tmp_path):
    path = layer(tmp_path, """
        frames:
          car:
            relative_to: ~
            pose: {x: 1}
            twist: {v_x: 0.5, w_z: 0.1}
            colour: red
        """)
    with pytest.warns(FramesYamlWarning, match="unknown field 'colour'"):
        tree = read_frames_yaml(path)
    entry = tree.frame_metadata("car")["frames_yaml"]["entry"]
    assert entry["twist"] == {"v_x": 0.5, "w_z": 0.1}
    assert entry["colour"] == "red"


def test_a_clean_file_reads_without_warnings(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_frames_yaml(layer(tmp_path, "version: '1.0'\nframes: {a: {pose: {x: 1}}}\n"))
