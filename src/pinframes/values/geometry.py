"""The geometry of a frame: a URDF link's ``<collision>`` and ``<visual>`` shapes, and those
given by ``FrameTree.add_geometry``.

A :class:`FrameGeometry` is what the URDF mounter records for every link it adds to a tree,
and what ``add_geometry`` adds to (in the frame's metadata under
:data:`GEOMETRY_METADATA_KEY`, so that renaming, removing, grafting and copying carry it).
The clearance query turns it into coal objects, the 3-D page into triangles; neither parses
the URDF again. Mesh files are named as the URDF writes them and are only opened by those
consumers. Lengths in metres.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import InvalidDataError
from .pose import Pose

__all__ = ["GEOMETRY_KINDS", "GEOMETRY_METADATA_KEY", "SHAPE_KINDS", "FrameGeometry", "Shape"]

GEOMETRY_METADATA_KEY = "geometry"
"""Key of ``FrameTree.frame_metadata(frame)`` under which a link's :class:`FrameGeometry` lives."""

GEOMETRY_KINDS = ("collision", "visual")
"""The two geometries of a URDF link."""

SHAPE_KINDS = ("box", "cylinder", "sphere", "mesh")
"""The shapes a URDF ``<geometry>`` can hold."""


@dataclass(frozen=True)
class Shape:
    """One ``<collision>`` or ``<visual>`` element of a URDF link.

    Attributes
    ----------
    kind : {"box", "cylinder", "sphere", "mesh"}
        The shape.
    dimensions : tuple of float
        Metres: a box's full edge lengths ``(x, y, z)``; a cylinder's ``(radius, length)``,
        its axis along z, centred on its origin; a sphere's ``(radius,)``; ``()`` for a mesh.
    xyz, rpy : tuple of float
        The URDF ``<origin>``: the shape's own coordinate system in the link frame, metres
        and radians (roll, pitch, yaw as URDF); :attr:`origin` gives it as a :class:`Pose`.
    mesh : str or None
        A mesh's file name as the URDF writes it (``package://...``, ``file://...``, absolute,
        or relative to the URDF's folder); None for the other shapes.
    scale : tuple of float
        A mesh's scale factors along its x, y, z axes (``(1, 1, 1)`` for the other shapes).
    name : str or None
        The element's ``name`` attribute.
    rgba : tuple of float or None
        A visual's material colour (red, green, blue, alpha in 0..1), named materials
        resolved; None when the URDF gives none, and for collisions.
    """

    kind: str
    dimensions: tuple[float, ...]
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    mesh: str | None = None
    scale: tuple[float, ...] = (1.0, 1.0, 1.0)
    name: str | None = None
    rgba: tuple[float, float, float, float] | None = None

    @property
    def origin(self) -> Pose:
        """The shape's coordinate system in the link frame (static)."""
        return Pose.from_xyz_rpy(*self.xyz, *self.rpy)

    def describe(self) -> str:
        """``box 0.1 x 0.2 x 0.3 m``, ``mesh meshes/pipe.stl``: for messages and tables."""
        if self.kind == "mesh":
            return f"mesh {self.mesh}"
        return f"{self.kind} " + " x ".join(f"{value:g}" for value in self.dimensions) + " m"


@dataclass(frozen=True)
class FrameGeometry:
    """The shapes of one frame: a URDF link's, as recorded when the robot was attached, and
    those added by ``FrameTree.add_geometry``.

    Attributes
    ----------
    link : str
        The link's name in its URDF (without the tree's prefix); for a frame that is no
        link, the frame's name when its first shape was added.
    urdf : str or None
        The URDF file, as an absolute path (its folder resolves relative mesh names); None
        when the robot came from an XML string.
    collision, visual : tuple of Shape
        The link's readable ``<collision>`` and ``<visual>`` elements, in document order.
    unreadable : tuple of (str, str)
        ``(field, problem)`` for each element that could not be read (``("collision[1]
        .geometry.box.size", "expected three finite numbers, got '1 2'")``): poses never
        need geometry, so a URDF with a malformed shape still mounts; whoever uses that
        geometry reports it.
    """

    link: str
    urdf: str | None
    collision: tuple[Shape, ...] = field(default=())
    visual: tuple[Shape, ...] = field(default=())
    unreadable: tuple[tuple[str, str], ...] = field(default=())
    package_dirs: tuple[str, ...] = field(default=())

    def shapes(self, kind: str) -> tuple[Shape, ...]:
        """The ``"collision"`` or ``"visual"`` shapes."""
        if kind not in GEOMETRY_KINDS:
            raise InvalidDataError(f"expected one of {', '.join(GEOMETRY_KINDS)}, got {kind!r}",
                                   field="geometry")
        return self.collision if kind == "collision" else self.visual

    def unreadable_shapes(self, kind: str) -> tuple[tuple[str, str], ...]:
        """``(field, problem)`` of the ``kind`` elements that could not be read."""
        self.shapes(kind)
        return tuple(entry for entry in self.unreadable if entry[0].startswith(kind))
