"""Real Duckietown maps written by others (../shared/data/duckietown-maps, skipped if absent)."""

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml

from conftest import SHARED_DATA
from pinframes import FramesYamlWarning, read_frames_yaml, write_frames_yaml
from pinframes.errors import FileFormatError

MAPS = SHARED_DATA / "duckietown-maps"
FOLDERS = sorted(p.name for p in MAPS.iterdir() if p.is_dir()) if MAPS.is_dir() else []
MALFORMED = "dt-gui-tools__test"

pytestmark = pytest.mark.skipif(not MAPS.is_dir(), reason=f"{MAPS} is absent")


def read_quietly(path: Path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FramesYamlWarning)
        return read_frames_yaml(path)


def ordered(data):
    if isinstance(data, dict):
        return [(key, ordered(value)) for key, value in data.items()]
    return data


def world_translations(tree) -> dict[str, np.ndarray]:
    return {name: tree.pose(name, tree.root).translation for name in tree.frames[1:]}


@pytest.mark.parametrize("folder", [f for f in FOLDERS if f != MALFORMED])
def test_every_real_map_is_written_back_without_loss(tmp_path, folder):
    source = MAPS / folder / "frames.yaml"
    tree = read_quietly(source)
    shutil.copy(MAPS / folder / "tile_maps.yaml", tmp_path)
    out = tmp_path / "frames.yaml"
    write_frames_yaml(tree, out)
    assert ordered(yaml.safe_load(out.read_text())) == ordered(
        yaml.safe_load(source.read_text()))
    again = read_quietly(out)
    assert again.frames == tree.frames
    for name in tree.frames[1:]:
        np.testing.assert_array_equal(again.local_pose(name).matrix,
                                      tree.local_pose(name).matrix, err_msg=name)


@pytest.mark.filterwarnings("ignore::pinframes.FramesYamlWarning")
@pytest.mark.parametrize("folder", [f for f in FOLDERS if f != MALFORMED])
def test_every_real_map_survives_a_rewrite_in_metres(tmp_path, folder):
    tree = read_quietly(MAPS / folder / "frames.yaml")
    out = tmp_path / "frames.yaml"  # no tile_maps.yaml here: tiles must become metres
    write_frames_yaml(tree, out)
    assert "tiles" not in out.read_text()
    again = read_quietly(out)
    for name in tree.frames[1:]:
        np.testing.assert_allclose(again.pose(name, "world").matrix,
                                   tree.pose(name, "world").matrix, atol=1e-12, err_msg=name)


@pytest.mark.skipif(MALFORMED not in FOLDERS, reason="the malformed map is absent")
def test_the_malformed_map_editor_file_is_reported():
    with pytest.raises(FileFormatError) as info:
        read_frames_yaml(MAPS / MALFORMED / "frames.yaml")
    assert (info.value.frame, info.value.field) == ("map_1/citizen1", "pose")
    assert "duplicate key 'pose'" in str(info.value)


def test_tiles_and_metres_versions_of_loop_0_coincide():
    """SPEC 8: metres = (v + 0.5) * tile_size; all 34 frame origins of the 2022 (metres) and
    2024 (tiles) versions of loop_0 coincide. (The two versions turn 11 tiles differently:
    their yaws change by a quarter or half turn, a change of content, not of units.)"""
    tiles = read_frames_yaml(MAPS / "duckiematrix-examples__loop_0" / "frames.yaml")
    metres = read_frames_yaml(MAPS / "duckiematrix-examples__loop_0_2022_meters" / "frames.yaml")
    in_tiles, in_metres = world_translations(tiles), world_translations(metres)
    assert len(in_tiles) == 34
    assert sorted(in_tiles) == sorted(in_metres)
    for name, origin in in_tiles.items():
        np.testing.assert_allclose(origin, in_metres[name], atol=1e-12, err_msg=name)
    # One tile by hand: tile_2_3 is at tiles (2, 3), tile size 0.585 m.
    np.testing.assert_allclose(in_tiles["map_0/tile_2_3"], [2.5 * 0.585, 3.5 * 0.585, 0.0])


def test_hand_checked_poses_of_a_duckietown_world_map():
    path = MAPS / "duckietown-world__gd2_udem1" / "frames.yaml"
    with pytest.warns(FramesYamlWarning, match="'map_1/tile_2_2'"):
        tree = read_frames_yaml(path)
    origins = world_translations(tree)
    np.testing.assert_allclose(origins["watchtower1/watchtower2"], [0.585, 1.0, 0.0])
    np.testing.assert_allclose(origins["map_1/tile_2_2/watchtower3"], [-0.35, 0.35, 0.0])
    np.testing.assert_allclose(origins["map_1/duckie1"], [3.7, 1.0, 0.0])
    assert tree.frame_metadata("map_1/tile_2_2")["frames_yaml"]["dummy"] is True


def test_a_child_declared_before_its_parent_in_loop_0():
    tree = read_frames_yaml(MAPS / "duckiematrix-examples__loop_0" / "frames.yaml")
    assert tree.parent("map_0/vehicle_0/camera") == "map_0/vehicle_0"
    np.testing.assert_allclose(world_translations(tree)["map_0/vehicle_0/camera"],
                               [0.8799999999999999, 0.18499999999999986, 0.0], atol=1e-15)
