"""`TreeLike`: what :mod:`.grafting` and :mod:`.tree_times` use of a :class:`FrameTree`.

Those modules do their work through the tree's public methods only. They cannot name
``FrameTree`` itself: ``frame_tree`` imports them, and an import back, even under
``TYPE_CHECKING``, is a cycle that ``tests/test_layers.py`` refuses. ``FrameTree`` matches
this protocol, and mypy checks that it does wherever it is passed in.
"""

from __future__ import annotations

from typing import Any, Protocol, TypeVar

import numpy as np

from ..values.joint import Joint
from ..values.joint_trajectory import JointTrajectory
from ..values.pose import Pose
from ..values.spatial_data import SpatialData
from ..values.subsystem import Subsystem

__all__ = ["Tree", "TreeLike"]

Tree = TypeVar("Tree", bound="TreeLike")
"""A tree of one class throughout a call: ``subtree(tree)`` returns a tree of ``type(tree)``."""


class TreeLike(Protocol):
    """The public members of a frame tree that the whole-tree operations use."""

    name: str | None
    metadata: dict[str, Any]
    subsystems: list[Subsystem]

    def __init__(self, root: str = ..., name: str | None = ..., reference_time: Any = ...
                 ) -> None: ...

    @property
    def root(self) -> str: ...

    @property
    def reference_time(self) -> np.datetime64 | None: ...

    @property
    def frames(self) -> list[str]: ...

    @property
    def joints(self) -> dict[str, Joint]: ...

    @property
    def data_names(self) -> list[str]: ...

    def __contains__(self, name: object) -> bool: ...

    def parent(self, name: str) -> str | None: ...

    def children(self, name: str) -> list[str]: ...

    def local_pose(self, name: str) -> Pose: ...

    def joint_of(self, name: str) -> Joint | None: ...

    def joint_trajectory(self, joint_name: str) -> JointTrajectory | None: ...

    def frame_metadata(self, name: str) -> dict[str, Any]: ...

    def data_frame(self, name: str) -> str: ...

    def get_data(self, name: str) -> SpatialData: ...

    def add(self, name: str, parent: str, pose: Pose | None = None) -> None: ...

    def attach_joint(self, name: str, parent: str, joint: Joint, origin: Pose | None = None
                     ) -> None: ...

    def replace_joint_trajectory(self, joint_name: str, trajectory: JointTrajectory | None
                                 ) -> None: ...

    def set_local_pose(self, name: str, pose: Pose) -> None: ...

    def assign_data(self, name: str, data: SpatialData | Any, frame: str) -> None: ...

    def remove(self, name: str, recursive: bool = False, drop_data: bool = False) -> None: ...

    def copy(self: Tree) -> Tree: ...

