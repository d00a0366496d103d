"""ROS bags (ROS 1 ``.bag``, ROS 2 folders, ``.db3`` and MCAP files) as frame trees, read with
rosbags and tf2's semantics (docs/ros-bags.md).

Modules: ``_storage`` (which kind of bag, its raw messages), ``_inflation`` (compressed
parts inflated within ``max_decompressed_bytes``), ``_sqlite_schema`` (a ``.db3`` whose
values SQLite would compute on reading refused), ``_tf_messages`` (TFMessage
bytes decoded in bulk), ``_messages`` (the types read; JointState and String through
rosbags), ``_tf_tracks`` (tf2's rules: one track per frame), ``_joint_states`` (samples per
joint), ``_assembly`` (tracks, robot and joints into a tree), ``_reader`` (``read_rosbag``).
"""

from pathlib import Path

from .._registry import FileFormat
from ..reading import InputFile
from ._reader import ROSBAG_METADATA_KEY, read_rosbag
from ._storage import BAG_KINDS, METADATA_FILE, bag_files, bag_kind, bag_kind_of_head

__all__ = ["BAG_KINDS", "ROSBAG_FORMAT", "ROSBAG_METADATA_KEY", "bag_files", "bag_kind",
           "bag_kind_of_head", "read_rosbag"]


def _is_bag_file(source: InputFile) -> bool:
    """A ROS 1 bag, MCAP or ROS 2 SQLite file, told by its magic bytes."""
    return bag_kind_of_head(source.head()) is not None


def _is_bag_folder(path: Path) -> bool:
    """A ROS 2 bag folder holds its metadata.yaml."""
    return (path / METADATA_FILE).is_file()


def _files_read(source: InputFile) -> list[Path]:
    """A bag folder's metadata.yaml and the storage files it names (a bag file: itself)."""
    return bag_files(source.path)


ROSBAG_FORMAT = FileFormat(
    "rosbag", "ROS bag", (".bag", ".mcap", ".db3"), read_rosbag, head_test=_is_bag_file,
    looks_like="a ROS bag (ROS 1, MCAP or ROS 2 SQLite)", folder_test=_is_bag_folder,
    unrecognised="a ROS 2 bag folder holds a metadata.yaml", files_read=_files_read)
"""ROS bags: files told by their magic bytes, ROS 2 bag folders by their metadata.yaml;
read with rosbags (the [ros] extra), never written."""
