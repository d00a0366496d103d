"""`pinframes.read` / `pinframes.write`: one registry picks the format from the file."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

import pinframes
from pinframes import FileFormatError, FrameTree, Pose


def _tree() -> FrameTree:
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 2.0, 0.5]))
    tree.add("tool", "table", Pose([0.0, 0.0, 0.25], [0.0, 0.0, 1.0, 0.0]))
    return tree


def _named(tree: FrameTree, last: str) -> str:
    (name,) = [frame for frame in tree.frames if frame.split("/")[-1] == last]
    return name


@pytest.mark.parametrize(("name", "expected"), [
    ("cell.yaml", "scene"), ("frames.yaml", "frames.yaml"), ("cell.asdf", "asdf"),
    ("cell.urdf", "urdf"),
])
def test_write_then_read_by_suffix(tmp_path, name, expected):
    path = tmp_path / name
    pinframes.write(_tree(), path)
    assert pinframes.formats.detect_format(path) == expected
    tree = pinframes.read(path)
    tool = _named(tree, "tool")  # frames.yaml names frames by their path ("table/tool")
    pose = tree.pose(tool, tree.root)
    # hand-derived: table at (1, 2, 0.5), tool 0.25 m above it, turned half a turn about z
    np.testing.assert_allclose(pose.translation, [1.0, 2.0, 0.75], atol=1e-12)
    np.testing.assert_allclose(pose.rotation, np.diag([-1.0, -1.0, 1.0]), atol=1e-12)


def test_an_explicit_format_wins_over_the_suffix(tmp_path):
    path = tmp_path / "cell.yaml"
    pinframes.write(_tree(), path, "frames.yaml")
    assert "frames" in pinframes.formats.InputFile(path).yaml()
    tree = pinframes.read(path, "frames.yaml")
    assert tree.parent(_named(tree, "tool")) == _named(tree, "table")


def test_unknown_suffix_option_and_format(tmp_path):
    with pytest.raises(FileFormatError, match=r"unknown file type '\.txt'"):
        pinframes.write(_tree(), tmp_path / "cell.txt")
    with pytest.raises(FileFormatError, match="URDF files take no 'schema' option"):
        pinframes.write(_tree(), tmp_path / "cell.urdf", schema="1.0.0")
    with pytest.raises(FileFormatError, match="unknown format 'obj'"):
        pinframes.write(_tree(), tmp_path / "cell.urdf", "obj")
    assert not list(tmp_path.iterdir())


def test_telling_an_asdf_file_reads_only_its_first_bytes(tmp_path):
    # detection read the whole file to look at its first 4 kB: here a sparse terabyte
    path = tmp_path / "huge.asdf"
    with open(path, "wb") as handle:
        handle.write(b"#ASDF 1.0.0\n")
        handle.truncate(2**40)
    assert pinframes.formats.detect_format(path) == "asdf"


_COUNT_OPENS = """
import os, sys
import pinframes
path = os.path.realpath(sys.argv[1])
opened = []
def count(event, args):
    if event == "open" and isinstance(args[0], (str, os.PathLike)):
        if os.path.realpath(args[0]) == path:
            opened.append(args[0])
sys.addaudithook(count)
pinframes.read(sys.argv[1])
print(len(opened))
"""


@pytest.mark.parametrize("name", ["cell.yaml", "frames.yaml", "cell.urdf"])
def test_read_opens_a_small_tree_file_once(tmp_path, name):
    # detection and the reader shared nothing: a scene was read 3 times and parsed twice
    path = tmp_path / name
    pinframes.write(_tree(), path)
    assert path.stat().st_size < 4096
    done = subprocess.run([sys.executable, "-c", _COUNT_OPENS, str(path)],
                          capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "1", done.stdout


def test_the_reader_gets_what_detection_read(tmp_path):
    path = tmp_path / "cell.yaml"
    pinframes.write(_tree(), path)
    source = pinframes.formats.InputFile(path)
    assert pinframes.formats.detect_format(source) == "scene"
    path.write_text("not: a scene\n")  # read already: the reader does not look again
    assert "tool" in pinframes.read(source).frames


@pytest.mark.parametrize(("suffix", "looks_like"), [
    (".csv", "a CSV table of poses"), (".json", "a JSON file of poses"),
    (".npz", "a ZIP archive of poses")])
def test_a_pose_file_given_as_a_tree_is_named_by_its_own_content_test(tmp_path, suffix,
                                                                      looks_like):
    pose = Pose([1.0, 2.0, 3.0], times=None)
    path = tmp_path / f"poses{suffix}"
    pinframes.write_poses(pose, path)
    with pytest.raises(FileFormatError, match=looks_like):
        pinframes.read(path)
    renamed = path.rename(tmp_path / "poses.yaml")  # told by content, whatever the name
    with pytest.raises(FileFormatError, match=looks_like):
        pinframes.read(renamed)


def test_each_tree_format_says_which_other_files_it_reads(tmp_path):
    (tmp_path / "layer").mkdir()
    pinframes.write(_tree(), tmp_path / "layer" / "frames.yaml")
    scene = tmp_path / "scene.yaml"
    scene.write_text("pinframes_scene: 1\nlayers: [{file: layer/frames.yaml}]\n"
                     "robots: [{urdf: arm.urdf, trajectory: motion.csv}]\n")
    assert pinframes.formats.files_read(scene) == [
        scene, tmp_path / "layer" / "frames.yaml", tmp_path / "layer" / "tile_maps.yaml",
        tmp_path / "arm.urdf", tmp_path / "motion.csv"]
    pinframes.write(_tree(), tmp_path / "cell.asdf")
    assert pinframes.formats.files_read(tmp_path / "cell.asdf") == [tmp_path / "cell.asdf"]
