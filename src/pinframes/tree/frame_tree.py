"""`FrameTree`: a tree of named coordinate frames whose poses may move in time.

The class is built in four steps, one idea a module: :mod:`._structure` holds the frames,
the data attached to them and every edit, :mod:`._queries` the pose, velocity, Jacobian and
inverse kinematics queries handed to the kinematics, :mod:`._collision_queries` the
clearance; here come attached data in any frame, robots mounted from files and the
whole-tree operations, whose work is done in :mod:`.grafting` and :mod:`.tree_times`.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import ArgumentTypeError, InvalidDataError, InvalidTimeError, PinframesError
from ..values.geometry import GEOMETRY_KINDS, GEOMETRY_METADATA_KEY, FrameGeometry
from ..values.pose import Pose
from ..values.shapes import ShapeLike, shape_record
from ..values.spatial_data import SpatialData, apply_pose
from ..values.subsystem import Subsystem
from ..values.timeconv import TimeAxis
from . import grafting, tree_times
from ._collision_queries import CollisionQueries
from ._robot_formats import robot_mounter

__all__ = ["FrameTree"]


class FrameTree(CollisionQueries):
    """A tree of coordinate frames, compiled to Pinocchio to answer pose queries.

    Parameters
    ----------
    root : str
        Name of the root frame.
    name : str or None
        Name of the tree (weldx calls it the hierarchy's name).
    reference_time : None or timestamp
        Reference time of the tree: relative keyframe times of frames without their own
        reference time count from it, and query results use it (docs/time-semantics.md).

    Every frame other than the root has a parent and a pose in that parent: static, moving
    (a time-dependent :class:`Pose`) or driven by a robot :class:`Joint`.
    """

    # -- robots from files, and whole-tree operations --------------------------------------
    def attach_urdf(
        self, urdf: str | os.PathLike[str], parent: str, pose: Pose | None = None,
        prefix: str = "", *, strict: bool = False, limits: Any = None,
        package_dirs: Iterable[str | os.PathLike[str]] = (),
        xacro_args: Mapping[str, Any] | None = None,
        srdf: str | os.PathLike[str] | None = None, xacro: bool | None = None,
    ) -> list[str]:
        """Mount a robot: its root link at ``parent`` (at ``pose``), every link a frame.

        Parameters
        ----------
        urdf : path or str
            A URDF or xacro file, or URDF XML text. Meshes are never needed.
        parent : str
            The frame the robot's root link is placed on.
        pose : Pose or None
            The root link's pose in ``parent`` (identity if None; may move in time).
        prefix : str
            Put before every link and joint name, to mount several copies of a robot.
        strict : bool
            Refuse a mimic joint whose primary joint is not in the file; by default it
            stays an independent joint, with one ``BrokenMimicWarning`` per such joint.
        limits : pinframes.Limits or None
            Bounds on the XML elements and their nesting (None: those of the read in
            progress, e.g. a scene's, else the defaults).
        package_dirs : iterable of path
            Folders for xacro's ``$(find PKG)`` and the robot's ``package://`` and
            ``model://`` meshes, searched before ``ROS_PACKAGE_PATH`` and the file's
            ancestor folders; remembered with the robot (clearance and the 3-D page use them).
        xacro_args : mapping, optional
            ``$(arg NAME)`` values of a xacro file.
        srdf : path, optional
            The robot's SRDF: its joint groups and group states for :meth:`solve_joints`,
            its disabled collision pairs for :meth:`clearance`.
        xacro : bool or None
            Whether a xacro file (and a xacro SRDF) is expanded with the ``xacro`` package,
            which runs the file's code: None (the default) expands a file whose name ends
            in ``.xacro``, True any file with xacro content, False none; xacro content that
            is not expanded is a ``FileFormatError``.

        Returns
        -------
        list of str
            The new frame names, root link first. Revolute, continuous and prismatic
            joints stay joints, at their rest value (0, or the limit nearest to 0) until
            :meth:`set_joint_trajectory` gives them samples; fixed,
            floating and planar joints become frames at their origin. A failed import
            leaves the tree unchanged.
        """
        return robot_mounter("urdf")(self, urdf, parent, pose, prefix, strict=strict,
                                     limits=limits, package_dirs=package_dirs,
                                     xacro_args=xacro_args, srdf=srdf, xacro=xacro)

    def add_geometry(self, frame: str, shape: ShapeLike, *, origin: Pose | None = None,
                     kind: str = "both",
                     rgba: tuple[float, float, float, float] | None = None) -> None:
        """Give ``frame`` a shape: a :class:`~pinframes.Box`, :class:`~pinframes.Cylinder`,
        :class:`~pinframes.Sphere` or :class:`~pinframes.Mesh`, with its coordinates at
        ``origin`` in the frame (static; None: the frame's own).

        ``kind`` is ``"collision"`` (measured by :meth:`clearance`), ``"visual"`` (drawn on
        the page) or ``"both"``. The shape joins those the frame has (a robot link keeps its
        URDF shapes) and moves with the frame; :meth:`to_pinocchio`, the page and scene
        files (a frame's ``geometry`` entry) keep it. ``rgba`` is its colour on the page
        (red, green, blue, alpha in 0..1).
        """
        self._require(frame, "frame")
        if kind not in ("both", *GEOMETRY_KINDS):
            raise ArgumentTypeError(f"expected 'both', 'collision' or 'visual', got {kind!r}",
                                    frame=frame, field="kind")
        try:
            record = shape_record(shape, origin, _colour(rgba))
        except PinframesError as exc:
            raise exc.located(frame=frame) from None
        metadata = self.frame_metadata(frame)
        recorded = metadata.get(GEOMETRY_METADATA_KEY) or FrameGeometry(frame, None)
        added = {name: (record,) if kind in ("both", name) else () for name in GEOMETRY_KINDS}
        metadata[GEOMETRY_METADATA_KEY] = dataclasses.replace(
            recorded, collision=recorded.collision + added["collision"],
            visual=recorded.visual + added["visual"])

    def graft(self, other: FrameTree, at: str | None = None, prefix: str = "",
              name: str | None = None, record: bool = True) -> Subsystem | None:
        """Mount tree ``other`` here: its root becomes frame ``at``, every other frame of it
        (moving frames, robot links with joints and trajectories, attached data) is added
        with ``prefix`` before its name (joints and data too), as weldx's ``merge`` does.

        ``at`` defaults to ``prefix + other.root``, which must be a frame of this tree.
        Keyframes counting from ``other``'s reference time keep their absolute times. A
        :class:`Subsystem` named ``name`` (default: ``prefix + other.name``) records the graft; the
        subsystems of ``other`` come along nested in it (with ``record=False`` there is no
        record, and they nest in nothing).

        The tree :attr:`metadata` of ``other`` comes along too: every entry, deep-copied,
        under ``prefix + key``, beside this tree's own entries, which stay as they are. The
        formats read only their own key (``"urdf"``, ``"frames_yaml"``), so entries that took
        a prefix are kept but not used when this tree is written. With a prefix, metadata keys
        must be strings (:class:`~pinframes.errors.ArgumentTypeError`, field ``metadata``).

        A name taken twice (frame, joint, data, subsystem, or metadata key) is a
        :class:`~pinframes.errors.FrameExistsError` naming it and its field (``frames``,
        ``joints``, ``data``, ``subsystems``, ``metadata``), and any failure leaves both trees
        as they were. Returns the record.
        """
        return grafting.graft(self, other, at, prefix, name, record)

    def subtree(self, frame: str) -> FrameTree:
        """A new tree rooted at ``frame`` with copies of everything below it: poses, joints
        and their trajectories, data, frame metadata and the subsystems inside it. A subsystem
        recording exactly this part (a :meth:`graft`) names the copy, gives its reference
        time and is not kept, so ``subtree`` undoes ``graft``. The tree :attr:`metadata` is
        not copied (:meth:`copy` copies it)."""
        return grafting.subtree(self, frame)

    def copy(self) -> FrameTree:
        """An independent copy: frames, joints, trajectories, data, subsystems, metadata."""
        return grafting.copy_tree(self)

    def time_union(self, frames: Sequence[str] | None = None) -> TimeAxis | None:
        """Every keyframe and joint sample time of ``frames`` (default: the whole tree), as
        weldx's ``time_union``: ns offsets after the tree's reference time (else the earliest
        frame reference time); None when none of them moves."""
        return tree_times.time_union(self, frames)

    def resampled(self, times: Any, time_ref: Any = None) -> FrameTree:
        """A copy whose moving frames and joint trajectories hold samples at ``times`` only
        (interpolated as :meth:`pose` does, held outside), as weldx's ``interp_time``.

        Relative ``times`` count from ``time_ref``, else from the tree's reference time;
        static frames and data stay as they are; frames keep their own reference times.
        """
        return tree_times.resampled(self, times, time_ref)

    # -- data attached to frames, in any frame ---------------------------------------------
    def get_data(self, name: str, relative_to: str | None = None, times: Any = None,
                 time_ref: Any = None) -> SpatialData:
        """Data ``name`` with its points in ``relative_to`` (default: as stored).

        Time-dependent data is transformed at its own times (``times`` must be None). Static
        data follows :meth:`pose`: with ``times`` None, at the union of the path's keyframe
        times (static points if nothing on the path moves), else at ``times``; moving points
        come back ``(T, M, 3)`` with the pose's times and reference time.
        """
        frame = self.data_frame(name)
        data = super().get_data(name)
        if (relative_to is None or relative_to == frame) and times is None:
            return data
        target = frame if relative_to is None else relative_to
        own = data.times
        if own is not None:
            if times is not None:
                raise InvalidTimeError(f"data {name!r} has times of its own; pass times=None",
                                       frame=frame, field="times")
            reference = data.reference_time
            times = own if reference is None else reference + own
            time_ref = None
        pose = self.pose(frame, target, times, time_ref)
        offsets = None if pose.times is None else pose.times.astype(np.int64)
        return data.with_points(apply_pose(pose, data.points), offsets, pose.reference_time)


def _colour(rgba: Any) -> tuple[float, float, float, float] | None:
    """``rgba`` as four numbers in 0..1, or None."""
    if rgba is None:
        return None
    values = np.asarray(rgba, dtype=float).reshape(-1)
    if values.shape != (4,) or not np.all((values >= 0) & (values <= 1)):
        raise InvalidDataError(f"expected red, green, blue, alpha in 0..1, got {rgba!r}",
                               field="rgba")
    red, green, blue, alpha = values.tolist()
    return (red, green, blue, alpha)
