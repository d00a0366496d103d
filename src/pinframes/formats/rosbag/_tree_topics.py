"""Which part of a tree goes on which topic of a bag, as a ROS system would publish it.

- Robots attached from URDF files (``FrameTree.attach_urdf``, a scene's ``robots``): their
  URDF on a description topic and their driven joints (mimic joints follow the URDF) on a
  joint states topic. Their links are on tf as ``robot_state_publisher`` publishes them from
  the description and the joint states: fixed joints on ``/tf_static``, the others on
  ``/tf`` at every time (so that a viewer without a ``robot_state_publisher``, Foxglove,
  sees the whole cell). One robot uses ``/robot_description`` and ``/joint_states``;
  several robots are namespaced, one ``robot_state_publisher`` each, as multi-robot ROS
  systems run them: ``/<name>/robot_description`` and ``/<name>/joint_states``, ``<name>``
  the URDF's robot name (characters other than letters, digits and ``_`` replaced by
  ``_``, ``_2``... added where two robots share a name).
- Every frame is on tf in its parent: on ``/tf_static`` when it never moves there, on
  ``/tf`` otherwise (a keyframed frame, a link of a joint that is not fixed, or a joint
  not from a URDF).
- Frame ids are the tree's names; tf2 drops a leading ``/``, so such names are refused.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ...errors import UnsupportedFeatureError
from ...tree import FrameTree
from ..urdf import URDF_METADATA_KEY, robot_links, robot_urdf

__all__ = ["RobotTopics", "TreeTopics", "tree_topics"]

DESCRIPTION = "robot_description"
JOINT_STATES = "joint_states"


@dataclass(frozen=True)
class RobotTopics:
    """One robot in a bag: its topics, its URDF text and the joints its joint states name
    (the tree's joint names, as the URDF names them)."""

    root_link: str
    description_topic: str
    joint_states_topic: str
    description: str
    joints: tuple[str, ...]


@dataclass(frozen=True)
class TreeTopics:
    """A tree's topics: frames on ``/tf_static`` and on ``/tf`` (tree names, parents first)
    and the robots."""

    static: tuple[str, ...]
    moving: tuple[str, ...]
    robots: tuple[RobotTopics, ...]


def tree_topics(tree: FrameTree) -> TreeTopics:
    """What of ``tree`` goes on which topic (see the module docstring)."""
    roots = [root for root in tree.metadata.get(URDF_METADATA_KEY, {}) if root in tree]
    namespaces = _namespaces(tree, roots)
    robots: list[RobotTopics] = []
    for root, namespace in zip(roots, namespaces, strict=True):
        links = robot_links(tree, root)
        joints = tuple(joint.name for link in links
                       if (joint := tree.joint_of(link)) is not None and joint.is_actuated)
        robots.append(RobotTopics(root, f"{namespace}/{DESCRIPTION}",
                                  f"{namespace}/{JOINT_STATES}", robot_urdf(tree, root), joints))
    on_tf = tree.frames[1:]
    _check_tf_names(tree)
    static = tuple(frame for frame in on_tf
                   if not tree.is_moving(frame) and tree.joint_of(frame) is None)
    moving = tuple(frame for frame in on_tf if frame not in set(static))
    return TreeTopics(static, moving, tuple(robots))


def _check_tf_names(tree: FrameTree) -> None:
    """tf2 drops a leading ``/`` of a frame id: such a name would read back as another
    frame, so it is refused (a writer writes what its reader reads back unchanged)."""
    for frame in tree.frames:
        if frame.startswith("/"):
            raise UnsupportedFeatureError(
                "tf2 drops the leading '/' of a frame id, so this frame would read back as "
                f"{frame.lstrip('/')!r}: rename it", frame=frame, field="name")


def _namespaces(tree: FrameTree, roots: list[str]) -> list[str]:
    """``""`` for a single robot, else ``/<robot name>`` per robot, each once."""
    if len(roots) <= 1:
        return [""] * len(roots)
    robots = tree.metadata[URDF_METADATA_KEY]
    taken: set[str] = set()
    namespaces = []
    for root in roots:
        base = re.sub(r"[^A-Za-z0-9_]", "_", str(robots[root].get("name") or root))
        base = base if base[:1].isalpha() else f"robot_{base}"
        name, number = base, 1
        while name in taken:
            number += 1
            name = f"{base}_{number}"
        taken.add(name)
        namespaces.append(f"/{name}")
    return namespaces
