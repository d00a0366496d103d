"""ROS bags (ROS 1 ``.bag``, ROS 2 folders, ``.db3`` and MCAP files) as frame trees, read with
rosbags and tf2's semantics (SPEC 10).

Modules: ``_storage`` (which kind of bag, its raw messages), ``_tf_messages`` (TFMessage
bytes decoded in bulk), ``_messages`` (the types read; JointState and String through
rosbags), ``_tf_tracks`` (tf2's rules: one track per frame), ``_joint_states`` (samples per
joint), ``_assembly`` (tracks, robot and joints into a tree), ``_reader`` (``read_rosbag``).
"""

from ._reader import ROSBAG_METADATA_KEY, read_rosbag
from ._storage import BAG_KINDS, bag_files, bag_kind, bag_kind_of_head

__all__ = ["BAG_KINDS", "ROSBAG_METADATA_KEY", "bag_files", "bag_kind", "bag_kind_of_head",
           "read_rosbag"]
