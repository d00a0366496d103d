"""Writing frames.yaml: verbatim round trips, foreign trees, edits after reading, refusals."""

import textwrap
from pathlib import Path

import numpy as np
import pytest
import yaml

from pinframes import FramesYamlWarning, FrameTree, Pose, read_frames_yaml, write_frames_yaml
from pinframes.errors import UnsupportedFeatureError, WriteError

from geometry import rot_z

HALF_PI = np.pi / 2

CITY = f"""\
version: 1.0
frames:
  map_0/car/camera: {{relative_to: '', pose: {{x: 0.1, z: 0.2}}}}
  map_0: {{relative_to: ~, pose: {{x: 1.0, y: 2.0, z: 0, roll: 0, pitch: 0, yaw: 0}}}}
  map_0/light: {{relative_to: map_0, pose: {{x: 0.5, yaw: {HALF_PI!r}}}}}
  map_0/car:
    relative_to: map_0/light
    pose: {{x: 1}}
    twist: {{v_x: 0.3}}
  map_0/tile_1_2: {{relative_to: ~, unit: tiles, pose: {{x: 1, y: 2, yaw: 0}}}}
  map_0/sign/post: {{pose: {{y: 3}}}}
"""
TILE_MAPS = "tile_maps:\n  map_0: {tile_size: {x: 0.5, y: 0.5}}\n"


def city(folder: Path) -> Path:
    folder.mkdir(exist_ok=True)
    (folder / "tile_maps.yaml").write_text(TILE_MAPS)
    path = folder / "frames.yaml"
    path.write_text(CITY)
    return path


def as_read(path: Path) -> dict:
    """The file as plain YAML data, in file order."""
    return yaml.safe_load(path.read_text())


def ordered(data):
    """Data with every mapping turned into a list of pairs, so order counts in comparisons."""
    if isinstance(data, dict):
        return [(key, ordered(value)) for key, value in data.items()]
    return data


def world_poses(tree: FrameTree) -> dict[str, np.ndarray]:
    return {name: tree.pose(name, tree.root).matrix for name in tree.frames[1:]}


def assert_same_world(a: FrameTree, b: FrameTree, names=None) -> None:
    poses_a, poses_b = world_poses(a), world_poses(b)
    for name in names or poses_a:
        np.testing.assert_allclose(poses_b[name], poses_a[name], atol=1e-12, err_msg=name)


def test_a_read_tree_is_written_back_unchanged(tmp_path):
    source = city(tmp_path / "in")
    tree = read_frames_yaml(source)
    out = tmp_path / "in" / "copy.yaml"
    write_frames_yaml(tree, out)
    assert ordered(as_read(out)) == ordered(as_read(source))
    assert "relative_to: ~" in out.read_text()
    assert_same_world(tree, read_frames_yaml(out))


def test_a_foreign_tree_gets_keys_from_paths_and_poses_in_parents(tmp_path):
    tree = FrameTree()
    tree.add("a", "world", Pose.from_xyz_rpy(1.0, 2.0, 3.0, 0.1, 0.2, 0.3))
    tree.add("b", "a", Pose([0.5, 0.0, 0.0], rot_z(HALF_PI)))
    tree.add("c", "world")
    out = tmp_path / "frames.yaml"
    write_frames_yaml(tree, out)
    data = as_read(out)
    assert data["version"] == 1.0
    assert list(data["frames"]) == ["a", "a/b", "c"]
    assert all(entry["relative_to"] is None for entry in data["frames"].values())
    b = data["frames"]["a/b"]["pose"]
    assert list(b) == ["x", "y", "z", "roll", "pitch", "yaw"]
    np.testing.assert_allclose([b[f] for f in ("x", "y", "z", "roll", "pitch")], 0.0 + np.array(
        [0.5, 0, 0, 0, 0]), atol=1e-15)
    assert b["yaw"] == pytest.approx(HALF_PI, abs=1e-15)
    assert data["frames"]["c"]["pose"] == dict.fromkeys(("x", "y", "z", "roll", "pitch", "yaw"),
                                                         0.0)
    again = read_frames_yaml(out)
    assert again.parent("a/b") == "a"
    np.testing.assert_allclose(again.pose("a/b", "world").matrix, tree.pose("b", "world").matrix,
                               atol=1e-15)


