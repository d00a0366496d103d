"""`PinocchioTree`: a whole frame tree as one Pinocchio model, with its configurations."""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import pinocchio as pin
from numpy.typing import NDArray

from ..values.geometry import FrameGeometry
from ._description import TreeDescription
from ._model import compile_model
from ._plan import plan_query
from ._sampling import (
    path_samplers,
    sample_configurations,
    warn_joints_without_samples,
)
from .collision.coal_objects import ShapeLoader

__all__ = ["PinocchioTree"]


class PinocchioTree:
    """A frame tree compiled to one ``pinocchio.Model``, for running Pinocchio yourself.

    Attributes
    ----------
    model : pinocchio.Model
        Universe = the tree's root; moving frames are free-flyer joints named after the
        frame, robot joints keep their names and kinds; every frame is an ``OP_FRAME``.
    frame_ids : dict of str to int
        Pinocchio frame id of every tree frame.
    joint_ids : dict of str to int
        Pinocchio joint id of every joint.

    Examples
    --------
    >>> compiled = tree.to_pinocchio()                        # doctest: +SKIP
    >>> data = compiled.model.createData()                    # doctest: +SKIP
    >>> q = compiled.configurations([0.0, 0.5])[1]            # doctest: +SKIP
    >>> pin.framesForwardKinematics(compiled.model, data, q)  # doctest: +SKIP
    >>> shapes = compiled.geometry_model("collision")         # doctest: +SKIP
    >>> shapes.addAllCollisionPairs()                         # doctest: +SKIP
    """

    def __init__(self, tree: TreeDescription,
                 geometry: Mapping[str, FrameGeometry] | None = None) -> None:
        self._tree = tree
        self._geometry = dict(geometry or {})
        self._compiled = compile_model(tree, tree.root, tree.frames)
        self.model: pin.Model = self._compiled.model
        self.frame_ids = dict(self._compiled.frame_ids)
        self.joint_ids = self._compiled.joint_ids

    def geometry_model(self, kind: str = "collision",
                       package_dirs: Iterable[str | os.PathLike[str]] = ()) -> pin.GeometryModel:
        """The frames' ``kind`` geometry as a ``pinocchio.GeometryModel`` on this model.

        One ``GeometryObject`` per ``<collision>`` (or ``<visual>``) element of every link
        that has any, and per shape given by ``FrameTree.add_geometry``, named
        ``FRAME_INDEX`` (``robot/link_2_0``), hanging on its frame (``parentFrame``,
        ``parentJoint`` and the placement in that joint), with the coal object
        ``FrameTree.clearance`` measures: ``pinocchio.buildGeomFromUrdf``'s for primitives
        and STL, OBJ, PLY meshes; COLLADA meshes in the unit their file gives (Pinocchio's
        loader leaves it out). Meshes are found as the clearance finds them, in
        ``package_dirs`` first. No collision pairs
        are set: ``addAllCollisionPairs()`` or ``addCollisionPair`` choose them. A mesh
        that is missing or unreadable is a :class:`~pinframes.errors.GeometryError`.
        """
        loader = ShapeLoader(kind, package_dirs)
        shapes = pin.GeometryModel()
        for frame, recorded in self._geometry.items():
            if not recorded.shapes(kind) and not recorded.unreadable_shapes(kind):
                continue
            frame_id = self.frame_ids[frame]
            on_frame = self.model.frames[frame_id]
            for index, shape in enumerate(loader.shapes(frame, recorded)):
                placement = on_frame.placement * pin.SE3(shape.rotation, shape.translation)
                piece = pin.GeometryObject(  # meshPath BOX, CYLINDER, SPHERE as Pinocchio's
                    f"{frame}_{index}", on_frame.parentJoint, frame_id, placement,
                    shape.geometry, shape.mesh_path or shape.shape.kind.upper(),
                    np.array(shape.shape.scale))
                if shape.shape.rgba is not None:
                    piece.meshColor = np.array(shape.shape.rgba)
                shapes.addGeometryObject(piece)
        return shapes

    def configurations(self, times: Any = None, time_ref: Any = None) -> NDArray[np.float64]:
        """Configurations ``q``, shape ``(T, nq)``, at ``times`` (rules of ``FrameTree.pose``).

        Each free-flyer gets the interpolated pose of its frame (``x y z qx qy qz qw``),
        each robot joint its interpolated value. ``times=None`` takes the union of every
        moving thing's keyframe times (one configuration if nothing moves).
        """
        tree, compiled = self._tree, self._compiled
        samplers, sources, resting = path_samplers(tree, compiled)
        plan = plan_query(tree, tree.root, tree.root, times, time_ref, "clamp", sources)
        warn_joints_without_samples(tree, resting)
        return sample_configurations(compiled, samplers, plan.sample_times, plan.shifts)
