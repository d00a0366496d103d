"""ROS bags (ROS 1 ``.bag``, ROS 2 folders, ``.db3`` and MCAP files) as frame trees, read with
rosbags and tf2's semantics (docs/ros-bags.md), and written with rosbags' writers
(docs/ros-bags-out.md).

Reading: ``_storage`` (which kind of bag, its raw messages), ``_inflation`` (compressed
parts inflated within ``max_decompressed_bytes``), ``_sqlite_schema`` (a ``.db3`` whose
values SQLite would compute on reading refused), ``_tf_messages`` (TFMessage
bytes decoded in bulk), ``_messages`` (the types read; JointState and String through
rosbags), ``_tf_tracks`` (tf2's rules: one track per frame), ``_joint_states`` (samples per
joint), ``_assembly`` (tracks, robot and joints into a tree), ``_reader`` (``read_rosbag``).
Writing: ``_bag_writer`` (the kind of bag a name asks for, written atomically),
``_outgoing`` (messages built from arrays), ``_tf_encoding`` (``/tf`` messages encoded
in bulk), ``_tree_topics`` (which part of a tree goes on
which topic), ``_writer`` (``write_rosbag``), ``_trajectory_writer`` (a joint trajectory as
a ``JointTrajectory`` and joint states).
"""

from pathlib import Path

from .._registry import FileFormat
from ..reading import InputFile
from ._reader import ROSBAG_METADATA_KEY, read_rosbag
from ._storage import BAG_KINDS, METADATA_FILE, bag_files, bag_kind, bag_kind_of_head
from ._trajectory_writer import write_trajectory_bag
from ._writer import write_rosbag

__all__ = ["BAG_KINDS", "ROSBAG_FORMAT", "ROSBAG_METADATA_KEY", "bag_files", "bag_kind",
           "bag_kind_of_head", "read_rosbag", "write_rosbag", "write_trajectory_bag"]


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
    "rosbag", "ROS bag", (".bag", ".mcap", ".db3"), read_rosbag, write_rosbag,
    ("times", "time_ref"), head_test=_is_bag_file,
    looks_like="a ROS bag (ROS 1, MCAP or ROS 2 SQLite)", folder_test=_is_bag_folder,
    unrecognised="a ROS 2 bag folder holds a metadata.yaml", files_read=_files_read)
"""ROS bags: files told by their magic bytes, ROS 2 bag folders by their metadata.yaml;
read and written with rosbags (the [ros] extra). A name to be written without a suffix is a
ROS 2 bag folder."""
