"""Closed meshes as solids: which meshes enclose a volume, and whether a point lies inside.

coal measures a mesh as a surface of triangles: a ball wholly inside a meshed fixture is
some distance away from every triangle, and coal reports that distance. A mesh whose
triangles close up (every edge shared by exactly two triangles, in opposite directions,
once identical vertices are merged) bounds a solid; :class:`SolidMesh` tells whether a point
lies in it by the generalised winding number (the solid angle its triangles span, seen
from the point, over 4 pi: 1 inside, 0 outside), which holds for any closed mesh, convex or
not. An open mesh (a sheet, a mesh with a hole) stays a surface.

:func:`component_points` gives one point on each connected piece of a mesh: a shape whose
surface does not cross a closed mesh's lies either wholly inside it or wholly outside,
piece by piece, so one point per piece tells which. Lengths in metres, in the mesh's own
coordinates.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["SolidMesh", "component_points", "solid_mesh"]

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


def solid_mesh(vertices: FloatArray, triangles: IndexArray) -> SolidMesh | None:
    """The solid that the mesh bounds, or None when the mesh is open."""
    merged, triangles = _merged(vertices, triangles)
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


def component_points(vertices: FloatArray, triangles: IndexArray) -> FloatArray:
    """One vertex of each connected piece of the mesh's triangles, shape ``(k, 3)``."""
    merged, triangles = _merged(vertices, triangles)
    labels = np.arange(merged.shape[0])
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]]])
    while True:  # each vertex takes the smallest label of its neighbours until none changes
        before = labels.copy()
        smaller = np.minimum(labels[edges[:, 0]], labels[edges[:, 1]])
        np.minimum.at(labels, edges[:, 0], smaller)
        np.minimum.at(labels, edges[:, 1], smaller)
        labels = labels[labels]
        if np.array_equal(labels, before):
            break
    used = np.unique(triangles)
    return merged[np.unique(labels[used])]


def _merged(vertices: FloatArray, triangles: IndexArray) -> tuple[FloatArray, IndexArray]:
    """Identical vertices merged, and triangles with a repeated corner left out."""
    merged, inverse = np.unique(vertices, axis=0, return_inverse=True)
    triangles = inverse.reshape(-1)[triangles]
    keep = ((triangles[:, 0] != triangles[:, 1]) & (triangles[:, 1] != triangles[:, 2])
            & (triangles[:, 0] != triangles[:, 2]))
    return merged, triangles[keep]
