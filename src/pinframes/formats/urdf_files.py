"""``read_urdf``: a URDF file with the joint values written beside it.

:func:`pinframes.write_urdf` writes a tree at one time as two files, the robot
(``cell.urdf``) and its joints' values then (``cell.joints.csv``, a joint trajectory file of
one row). Reading the URDF reads both, so the robot stands where it stood. This sits beside
the ``urdf`` package rather than in it: the joint trajectory reader is built on the format
registry, which itself reads robot descriptions through the ``urdf`` package.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import PinframesError
from ..tree import FrameTree
from .limits import Limits
from .trajectory_files import read_joint_trajectory
from .urdf import joint_state_path, read_robot

__all__ = ["read_urdf"]


def read_urdf(path: str | os.PathLike[str], *, strict: bool = False,
              limits: Limits | None = None, joint_state: bool = True) -> FrameTree:
    """A robot file as a tree: its root is the robot's root link, named after the robot.

    ``strict`` refuses a mimic of a joint the file does not have (by default such a joint
    stays independent, with a :class:`~pinframes.urdf.BrokenMimicWarning`). ``limits``
    (:class:`pinframes.Limits`; None: the defaults) bounds the XML elements
    (``max_xml_elements``) and their nesting (``max_depth``); a ``<!DOCTYPE>`` is refused.

    The joint values :func:`~pinframes.write_urdf` writes beside the file (``cell.urdf`` ->
    ``cell.joints.csv``) are read with it when that file exists: one sample per joint, at
    the time the file was written, so the robot stands where it stood then.
    ``joint_state=False`` leaves every joint at its rest value.
    """
    tree = read_robot(path, strict=strict, limits=limits)
    beside = _joint_state_file(path)
    if joint_state and beside is not None and beside.is_file():
        times, positions, names = read_joint_trajectory(beside, limits=limits)
        try:
            tree.set_joint_trajectory(times, positions, names)
        except PinframesError as exc:
            raise exc.located(file=beside) from None
    return tree


def _joint_state_file(path: str | os.PathLike[str]) -> Path | None:
    """Where the joint values of the URDF ``path`` would be; None for URDF text."""
    if isinstance(path, str) and path.lstrip().startswith("<"):
        return None
    return joint_state_path(path)
