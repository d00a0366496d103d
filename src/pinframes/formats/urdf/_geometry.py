"""The ``<collision>`` and ``<visual>`` elements of URDF links, read into :class:`FrameGeometry`.

Read as urdfdom reads them: an ``<origin>`` (identity when absent) and one ``<geometry>`` with
a ``<box size>``, ``<cylinder radius length>``, ``<sphere radius>`` or ``<mesh filename
[scale]>``; a visual's ``<material>`` is a colour given inline or the name of a top-level
``<material>``. Poses never need geometry, so a malformed element does not stop the robot
from mounting: it is recorded in :attr:`FrameGeometry.unreadable` with its field
(``collision[0].geometry.box.size``) and problem, for whoever uses that geometry to report.
An ``<origin>`` inside ``<geometry>`` (where urdfdom and Pinocchio ignore it) is ignored too;
:func:`stray_geometry_origins` names them for the reader's one warning. Mesh files are not
opened. :func:`shape_elements` writes recorded shapes back as such
elements, for frames that are no URDF link (shapes given by ``FrameTree.add_geometry``).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

from ...errors import FileFormatError
from ...values.geometry import FrameGeometry, Shape
from ._numbers import numbers

__all__ = ["link_geometry", "named_colours", "shape_elements", "stray_geometry_origins"]

_SIZES = {"box": ("size",), "cylinder": ("radius", "length"), "sphere": ("radius",)}
Colour = tuple[float, float, float, float]


def named_colours(root: ET.Element, source: str) -> dict[str, Colour]:
    """The colours of the top-level ``<material name>`` elements that give one."""
    colours = {}
    for material in root.iterfind("material"):
        name = material.get("name")
        colour = _colour(material, source, None, f"material {name!r}")
        if name and colour is not None:
            colours[name] = colour
    return colours


def link_geometry(link: ET.Element, name: str, source: str, colours: dict[str, Colour],
                  package_dirs: tuple[str, ...] = ()) -> FrameGeometry:
    """The shapes of ``link`` (a ``<link>`` element named ``name``) of the URDF ``source``;
    ``package_dirs``, absolute, are kept to look for its meshes in."""
    urdf = None if source == "<urdf string>" else os.path.abspath(source)
    shapes: dict[str, list[Shape]] = {"collision": [], "visual": []}
    unreadable = []
    for kind, found in shapes.items():
        for index, element in enumerate(link.iterfind(kind)):
            try:
                found.append(_shape(element, f"{kind}[{index}]", name, source, colours))
            except FileFormatError as exc:
                unreadable.append((exc.field or kind, exc.message))
    return FrameGeometry(name, urdf, tuple(shapes["collision"]), tuple(shapes["visual"]),
                         tuple(unreadable), package_dirs)


def stray_geometry_origins(root: ET.Element) -> list[str]:
    """The ``<origin>`` elements inside a link's ``<geometry>``, as ``link.collision[0]``."""
    found = []
    for link in root.iterfind("link"):
        for kind in ("collision", "visual"):
            for index, element in enumerate(link.iterfind(kind)):
                if element.find("geometry/origin") is not None:
                    found.append(f"{link.get('name')}.{kind}[{index}]")
    return found


def _shape(element: ET.Element, where: str, link: str, source: str,
           colours: dict[str, Colour]) -> Shape:
    geometry = element.find("geometry")
    described = [] if geometry is None else [child for child in geometry
                                             if isinstance(child.tag, str)
                                             and child.tag != "origin"]
    if len(described) != 1:
        raise FileFormatError(
            "expected one <geometry> holding one box, cylinder, sphere or mesh",
            file=source, frame=link, field=f"{where}.geometry")
    (shape,) = described
    field = f"{where}.geometry.{shape.tag}"
    origin = element.find("origin")
    x, y, z = numbers(origin, "xyz", 3, source, link, f"{where}.origin.xyz", (0.0, 0.0, 0.0))
    roll, pitch, yaw = numbers(origin, "rpy", 3, source, link, f"{where}.origin.rpy",
                               (0.0, 0.0, 0.0))
    rgba = None
    material = element.find("material")
    if where.startswith("visual") and material is not None:
        rgba = _colour(material, source, link, f"{where}.material")
        if rgba is None:
            rgba = colours.get(material.get("name", ""))
    mesh: str | None = None
    scale: tuple[float, ...] = (1.0, 1.0, 1.0)
    dimensions: tuple[float, ...] = ()
    if shape.tag == "mesh":
        mesh = shape.get("filename")
        if not mesh:
            raise FileFormatError("a <mesh> without filename", file=source, frame=link,
                                  field=f"{field}.filename")
        scale = numbers(shape, "scale", 3, source, link, f"{field}.scale", scale)
    elif shape.tag == "box":
        dimensions = numbers(shape, "size", 3, source, link, f"{field}.size", None)
    elif shape.tag in _SIZES:
        dimensions = tuple(numbers(shape, attribute, 1, source, link,
                                   f"{field}.{attribute}", None)[0]
                           for attribute in _SIZES[shape.tag])
    else:
        raise FileFormatError(f"unknown geometry <{shape.tag}>; expected box, cylinder, "
                              "sphere or mesh", file=source, frame=link, field=field)
    if dimensions and min(dimensions) < 0:
        raise FileFormatError(f"sizes must not be negative, got {dimensions}", file=source,
                              frame=link, field=field)
    return Shape(shape.tag, dimensions, (x, y, z), (roll, pitch, yaw), mesh, scale,
                 element.get("name"), rgba)


def _colour(material: ET.Element, source: str, link: str | None, where: str) -> Colour | None:
    colour = material.find("color")
    if colour is None:
        return None
    values = numbers(colour, "rgba", 4, source, link, f"{where}.color.rgba", None)
    return (values[0], values[1], values[2], values[3])


def shape_elements(recorded: FrameGeometry, frame: str) -> list[ET.Element]:
    """``<collision>`` and ``<visual>`` elements of the recorded shapes (a visual's colour
    as an inline material named ``FRAME_visual_INDEX``)."""
    elements = []
    for kind in ("collision", "visual"):
        for index, shape in enumerate(recorded.shapes(kind)):
            element = ET.Element(kind)
            ET.SubElement(element, "origin", xyz=_text(shape.xyz), rpy=_text(shape.rpy))
            geometry = ET.SubElement(element, "geometry")
            if shape.kind == "box":
                ET.SubElement(geometry, "box", size=_text(shape.dimensions))
            elif shape.kind == "cylinder":
                radius, length = shape.dimensions
                ET.SubElement(geometry, "cylinder", radius=repr(radius), length=repr(length))
            elif shape.kind == "sphere":
                ET.SubElement(geometry, "sphere", radius=repr(shape.dimensions[0]))
            else:
                ET.SubElement(geometry, "mesh", filename=str(shape.mesh),
                              scale=_text(shape.scale))
            if kind == "visual" and shape.rgba is not None:
                material = ET.SubElement(element, "material", name=f"{frame}_visual_{index}")
                ET.SubElement(material, "color", rgba=_text(shape.rgba))
            elements.append(element)
    return elements


def _text(values: tuple[float, ...]) -> str:
    return " ".join(repr(float(value)) for value in values)
