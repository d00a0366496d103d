"""Robot file formats that :meth:`FrameTree.attach_urdf` can mount, looked up by name.

The tree sits below the formats layer and never imports it: the formats layer registers
its URDF mounter here when :mod:`pinframes` is imported, and the tree looks it up by name
when a robot is attached.
"""

from __future__ import annotations

from collections.abc import Callable

from ..errors import UnsupportedFeatureError

__all__ = ["RobotMounter", "register_robot_format", "robot_mounter"]

RobotMounter = Callable[..., list[str]]
"""``mount(tree, source, parent, pose, prefix, *, strict, limits, package_dirs, xacro_args,
srdf, xacro) -> new frame names``: parses ``source`` (a path or the file's text) and adds the
robot's links below ``parent``, all or nothing; ``strict`` refuses what is otherwise loaded
with a warning; ``limits`` (a ``pinframes.Limits`` or None) bounds the parse; the others as
``FrameTree.attach_urdf`` says."""

_MOUNTERS: dict[str, RobotMounter] = {}


def register_robot_format(name: str, mount: RobotMounter) -> None:
    """Make robots in format ``name`` (e.g. ``"urdf"``) mountable on a tree."""
    _MOUNTERS[name] = mount


def robot_mounter(name: str) -> RobotMounter:
    """The mounter registered for format ``name``."""
    mount = _MOUNTERS.get(name)
    if mount is None:
        raise UnsupportedFeatureError(f"no {name} reader is registered (import pinframes, "
                                      "which registers the formats)")
    return mount
