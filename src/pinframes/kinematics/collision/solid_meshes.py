"""Closed meshes as solids: which meshes enclose a volume, and whether a point lies inside.

coal measures a mesh as a surface of triangles: a ball wholly inside a meshed fixture is
some distance away from every triangle, and coal reports that distance. A mesh whose
triangles close up (every edge shared by exactly two triangles, in opposite directions,
once identical vertices are merged) bounds a solid; :class:`SolidMesh` tells whether a point
lies in it by the generalised winding number (the solid angle its triangles span, seen
from the point, over 4 pi: 1 inside, 0 outside), which holds for any closed mesh, convex or
not. An open mesh (a sheet, a mesh with a hole) stays a surface.

:func:`solid_mesh` also gives one point on each connected piece of a mesh: a shape whose
surface does not cross a closed mesh's lies either wholly inside it or wholly outside,
piece by piece, so one point per piece tells which. Lengths in metres, in the mesh's own
coordinates.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["SolidMesh", "solid_mesh"]

FloatArray = NDArray[np.float64]
IndexArray = NDArray[np.int64]


class SolidMesh:
    """The solid a closed mesh bounds (see the module's docstring).

    Parameters
    ----------
    corners : ndarray, shape (m, 3, 3)
        Each triangle's three corners, metres.
    """

    def __init__(self, corners: FloatArray) -> None:
        self._corners = corners
        self.lower = corners.reshape(-1, 3).min(axis=0)
        self.upper = corners.reshape(-1, 3).max(axis=0)

    def contains(self, points: FloatArray) -> bool:
        """Whether any of ``points`` ``(k, 3)`` lies inside the solid."""
        for point in points:
            if np.any(point < self.lower) or np.any(point > self.upper):
                continue
            if abs(self._winding_number(point)) > 0.5:
                return True
        return False

    def _winding_number(self, point: FloatArray) -> float:
        """Solid angle of the triangles seen from ``point``, over 4 pi (Van Oosterom and
        Strackee's formula per triangle)."""
        a, b, c = np.moveaxis(self._corners - point, 1, 0)
        la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
        numerator = np.einsum("ij,ij->i", a, np.cross(b, c))
        denominator = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
                       + np.einsum("ij,ij->i", a, c) * lb + np.einsum("ij,ij->i", b, c) * la)
        return float(2.0 * np.arctan2(numerator, denominator).sum() / (4.0 * np.pi))


def solid_mesh(vertices: FloatArray, triangles: IndexArray
               ) -> tuple[SolidMesh | None, FloatArray]:
    """The solid that the mesh bounds (None when the mesh is open), and one vertex of each
    connected piece of its triangles, shape ``(k, 3)``."""
    merged, triangles = _merged(vertices, triangles)
    return _solid(merged, triangles), _piece_points(merged, triangles)


def _solid(merged: FloatArray, triangles: IndexArray) -> SolidMesh | None:
    if triangles.shape[0] < 4:
        return None
    directed = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]],
                               triangles[:, [2, 0]]])
    size = merged.shape[0] + 1
    forward = np.sort(directed[:, 0] * size + directed[:, 1])
    backward = np.sort(directed[:, 1] * size + directed[:, 0])
    # closed and consistently turned: each directed edge once, and its reverse once
    if np.any(forward[1:] == forward[:-1]) or not np.array_equal(forward, backward):
        return None
    return SolidMesh(merged[triangles])


def _piece_points(merged: FloatArray, triangles: IndexArray) -> FloatArray:
    """One vertex of each connected piece, by union-find on whole arrays: every edge whose
    ends lie in different trees hangs the larger root on the smaller, then every vertex
    jumps to its root, until no edge joins two trees."""
    start, end = triangles.reshape(-1), triangles[:, [1, 2, 0]].reshape(-1)
    parent = np.arange(merged.shape[0])
    while True:
        first, second = parent[start], parent[end]
        apart = first != second
        if not apart.any():
            break
        np.minimum.at(parent, np.maximum(first, second)[apart], np.minimum(first, second)[apart])
        while not np.array_equal(jumped := parent[parent], parent):
            parent = jumped
    return merged[np.unique(parent[np.unique(triangles)])]


def _merged(vertices: FloatArray, triangles: IndexArray) -> tuple[FloatArray, IndexArray]:
    """Identical vertices merged, and triangles with a repeated corner left out."""
    rows = np.ascontiguousarray(vertices + 0.0)  # -0.0 and 0.0: one vertex
    keys = rows.view(np.dtype((np.void, rows.dtype.itemsize * 3))).reshape(-1)
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    triangles = inverse.reshape(-1)[triangles]
    keep = ((triangles[:, 0] != triangles[:, 1]) & (triangles[:, 1] != triangles[:, 2])
            & (triangles[:, 0] != triangles[:, 2]))
    return rows[first], triangles[keep]
