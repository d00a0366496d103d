"""Shapes to put on a frame: :class:`Box`, :class:`Cylinder`, :class:`Sphere`, :class:`Mesh`.

``FrameTree.add_geometry(frame, shape, origin=..., kind=...)`` records them on the frame as
URDF shapes are recorded on a robot's links (:class:`~pinframes.values.geometry.Shape`), so
that the clearance, the 3-D page, ``to_pinocchio()`` and the scene writer use them alike. A
plate, a pipe or a fixture needs no URDF of its own. Lengths in metres, centred on the
shape's origin as URDF's ``<box>``, ``<cylinder>`` (axis along z) and ``<sphere>`` are.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ArgumentTypeError, InvalidDataError
from .geometry import Shape
from .pose import Pose

__all__ = ["Box", "Cylinder", "Mesh", "ShapeLike", "Sphere", "shape_record"]

_NAMED_LOCATIONS = ("package://", "model://", "file://")


def _lengths(values: Any, count: int, field: str) -> tuple[float, ...]:
    """``count`` finite lengths (metres) that are not negative."""
    try:
        numbers = np.asarray(values, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ArgumentTypeError(f"expected {count} number(s), got {values!r}",
                                field=field) from None
    if numbers.shape != (count,) or not np.all(np.isfinite(numbers)) or np.any(numbers < 0):
        raise InvalidDataError(f"expected {count} finite lengths of 0 m or more, got "
                               f"{values!r}", field=field)
    return tuple(float(value) for value in numbers)


@dataclass(frozen=True, init=False)
class Box:
    """A box of full edge lengths ``size`` = ``(x, y, z)`` metres, centred on its origin."""

    size: tuple[float, float, float]

    def __init__(self, size: ArrayLike) -> None:
        x, y, z = _lengths(size, 3, "size")
        object.__setattr__(self, "size", (x, y, z))


@dataclass(frozen=True)
class Cylinder:
    """A solid cylinder of ``radius`` and ``length`` (metres) along its z axis, centred on
    its origin."""

    radius: float
    length: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", _lengths(self.radius, 1, "radius")[0])
        object.__setattr__(self, "length", _lengths(self.length, 1, "length")[0])


@dataclass(frozen=True)
class Sphere:
    """A ball of ``radius`` metres, centred on its origin."""

    radius: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", _lengths(self.radius, 1, "radius")[0])


@dataclass(frozen=True, init=False)
class Mesh:
    """The triangles of a mesh file (STL, COLLADA ``.dae``, OBJ, PLY), in its own
    coordinates times ``scale`` (one factor, or one per axis).

    ``path`` is a file (a relative path is taken from the current folder when the shape is
    added), or a ``package://`` / ``model://`` / ``file://`` name found as a URDF's meshes
    are. A closed mesh is a solid for the clearance, an open one a surface.
    """

    path: str
    scale: tuple[float, float, float]

    def __init__(self, path: str | os.PathLike[str], scale: float | ArrayLike = 1.0) -> None:
        if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
            raise ArgumentTypeError(f"expected a mesh file name, got {path!r}", field="path")
        name = os.fspath(path)
        if not name.startswith(_NAMED_LOCATIONS):
            name = os.path.abspath(name)
        object.__setattr__(self, "path", name)
        try:
            factors = np.asarray(scale, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            raise ArgumentTypeError(f"expected 1 or 3 numbers, got {scale!r}",
                                    field="scale") from None
        if factors.shape == (1,):
            factors = np.repeat(factors, 3)
        _lengths(np.abs(factors), 3, "scale")  # finite; mirroring signs allowed
        x, y, z = (float(factor) for factor in factors)
        object.__setattr__(self, "scale", (x, y, z))


ShapeLike = Box | Cylinder | Sphere | Mesh


def shape_record(shape: ShapeLike, origin: Pose | None = None,
                 rgba: tuple[float, float, float, float] | None = None) -> Shape:
    """``shape`` at ``origin`` (its coordinates in the frame; static) as a recorded
    :class:`~pinframes.values.geometry.Shape`."""
    xyz_rpy: tuple[float, ...] = (0.0,) * 6
    if origin is not None:
        if not isinstance(origin, Pose):
            raise ArgumentTypeError(f"expected a pinframes.Pose, got {type(origin).__name__}",
                                    field="origin")
        if origin.is_time_dependent:
            raise InvalidDataError("a shape's origin must be static (the frame moves)",
                                   field="origin")
        xyz_rpy = tuple(float(value) for value in origin.to_xyz_rpy())
    x, y, z, roll, pitch, yaw = xyz_rpy
    xyz, rpy = (x, y, z), (roll, pitch, yaw)
    if isinstance(shape, Box):
        return Shape("box", shape.size, xyz, rpy, rgba=rgba)
    if isinstance(shape, Cylinder):
        return Shape("cylinder", (shape.radius, shape.length), xyz, rpy, rgba=rgba)
    if isinstance(shape, Sphere):
        return Shape("sphere", (shape.radius,), xyz, rpy, rgba=rgba)
    if isinstance(shape, Mesh):
        return Shape("mesh", (), xyz, rpy, shape.path, shape.scale, rgba=rgba)
    raise ArgumentTypeError("expected a pinframes.Box, Cylinder, Sphere or Mesh, got "
                            f"{type(shape).__name__}", field="shape")
