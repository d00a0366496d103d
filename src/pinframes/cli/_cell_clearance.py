"""The demo's clearance lines: how close the robot comes to the bundled cell's parts.

The robot's links and its torch on one side, the cell's fixtures, faceplate and pipe on the
other, checked at every sample of the motion. Two pairs touch or nearly touch by design and
are not counted; the lines say which and why.
"""

from __future__ import annotations

from ..tree import FrameTree
from ..values.geometry import GEOMETRY_METADATA_KEY
from .clearance import clearance_summary

__all__ = ["CELL_SIDE", "EXCLUDED", "ROBOT_SIDE", "clearance_lines"]

ROBOT_SIDE = ["robot/*", "torch"]
CELL_SIDE = ["fixtures", "faceplate", "pipe"]
EXCLUDED = {
    ("torch", "pipe"): "the torch works at the seam",
    ("robot/base_link", "fixtures"): "the robot stands on its riser",
}


def clearance_lines(tree: FrameTree) -> str:
    """Two ``name  value`` lines for the demo's summary table; "" for a tree without the
    cell's parts and their geometry (another ``--scene``, a converted file)."""
    parts = ["torch", "robot/base_link", *CELL_SIDE]
    if not all(name in tree and GEOMETRY_METADATA_KEY in tree.frame_metadata(name)
               for name in parts):
        return ""
    result = tree.clearance(ROBOT_SIDE, CELL_SIDE, exclude=list(EXCLUDED))
    at_seam = tree.clearance("torch", "pipe", times=result.times,
                             time_ref=result.reference_time)
    reasons = [f"{a}-{b} ({why}: {1000 * at_seam.distance.min():.1f} mm at the closest)"
               if (a, b) == ("torch", "pipe") else f"{a}-{b} ({why})"
               for (a, b), why in EXCLUDED.items()]
    summary = clearance_summary(result, counts=False).removeprefix("smallest clearance ")
    return (f"robot-cell clearance   {summary}\n"
            f"pairs not counted      {'; '.join(reasons)}\n")
