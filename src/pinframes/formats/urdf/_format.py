"""``read_urdf``: a URDF file with the joint values written beside it.

:func:`pinframes.write_urdf` writes a tree at one time as two files, the robot
(``cell.urdf``) and its joints' values then (``cell.joints.csv``, a joint trajectory file of
one row). Reading the URDF reads both, so the robot stands where it stood. Here too the
format's entry (:data:`URDF_FORMAT`) in the formats' registry.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from ...errors import PinframesError
from ...tree import FrameTree
from .._registry import FileFormat
from ..joint_trajectory import read_joint_trajectory
from ..limits import Limits
from ..reading import InputFile
from ._parse import is_urdf
from ._read_write import joint_state_path, read_robot, write_urdf

__all__ = ["URDF_FORMAT", "read_urdf"]


def read_urdf(path: str | os.PathLike[str], *, strict: bool = False,
              limits: Limits | None = None, joint_state: bool = True,
              package_dirs: Iterable[str | os.PathLike[str]] = (),
              xacro_args: Mapping[str, Any] | None = None,
              srdf: str | os.PathLike[str] | None = None,
              xacro: bool | None = None) -> FrameTree:
    """A robot file as a tree: its root is the robot's root link, named after the robot.

    A xacro file is expanded with the ``xacro`` package (``pip install "pinframes[ros]"``)
    only when asked, since the expansion runs the file's code: ``xacro=True``, or
    (``xacro=None``, the default) a file whose name ends in ``.xacro``; other xacro content
    is a ``FileFormatError`` saying how to opt in, ``xacro=False`` never expands. The
    expansion runs in a child process bounded by ``max_xacro_seconds`` and
    ``max_xacro_bytes`` (:class:`pinframes.Limits`), without environment variables.
    ``xacro_args`` give its ``$(arg NAME)`` values, and ``$(find PKG)`` is the package whose
    ``package.xml`` names it in ``package_dirs`` (crawled), then ``ROS_PACKAGE_PATH`` and
    ``AMENT_PREFIX_PATH``, then the file's ancestor folders. ``package_dirs`` are remembered
    with the robot: clearance and the 3-D page look for its ``package://`` and ``model://``
    meshes there without being told again. ``srdf``, the robot's SRDF file, names its joint
    groups and group states (``solve_joints(joints="arm", seed="home")``) and the link pairs
    that :meth:`~pinframes.FrameTree.clearance` leaves out; an SRDF shipped as xacro
    (``*.srdf.xacro``) is expanded as the robot file is, with the same ``xacro_args``.

    ``strict`` refuses a mimic of a joint the file does not have (by default such a joint
    stays independent, with a :class:`~pinframes.BrokenMimicWarning`). ``limits``
    (:class:`pinframes.Limits`; None: the defaults) bounds the XML elements
    (``max_xml_elements``) and their nesting (``max_depth``); a ``<!DOCTYPE>`` is refused.

    The joint values :func:`~pinframes.write_urdf` writes beside the file (``cell.urdf`` ->
    ``cell.joints.csv``) are read with it when that file exists: one sample per joint, at
    the time the file was written, so the robot stands where it stood then.
    ``joint_state=False`` leaves every joint at its rest value.
    """
    tree = read_robot(path, strict=strict, limits=limits, package_dirs=package_dirs,
                      xacro_args=xacro_args, srdf=srdf, xacro=xacro)
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


def _files_read(source: InputFile) -> list[Path]:
    """The joint values beside the URDF (``cell.urdf`` -> ``cell.joints.csv``)."""
    return [joint_state_path(source.path)]


URDF_FORMAT = FileFormat("urdf", "URDF", (".urdf", ".xacro"), read_urdf, write_urdf,
                         ("time", "freeze_joints"), head_test=is_urdf, looks_like="a URDF file",
                         files_read=_files_read)
"""The URDF format: XML whose root element is ``<robot>``, with the joint values beside it."""
