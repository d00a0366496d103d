"""The one snapshot rule of the writers that store one pose per frame (URDF, frames.yaml,
and scene files written at a time).

With a time, every moving frame and every driven joint is taken at that one instant
(:meth:`FrameTree.snapshot`). Without one, a tree in which something moves is an error that
names what moves and the option to pass: nothing is frozen at a guessed time.
"""

from __future__ import annotations

import os
from typing import Any

from ..errors import UnsupportedFeatureError
from ..kinematics import Snapshot
from ..tree import FrameTree

__all__ = ["moving_parts", "one_instant"]


def moving_parts(tree: FrameTree) -> tuple[list[str], list[str]]:
    """The frames that move in their parent, and the joints driven by a trajectory."""
    frames = [name for name in tree.frames[1:] if tree.is_moving(name)]
    joints = [name for name in tree.joints if tree.joint_trajectory(name) is not None]
    return frames, joints


def one_instant(tree: FrameTree, time: Any, path: str | os.PathLike[str], what: str
                ) -> Snapshot:
    """The instant a ``what`` file (one pose per frame) takes ``tree`` at.

    Raises :class:`UnsupportedFeatureError` naming the moving frames and driven joints when
    ``time`` is None and anything moves.
    """
    if time is None:
        frames, joints = moving_parts(tree)
        if frames or joints:
            moving = []
            if frames:
                moving.append(f"frames {_listed(frames)} move")
            if joints:
                moving.append(f"joints {_listed(joints)} are driven")
            first = frames[0] if frames else next(
                name for name in tree.frames[1:]
                if getattr(tree.joint_of(name), "name", None) == joints[0])
            raise UnsupportedFeatureError(
                f"{' and '.join(moving)}, and {what} holds one pose per frame: pass time= "
                "(--time on the command line) to write the tree at one time",
                file=path, frame=first, field="time")
    return tree.snapshot(time)


def _listed(names: list[str], shown: int = 5) -> str:
    text = ", ".join(repr(name) for name in names[:shown])
    return text + (f" and {len(names) - shown} more" if len(names) > shown else "")
