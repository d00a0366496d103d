"""A tree written to a folder replaces it only when it is a ROS 2 bag and nothing else: a
folder that merely holds a file named ``metadata.yaml`` (a thesis, a project) keeps every
file, and a symbolic link to a folder never empties what it points to."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import pinframes
from pinframes import FrameTree, Pose
from pinframes.errors import WriteError


def small_tree() -> FrameTree:
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 0.0, 0.8]))
    return tree


def rosbags_bag(folder: Path) -> None:
    """A ROS 2 bag folder written by rosbags' own writer (one String message)."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.LATEST)
    message = store.types["std_msgs/msg/String"](data="hello")
    with Writer(folder, version=8, storage_plugin=StoragePlugin.MCAP) as writer:
        connection = writer.add_connection("/chatter", "std_msgs/msg/String", typestore=store)
        writer.write(connection, 1, store.serialize_cdr(message, "std_msgs/msg/String"))


def thesis(folder: Path) -> dict[str, str]:
    """A thesis folder with a ``metadata.yaml`` of its own; its files and their text."""
    folder.mkdir()
    (folder / "data").mkdir()
    files = {"metadata.yaml": "title: Frames in time\nauthor: A. Student\n",
             "thesis.tex": "\\documentclass{report}\n", "data/run1.csv": "t,x\n0,1\n"}
    for name, text in files.items():
        (folder / name).write_text(text)
    return files


def contents(folder: Path) -> dict[str, str]:
    return {str(path.relative_to(folder)): path.read_text()
            for path in sorted(folder.rglob("*")) if path.is_file()}


def test_a_thesis_folder_with_a_metadata_yaml_keeps_every_file(tmp_path):
    folder = tmp_path / "project"
    files = thesis(folder)
    with pytest.raises(WriteError, match="not rosbag2 metadata") as caught:
        pinframes.write(small_tree(), folder)
    assert caught.value.file == str(folder)
    assert contents(folder) == files
    assert sorted(os.listdir(tmp_path)) == ["project"]  # no temporary left


def test_rosbag2_metadata_beside_other_files_names_the_first_stranger(tmp_path):
    folder = tmp_path / "run"
    rosbags_bag(folder)
    (folder / "notes.txt").write_text("keep me")
    (folder / "a_subfolder").mkdir()
    with pytest.raises(WriteError, match="'a_subfolder' is not one of the storage files"):
        pinframes.write(small_tree(), folder)
    assert (folder / "notes.txt").read_text() == "keep me"
    assert (folder / "a_subfolder").is_dir()


def test_a_bag_written_by_rosbags_is_replaced_whole(tmp_path):
    folder = tmp_path / "run"
    rosbags_bag(folder)
    assert sorted(os.listdir(folder)) == ["metadata.yaml", "run.mcap"]
    assert "/chatter" in (folder / "metadata.yaml").read_text()
    pinframes.write(small_tree(), folder)
    assert sorted(os.listdir(folder)) == ["metadata.yaml", "run.mcap"]
    assert "/chatter" not in (folder / "metadata.yaml").read_text()
    assert pinframes.read(folder).frames == ["world", "table"]


@pytest.mark.parametrize("make", [rosbags_bag, thesis])
def test_a_symbolic_link_to_a_folder_is_never_emptied(tmp_path, make):
    real = tmp_path / "real"
    make(real)
    before = {path.name for path in real.iterdir()}
    link = tmp_path / "link"
    link.symlink_to(real, target_is_directory=True)
    with pytest.raises(WriteError, match="symbolic link to a folder") as caught:
        pinframes.write(small_tree(), link)
    assert caught.value.file == str(link)
    assert {path.name for path in real.iterdir()} == before and link.is_symlink()
