"""coal geometries of the shapes recorded for a frame (a :class:`~pinframes.FrameGeometry`).

Boxes, cylinders and spheres become coal's primitives, as Pinocchio's URDF reader makes them
(``coal.Box`` of the full edge lengths, ``coal.Cylinder(radius, length)`` along z,
``coal.Sphere``); meshes are read by :func:`~.mesh_reader.read_mesh` (the reader the 3-D page
uses too) from the file :class:`~.mesh_files.MeshFiles` finds, into the BVH models
(``BVHModelOBBRSS``, the scale applied) that ``pinocchio.buildGeomFromUrdf`` builds. So a
distance computed here is the distance Pinocchio + coal compute on the same URDF (for
COLLADA meshes, once their unit is applied, which Pinocchio's loader does not do). A closed
mesh also carries the solid it bounds (:mod:`.solid_meshes`). Sizes, origins and scaled
vertices must be finite and within :data:`LARGEST_COORDINATE` metres, where coal's squared
distances stay exact enough. Every problem is a :class:`~pinframes.errors.GeometryError`
naming the frame, the shape's field and the file.
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
from .mesh_files import HOW_TO_SEARCH, mesh_file_problem, mesh_files_of, outside_its_package
from .mesh_reader import DEFAULT_BOUNDS, MeshBounds, TriangleBudget, read_mesh
from .solid_meshes import SolidMesh, solid_mesh

__all__ = ["LARGEST_COORDINATE", "CollisionShape", "ShapeLoader"]

LARGEST_COORDINATE = 1e9
"""Metres: the largest size or vertex coordinate a shape may have (a million kilometres;
coal squares distances, and far beyond this its answers lose every digit)."""


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
    solid : SolidMesh or None
        For a closed mesh, the solid it bounds; None for primitives (coal measures them as
        solids already) and open meshes.
    probes : ndarray, shape (k, 3)
        One point of each connected piece of the shape, in its own coordinates: if none of
        them lies in another shape's solid and the surfaces do not meet, the shape is
        outside that solid.
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
    solid: SolidMesh | None
    probes: NDArray[np.float64]


class ShapeLoader:
    """Makes the coal shapes of frames, reading each mesh file once.

    Parameters
    ----------
    kind : {"collision", "visual"}
        Which geometry of the URDF links.
    package_dirs : iterable of path
        Folders searched for ``package://``, ``model://`` and relative mesh names first,
        before those given when each robot was read (see
        :func:`~pinframes.kinematics.collision.mesh_files.mesh_files_of`).
    bounds : MeshBounds
        The most triangles one mesh file may hold after instancing, and its most bytes.
    """

    def __init__(self, kind: str, package_dirs: Iterable[str | os.PathLike[str]] = (),
                 bounds: MeshBounds = DEFAULT_BOUNDS) -> None:
        if kind not in GEOMETRY_KINDS:
            raise GeometryError(f"expected one of {', '.join(GEOMETRY_KINDS)}, got {kind!r}",
                                field="geometry")
        self.kind = kind
        self.bounds = bounds
        self._package_dirs = tuple(package_dirs)
        self._files: dict[str, tuple[NDArray[np.float64], NDArray[np.int64]]] = {}
        self._meshes: dict[tuple[str, tuple[float, ...]], _Mesh] = {}

    def shapes(self, frame: str, geometry: FrameGeometry | None,
               budget: TriangleBudget | None = None) -> list[CollisionShape]:
        """The coal shapes of ``frame``, whose recorded geometry is ``geometry``; their
        meshes' triangles are taken from ``budget``, the request's (None: a budget of
        their own)."""
        budget = TriangleBudget(self.bounds.max_triangles) if budget is None else budget
        kind = self.kind
        if geometry is None:
            raise GeometryError(
                f"has no geometry: only the links of attached URDFs (their <{kind}> elements) "
                "and frames given shapes by add_geometry have some", frame=frame,
                field="geometry")
        for field, problem in geometry.unreadable_shapes(kind):
            raise GeometryError(f"link {geometry.link!r}: {problem}", file=geometry.urdf,
                                frame=frame, field=field)
        if not geometry.shapes(kind):
            raise GeometryError(f"link {geometry.link!r} has no <{kind}> geometry",
                                file=geometry.urdf, frame=frame, field=kind)
        return [self._shape(frame, f"{kind}[{index}]", shape, geometry, budget)
                for index, shape in enumerate(geometry.shapes(kind))]

    def _shape(self, frame: str, field: str, shape: Shape, geometry: FrameGeometry,
               budget: TriangleBudget) -> CollisionShape:
        _check_sizes(frame, field, shape, geometry)
        mesh_path, solid, probes = None, None, np.zeros((1, 3))
        if shape.kind == "mesh":
            assert shape.mesh is not None  # a mesh always names its file
            mesh_path = self._find(frame, field, shape.mesh, geometry)
            mesh = self._mesh(frame, field, mesh_path, shape.scale, budget)
            made, solid, probes = mesh.model, mesh.solid, mesh.probes
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
                              centre, radius, mesh_path, solid, probes)

    def _find(self, frame: str, field: str, name: str, geometry: FrameGeometry) -> str:
        if (refused := outside_its_package(name)) is not None:
            raise GeometryError(f"link {geometry.link!r}: mesh {name!r} {refused}",
                                file=geometry.urdf, frame=frame, field=f"{field}.mesh")
        mesh_files = mesh_files_of(geometry, self._package_dirs)
        found = mesh_files.find(name)
        if found is None:
            raise GeometryError(f"link {geometry.link!r}: mesh {name!r} not found "
                                f"({mesh_files.looked_in(name)}); {HOW_TO_SEARCH}",
                                file=geometry.urdf,
                                frame=frame, field=f"{field}.mesh")
        return str(found)

    def _mesh(self, frame: str, field: str, path: str, scale: tuple[float, ...],
              budget: TriangleBudget) -> _Mesh:
        where = {"file": path, "frame": frame, "field": f"{field}.mesh"}
        vertices, triangles = self._file(path, where)
        if (problem := budget.problem(triangles.shape[0])) is not None:
            raise GeometryError(f"mesh: {problem}", **where)
        key = (path, scale)
        mesh = self._meshes.get(key)
        if mesh is None:
            with np.errstate(over="ignore", invalid="ignore"):
                vertices = vertices * np.array(scale)
            if not np.all(np.abs(vertices) <= LARGEST_COORDINATE):
                raise GeometryError(
                    f"mesh vertices (scale {' '.join(map(str, scale))} applied) must be finite "
                    f"and within {LARGEST_COORDINATE:g} m", **where)
            corners = vertices[triangles]
            normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            # coal measures a triangle of no area wrongly (a ball 0.9 m beside one reads
            # -0.1 m): such triangles are left out
            triangles = triangles[np.any(normals != 0.0, axis=1)]
            if triangles.shape[0] == 0:
                raise GeometryError("mesh has no triangle of non-zero area (with the scale "
                                    f"{' '.join(map(str, scale))} applied)", **where)
            model = coal.BVHModelOBBRSS()
            model.beginModel(triangles.shape[0], vertices.shape[0])
            model.addVertices(vertices)
            model.addTriangles(triangles)
            model.endModel()
            mesh = _Mesh(model, *solid_mesh(vertices, triangles))
            self._meshes[key] = mesh
        return mesh

    def _file(self, path: str, where: dict[str, str]
              ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
        """The vertices (metres, unscaled) and triangles of the mesh file ``path``, read
        once whatever the scales it is used at."""
        if path not in self._files:
            if (problem := mesh_file_problem(Path(path), self.bounds.max_bytes)) is not None:
                raise GeometryError(f"mesh {problem}", **where)
            try:
                self._files[path] = read_mesh(
                    Path(path), max_triangles=self.bounds.max_triangles).merged()
            except GeometryError as exc:
                raise GeometryError(f"mesh {exc.message}", **where) from None
        return self._files[path]


@dataclass(frozen=True)
class _Mesh:
    """A mesh file's coal model at one scale, its solid when closed, and one point of each
    of its pieces."""

    model: Any
    solid: SolidMesh | None
    probes: NDArray[np.float64]


def _check_sizes(frame: str, field: str, shape: Shape, geometry: FrameGeometry) -> None:
    """Sizes and the origin finite and within :data:`LARGEST_COORDINATE`, sizes not negative
    (a mesh's scaled vertices are checked when it is read)."""
    for name, values in (("dimensions", shape.dimensions), ("origin", (*shape.xyz, *shape.rpy))):
        numbers = np.asarray(values, dtype=float)
        if not np.all(np.abs(numbers) <= LARGEST_COORDINATE) or (
                name == "dimensions" and np.any(numbers < 0)):
            raise GeometryError(
                f"{shape.describe()}: {name} must be finite and within "
                f"{LARGEST_COORDINATE:g} m (sizes not negative), got {tuple(values)}",
                file=geometry.urdf, frame=frame, field=f"{field}.{name}")
