"""The demo's ROS line: the bundled cell's run written as an MCAP recording that Foxglove,
``ros2 bag play`` and :func:`pinframes.read` open."""

from __future__ import annotations

from pathlib import Path

from ..errors import UnsupportedFeatureError
from ..formats import write
from ..tree import FrameTree

__all__ = ["BAG_FILE", "write_demo_bag"]

BAG_FILE = "cell_run.mcap"


def write_demo_bag(tree: FrameTree, out: Path) -> tuple[Path | None, str]:
    """Write ``tree`` to ``out/cell_run.mcap`` at every keyframe and joint sample; return the
    file (None when the ``ros`` extra is missing) and the line that says what it holds, or
    what installing the extra adds."""
    path = out / BAG_FILE
    try:
        write(tree, path)
    except UnsupportedFeatureError:  # rosbags is not installed: the bag is optional
        return None, (f'no ROS bag: pip install "pinframes[ros]" adds rosbags, and the demo '
                      f"then also writes the run as {BAG_FILE} (Foxglove, ros2 bag play)")
    union = tree.time_union()
    samples = 1 if union is None else union.offsets.shape[0]
    return path, (f"{'ROS recording'.ljust(21)}  {path} ({samples} times: /tf, /tf_static, "
                  "robot descriptions and joint states; opens in Foxglove)")
