"""coal geometries of the shapes recorded for a frame (a :class:`~pinframes.FrameGeometry`).

Boxes, cylinders and spheres become coal's primitives, as Pinocchio's URDF reader makes them
(``coal.Box`` of the full edge lengths, ``coal.Cylinder(radius, length)`` along z,
``coal.Sphere``); meshes are read by coal's own mesh loader (assimp) into the same BVH models
(``BVHModelOBBRSS``, the scale applied) that ``pinocchio.buildGeomFromUrdf`` builds, from the
file :class:`~pinframes.kinematics.collision.mesh_files.MeshFiles` finds. So a distance
computed here is the distance Pinocchio + coal compute on the same URDF. Every problem is a
:class:`~pinframes.errors.GeometryError` naming the frame, the shape's field and the file.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import coal
import numpy as np
from numpy.typing import NDArray

from ...errors import GeometryError
from ...values.geometry import GEOMETRY_KINDS, FrameGeometry, Shape
from .mesh_files import HOW_TO_SEARCH, MeshFiles, mesh_file_problem, package_search_dirs

__all__ = ["CollisionShape", "ShapeLoader"]


@dataclass(frozen=True)
class CollisionShape:
    """One shape of a frame, ready for coal.

    Attributes
    ----------
    frame : str
        The tree frame (a URDF link) the shape hangs on.
    field : str
        Where the shape is in its URDF link: ``collision[0]``, ``visual[2]``.
    shape : Shape
        The recorded shape.
    geometry : coal.CollisionGeometry
        The coal object, in the shape's own coordinates.
    rotation, translation : ndarray, shapes (3, 3) and (3,)
        The shape's coordinates in the frame (its URDF ``<origin>``), metres.
    centre, radius : ndarray (3,) and float
        A sphere that holds the whole shape, its centre in the shape's own coordinates
        (metres): two shapes whose spheres are ``d`` apart are at least ``d`` apart.
    mesh_path : str or None
        The mesh file read, for a mesh.
    """

    frame: str
    field: str
    shape: Shape
    geometry: Any
    rotation: NDArray[np.float64]
    translation: NDArray[np.float64]
    centre: NDArray[np.float64]
    radius: float
    mesh_path: str | None


class ShapeLoader:
    """Makes the coal shapes of frames, reading each mesh file once.

    Parameters
    ----------
    kind : {"collision", "visual"}
        Which geometry of the URDF links.
    package_dirs : iterable of path
        Folders searched for ``package://`` and relative mesh names first (see
        :class:`~pinframes.kinematics.collision.mesh_files.MeshFiles`).
    """

    def __init__(self, kind: str, package_dirs: Iterable[str | os.PathLike[str]] = ()) -> None:
        if kind not in GEOMETRY_KINDS:
            raise GeometryError(f"expected one of {', '.join(GEOMETRY_KINDS)}, got {kind!r}",
                                field="geometry")
        self.kind = kind
        self._search_dirs = package_search_dirs(package_dirs)
        self._meshes: dict[tuple[str, tuple[float, ...]], Any] = {}

    def shapes(self, frame: str, geometry: FrameGeometry | None) -> list[CollisionShape]:
        """The coal shapes of ``frame``, whose recorded geometry is ``geometry``."""
        kind = self.kind
        if geometry is None:
            raise GeometryError(
                "has no geometry: only the links of attached URDFs have shapes (their "
                f"<{kind}> elements)", frame=frame, field="geometry")
        for field, problem in geometry.unreadable_shapes(kind):
            raise GeometryError(f"link {geometry.link!r}: {problem}", file=geometry.urdf,
                                frame=frame, field=field)
        if not geometry.shapes(kind):
            raise GeometryError(f"link {geometry.link!r} has no <{kind}> geometry",
                                file=geometry.urdf, frame=frame, field=kind)
        return [self._shape(frame, f"{kind}[{index}]", shape, geometry)
                for index, shape in enumerate(geometry.shapes(kind))]

    def _shape(self, frame: str, field: str, shape: Shape,
               geometry: FrameGeometry) -> CollisionShape:
        mesh_path = None
        if shape.kind == "mesh":
            assert shape.mesh is not None  # a mesh always names its file
            mesh_path = self._find(frame, field, shape.mesh, geometry)
            made = self._mesh(frame, field, mesh_path, shape.scale)
        elif shape.kind == "box":
            made = coal.Box(*shape.dimensions)
        elif shape.kind == "cylinder":
            made = coal.Cylinder(*shape.dimensions)
        else:
            made = coal.Sphere(*shape.dimensions)
        made.computeLocalAABB()
        centre = np.array(made.aabb_center)
        radius = float(made.aabb_radius)  # the box's corners: a mesh's vertices fit tighter
        if shape.kind == "mesh":
            radius = float(np.linalg.norm(np.asarray(made.vertices()) - centre, axis=1).max())
        origin = shape.origin
        return CollisionShape(frame, field, shape, made, origin.rotation, origin.translation,
                              centre, radius, mesh_path)

    def _find(self, frame: str, field: str, name: str, geometry: FrameGeometry) -> str:
        mesh_files = MeshFiles(None if geometry.urdf is None else Path(geometry.urdf),
                               self._search_dirs)
        found = mesh_files.find(name)
        if found is None:
            raise GeometryError(f"link {geometry.link!r}: mesh {name!r} not found "
                                f"({mesh_files.looked_in(name)}); {HOW_TO_SEARCH}",
                                file=geometry.urdf,
                                frame=frame, field=f"{field}.mesh")
        return str(found)

    def _mesh(self, frame: str, field: str, path: str, scale: tuple[float, ...]) -> Any:
        key = (path, scale)
        mesh = self._meshes.get(key)
        if mesh is None:
            if (problem := mesh_file_problem(Path(path), None)) is not None:
                raise GeometryError(f"mesh {problem}", file=path, frame=frame,
                                    field=f"{field}.mesh")
            try:
                mesh = coal.MeshLoader().load(path, np.array(scale, dtype=float))
            except (ValueError, RuntimeError) as exc:
                raise GeometryError(f"mesh cannot be read: {_loader_message(exc)}", file=path,
                                    frame=frame, field=f"{field}.mesh") from None
            if mesh.num_tris == 0:
                raise GeometryError("mesh has no triangles", file=path, frame=frame,
                                    field=f"{field}.mesh")
            self._meshes[key] = mesh
        return mesh


def _loader_message(error: Exception) -> str:
    """The reason in coal's loader error, without its C++ file and function lines."""
    text = str(error)
    _, found, reason = text.partition("message:")
    lines = [line.strip() for line in (reason if found else text).splitlines() if line.strip()]
    return "; ".join(lines[:3]) or type(error).__name__
