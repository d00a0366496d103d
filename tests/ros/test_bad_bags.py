"""Bad bags are pinframes errors naming the bag: truncated or corrupt files, an unknown
storage, a folder without metadata, no tf messages, topics of the wrong type, limits."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import pinframes
from pinframes.errors import FileFormatError, PinframesError, ReadError

from ros.bag_writing import (
    JOINT_STATE,
    STORAGES,
    Message,
    Transform,
    joint_state,
    ros_version_of,
    string,
    tf_messages,
    write_bag,
)

SECOND = 1_000_000_000
START = 1_700_000_000 * SECOND


def _good_bag(tmp_path: Path, storage: str, count: int = 200) -> Path:
    version = ros_version_of(storage)
    return write_bag(tmp_path / "good", storage, tf_messages(version, [
        Transform("world", "tool", START + i * SECOND // 10, (i, 0, 0)) for i in range(count)]))


def _storage_file(bag: Path) -> Path:
    return bag if bag.is_file() else next(f for f in bag.iterdir() if f.suffix != ".yaml")


@pytest.mark.parametrize("storage", STORAGES)
def test_truncated_bags_are_errors_naming_the_bag(tmp_path, storage):
    bag = _good_bag(tmp_path, storage)
    data = _storage_file(bag).read_bytes()
    for keep in (0.03, 0.3, 0.6, 0.97):
        cut = tmp_path / f"cut{keep}"
        if bag.is_dir():
            shutil.copytree(bag, cut)
            target = _storage_file(cut)
        else:
            target = cut.with_suffix(".bag")
            cut = target
        target.write_bytes(data[:int(len(data) * keep)])
        try:
            tree = pinframes.read(cut)
        except PinframesError as exc:
            assert exc.file is not None and Path(exc.file).name == cut.name
        else:  # a reader may recover what was written before the cut, never invent
            assert len(tree.local_pose("tool")) < 200


@pytest.mark.filterwarnings("ignore::pinframes.BagWarning")
@pytest.mark.parametrize("storage", STORAGES)
def test_corrupt_bytes_are_errors_naming_the_bag(tmp_path, storage):
    bag = _good_bag(tmp_path, storage)
    target = _storage_file(bag)
    data = bytearray(target.read_bytes())
    for start in range(64, len(data) - 64, max(1, len(data) // 7)):
        corrupt = bytearray(data)
        corrupt[start:start + 48] = bytes(range(200, 248))
        target.write_bytes(corrupt)
        try:
            pinframes.read_rosbag(bag)
        except PinframesError as exc:
            assert exc.file is not None and Path(exc.file).name == bag.name


def test_unknown_storage_and_missing_metadata_and_files(tmp_path):
    bag = _good_bag(tmp_path, "mcap", 3)
    metadata = bag / "metadata.yaml"
    text = metadata.read_text()
    metadata.write_text(text.replace("storage_identifier: mcap", "storage_identifier: zarr"))
    with pytest.raises(FileFormatError, match="unknown storage 'zarr'") as caught:
        pinframes.read(bag)
    assert caught.value.field.endswith("storage_identifier")
    metadata.write_text(text)
    _storage_file(bag).unlink()
    with pytest.raises(ReadError, match="missing"):
        pinframes.read(bag)
    metadata.unlink()
    with pytest.raises(FileFormatError, match=r"without metadata\.yaml") as caught:
        pinframes.read_rosbag(bag)
    assert caught.value.file == str(bag)
    with pytest.raises(ReadError, match=r"is a folder, not a file \(a ROS 2 bag folder holds "
                       r"a metadata\.yaml\)"):
        pinframes.read(bag)


def test_no_tf_messages_names_the_topics_the_bag_has(tmp_path):
    bag = write_bag(tmp_path / "states", "ros1", [
        Message("/joint_states", JOINT_STATE, START, joint_state(1, START, ["a"], [0.0]))])
    with pytest.raises(FileFormatError, match=r"no tf messages on /tf, /tf_static.*"
                       "/joint_states") as caught:
        pinframes.read(bag)
    assert caught.value.file == str(bag)


def test_a_topic_of_the_wrong_type_is_named(tmp_path):
    bag = write_bag(tmp_path / "wrong", "mcap", [
        Message("/tf", "std_msgs/msg/String", START, string(2, "hello"))])
    with pytest.raises(FileFormatError, match="std_msgs/msg/String, expected") as caught:
        pinframes.read(bag)
    assert caught.value.field == "/tf"


def test_not_a_bag(tmp_path):
    folder = tmp_path / "plain"
    folder.mkdir()
    with pytest.raises(FileFormatError, match=r"without metadata\.yaml"):
        pinframes.read_rosbag(folder)
    other = tmp_path / "x.bag"
    other.write_text("hello")
    with pytest.raises(FileFormatError, match="not a ROS bag"):
        pinframes.read_rosbag(other)


def test_limits_bound_what_is_read(tmp_path):
    bag = _good_bag(tmp_path, "sqlite3", 50)
    with pytest.raises(FileFormatError, match="max_samples") as caught:
        pinframes.read(bag, limits=pinframes.Limits(max_samples=49))
    assert caught.value.frame == "tool"
    assert len(pinframes.read(bag, limits=pinframes.Limits(max_samples=50))
               .local_pose("tool")) == 50
    with pytest.raises(FileFormatError, match="max_decompressed_bytes"):
        pinframes.read_rosbag(bag, limits=pinframes.Limits(max_decompressed_bytes=1000))
