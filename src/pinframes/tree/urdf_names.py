"""What the URDF mounter keeps of each robot in a tree's metadata, and the robots' joints
named as their URDF names them (the tree's prefix removed)."""

from __future__ import annotations

from collections.abc import Sequence

from ._structure import EditableTree

__all__ = ["URDF_METADATA_KEY", "urdf_joint_names"]

URDF_METADATA_KEY = "urdf"
"""Key of the per-frame (and per-tree) metadata that keeps URDF details: per robot (by its
root frame) its name, prefix, extra XML and file; per link frame its robot and URDF names."""


def urdf_joint_names(tree: EditableTree, joint_names: Sequence[str]) -> list[str] | None:
    """``joint_names`` (the tree's) as the robot's URDF names them, when every one belongs
    to the same robot read from a URDF (as a scene's ``robots[].trajectory`` names them),
    else None."""
    frames = {joint.name: frame for frame in tree.frames
              if (joint := tree.joint_of(frame)) is not None}
    robots = tree.metadata.get(URDF_METADATA_KEY, {})
    prefixes = set()
    for name in joint_names:
        kept = tree.frame_metadata(frames[name]).get(URDF_METADATA_KEY, {})
        prefixes.add(robots.get(kept.get("robot"), {}).get("prefix"))
    prefix = prefixes.pop() if len(prefixes) == 1 else None
    if not isinstance(prefix, str) or not all(name.startswith(prefix) for name in joint_names):
        return None
    return [name[len(prefix):] for name in joint_names]
