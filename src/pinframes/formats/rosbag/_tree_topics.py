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
- A frame that is no URDF link but has shapes recorded on it (``FrameTree.add_geometry``, a
  scene's geometry entries) goes out as a robot of one link, named after the frame, so that
  viewers draw its shapes.
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
from ...values.geometry import GEOMETRY_METADATA_KEY, FrameGeometry
from ..urdf import URDF_METADATA_KEY, robot_links, robot_urdf, shapes_urdf

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
    robots = tree.metadata.get(URDF_METADATA_KEY, {})
    roots = [root for root in robots if root in tree]
    members = {link for root in roots for link in robot_links(tree, root)}
    shaped = [frame for frame in tree.frames if frame not in members
              and isinstance(tree.frame_metadata(frame).get(GEOMETRY_METADATA_KEY),
                             FrameGeometry)]
    names = [str(robots[root].get("name") or root) for root in roots] + shaped
    descriptions = [robot_urdf(tree, root) for root in roots]
    descriptions += [shapes_urdf(tree, frame) for frame in shaped]
    topics = []
    for root, namespace, description in zip([*roots, *shaped], _namespaces(names),
                                            descriptions, strict=True):
        joints = tuple(joint.name for link in robot_links(tree, root)
                       if (joint := tree.joint_of(link)) is not None and joint.is_actuated)
        topics.append(RobotTopics(root, f"{namespace}/{DESCRIPTION}",
                                  f"{namespace}/{JOINT_STATES}", description, joints))
    _check_tf_names(tree)
    static = tuple(frame for frame in tree.frames[1:]
                   if not tree.is_moving(frame) and tree.joint_of(frame) is None)
    moving = tuple(frame for frame in tree.frames[1:] if frame not in set(static))
    return TreeTopics(static, moving, tuple(topics))


def _check_tf_names(tree: FrameTree) -> None:
    """tf2 drops a leading ``/`` of a frame id: such a name would read back as another
    frame, so it is refused (a writer writes what its reader reads back unchanged)."""
    for frame in tree.frames:
        if frame.startswith("/"):
            raise UnsupportedFeatureError(
                "tf2 drops the leading '/' of a frame id, so this frame would read back as "
                f"{frame.lstrip('/')!r}: rename it", frame=frame, field="name")


def _namespaces(names: list[str]) -> list[str]:
    """``""`` for a single robot, else ``/<name>`` per robot, each once."""
    if len(names) <= 1:
        return [""] * len(names)
    taken: set[str] = set()
    namespaces = []
    for robot in names:
        base = re.sub(r"[^A-Za-z0-9_]", "_", robot)
        base = base if base[:1].isalpha() else f"robot_{base}"
        name, number = base, 1
        while name in taken:
            number += 1
            name = f"{base}_{number}"
        taken.add(name)
        namespaces.append(f"/{name}")
    return namespaces