def test_names_that_already_are_keys_are_not_doubled(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.add("map_0/car/mirror", "map_0/car", Pose([0.0, 0.4, 0.0]))
    tree.add("bumper", "map_0/car", Pose([0.9, 0.0, 0.0]))
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    frames = as_read(out)["frames"]
    assert list(frames)[-2:] == ["map_0/car/mirror", "map_0/car/bumper"]
    again = read_frames_yaml(out)
    np.testing.assert_allclose(again.pose("map_0/car/bumper", "world").matrix,
                               tree.pose("bumper", "world").matrix, atol=1e-15)


@pytest.mark.parametrize(("name", "parent"), [("x/y", "world"), ("p/q/r", "p"), ("q/r", "p")])
def test_a_slash_that_would_move_a_frame_is_refused(tmp_path, name, parent):
    tree = FrameTree()
    tree.add("p", "world")
    tree.add(name, parent)
    with pytest.raises(UnsupportedFeatureError) as info:
        write_frames_yaml(tree, tmp_path / "frames.yaml")
    assert info.value.frame == name
    assert not (tmp_path / "frames.yaml").exists()


def test_a_slash_that_matches_the_parent_key_is_kept(tmp_path):
    tree = FrameTree()
    tree.add("p", "world")
    tree.add("p/q", "p", Pose([1.0, 0.0, 0.0]))
    tree.add("r", "p/q")
    write_frames_yaml(tree, tmp_path / "frames.yaml")
    assert list(as_read(tmp_path / "frames.yaml")["frames"]) == ["p", "p/q", "p/q/r"]


def test_two_frames_with_one_key_are_refused(tmp_path):
    tree = FrameTree()
    tree.add("a", "world")
    tree.add("b", "a")
    tree.add("a/b", "a")
    with pytest.raises(UnsupportedFeatureError, match="'b' and 'a/b' would both get the key"):
        write_frames_yaml(tree, tmp_path / "frames.yaml")


def moving_tree() -> FrameTree:
    tree = FrameTree()
    tree.add("cart", "world", Pose([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], times=[0.0, 2.0]))
    tree.add("cart/arm", "cart", Pose([0.0, 1.0, 0.0]))
    return tree


def test_moving_frames_are_refused_without_a_time(tmp_path):
    out = tmp_path / "frames.yaml"
    out.write_text("old content\n")
    with pytest.raises(UnsupportedFeatureError, match="pass time=") as info:
        write_frames_yaml(moving_tree(), out)
    assert info.value.frame == "cart"
    assert out.read_text() == "old content\n"
    assert [p.name for p in tmp_path.iterdir()] == ["frames.yaml"]


def test_moving_frames_are_written_at_a_given_time(tmp_path):
    out = tmp_path / "frames.yaml"
    write_frames_yaml(moving_tree(), out, time=0.5)
    frames = as_read(out)["frames"]
    assert frames["cart"]["pose"]["x"] == pytest.approx(0.5, abs=1e-15)
    assert frames["cart/arm"]["pose"]["y"] == pytest.approx(1.0, abs=1e-15)


def test_a_missing_folder_is_a_write_error(tmp_path):
    with pytest.raises(WriteError):
        write_frames_yaml(moving_tree(), tmp_path / "nowhere" / "frames.yaml", time=0.0)


def test_a_changed_pose_is_written_in_its_relative_to_frame(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.set_local_pose("map_0/car", Pose([0.5, 1.5, 0.0]))
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    car = as_read(out)["frames"]["map_0/car"]
    # light sits at (0.5, 0, 0) in map_0 turned 90 degrees: map_0's (0.5, 1.5) is (1.5, 0)
    # in light, turned -90 degrees.
    assert car["relative_to"] == "map_0/light"
    np.testing.assert_allclose([car["pose"][f] for f in ("x", "y", "z")], [1.5, 0.0, 0.0],
                               atol=1e-15)
    assert car["pose"]["yaw"] == pytest.approx(-HALF_PI, abs=1e-15)
    assert car["twist"] == {"v_x": 0.3}
    assert_same_world(tree, read_frames_yaml(out))


def test_moving_a_relative_to_target_rewrites_its_dependants(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.set_local_pose("map_0/light", Pose([0.0, 0.0, 0.0]))
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    frames = as_read(out)["frames"]
    assert frames["map_0/light"]["pose"]["x"] == 0.0
    assert frames["map_0/car"]["relative_to"] == "map_0/light"
    assert_same_world(tree, read_frames_yaml(out))


def test_remove_and_add_is_written_as_a_new_frame(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.remove("map_0/light")
    tree.add("map_0/light", "map_0", Pose([7.0, 0.0, 0.0]))
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    frames = as_read(out)["frames"]
    assert list(frames)[-1] == "map_0/light"
    assert frames["map_0/light"]["relative_to"] is None
    assert frames["map_0/light"]["pose"]["x"] == 7.0
    assert frames["map_0/car"]["relative_to"] == "map_0/light"
    assert_same_world(tree, read_frames_yaml(out))


def test_removing_a_relative_to_target_falls_back_to_the_key_parent(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.remove("map_0/light")
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    car = as_read(out)["frames"]["map_0/car"]
    assert car["relative_to"] is None
    # car was 1 m along light's x (map_0's +y) from light at (0.5, 0, 0), turned 90 degrees.
    np.testing.assert_allclose([car["pose"][f] for f in ("x", "y", "z")], [0.5, 1.0, 0.0],
                               atol=1e-15)
    assert_same_world(tree, read_frames_yaml(out))


def test_renames_are_followed_by_keys_and_relative_to(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.rename("map_0/light", "map_0/lamp")
    tree.rename("map_0/car", "truck")
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    data = as_read(out)
    expected = as_read(tmp_path / "frames.yaml")
    frames = data["frames"]
    assert list(frames) == [key.replace("map_0/light", "map_0/lamp").replace(
        "map_0/car", "map_0/truck") for key in expected["frames"]]
    assert frames["map_0/truck"] == {**expected["frames"]["map_0/car"],
                                     "relative_to": "map_0/lamp"}
    again = read_frames_yaml(out)
    np.testing.assert_allclose(again.pose("map_0/truck/camera", "world").matrix,
                               tree.pose("map_0/car/camera", "world").matrix, atol=1e-15)


def test_renaming_a_tile_map_writes_its_tiles_in_metres(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.rename("map_0", "city")
    out = tmp_path / "out.yaml"
    with pytest.warns(FramesYamlWarning, match="1 'unit: tiles' frames .* written in metres"):
        write_frames_yaml(tree, out)
    tile = as_read(out)["frames"]["city/tile_1_2"]
    assert "unit" not in tile
    np.testing.assert_allclose([tile["pose"][f] for f in ("x", "y")], [0.75, 1.25], atol=1e-15)
    again = read_frames_yaml(out)
    np.testing.assert_allclose(again.pose("city/tile_1_2", "world").matrix,
                               tree.pose("map_0/tile_1_2", "world").matrix, atol=1e-15)


def test_tiles_stay_tiles_only_beside_a_matching_tile_maps_yaml(tmp_path):
    tree = read_frames_yaml(city(tmp_path / "in"))
    (tmp_path / "same").mkdir()
    (tmp_path / "same" / "tile_maps.yaml").write_text(TILE_MAPS)
    write_frames_yaml(tree, tmp_path / "same" / "frames.yaml")
    assert as_read(tmp_path / "same" / "frames.yaml")["frames"]["map_0/tile_1_2"]["unit"] == (
        "tiles")
    (tmp_path / "alone").mkdir()
    with pytest.warns(FramesYamlWarning, match="written in metres"):
        write_frames_yaml(tree, tmp_path / "alone" / "frames.yaml")
    tile = as_read(tmp_path / "alone" / "frames.yaml")["frames"]["map_0/tile_1_2"]
    assert "unit" not in tile
    assert (tile["pose"]["x"], tile["pose"]["y"]) == pytest.approx((0.75, 1.25), abs=1e-15)


def test_dummies_are_implied_unless_they_changed(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    assert "map_0/sign" not in as_read(out)["frames"]
    tree.set_local_pose("map_0/sign", Pose([0.0, 0.0, 1.0]))
    write_frames_yaml(tree, out)
    assert as_read(out)["frames"]["map_0/sign"]["pose"]["z"] == 1.0
    assert_same_world(tree, read_frames_yaml(out))


def test_a_dummy_left_without_children_is_still_written(tmp_path):
    tree = read_frames_yaml(city(tmp_path))
    tree.remove("map_0/sign/post")
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    assert "map_0/sign" in as_read(out)["frames"]
    assert "map_0/sign" in read_frames_yaml(out)


def test_version_and_unknown_fields_are_written_back(tmp_path):
    source = tmp_path / "frames.yaml"
    source.write_text(textwrap.dedent("""\
        version: '1.0'
        frames:
          a: {relative_to: ~, pose: {x: 1, theta: 2}, colour: red}
        author: someone
        """))
    with pytest.warns(FramesYamlWarning):
        tree = read_frames_yaml(source)
    out = tmp_path / "out.yaml"
    write_frames_yaml(tree, out)
    assert ordered(as_read(out)) == ordered(as_read(source))
