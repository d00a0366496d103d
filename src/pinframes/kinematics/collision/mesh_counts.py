"""Triangles of an STL, OBJ, PLY or OFF file counted from its bytes, before assimp loads it.

assimp builds every triangle before anyone can count them, and triangulates a polygon in
time that grows with the square of its corners. So the count comes first: a binary STL's
from its header, an ASCII STL's facets, the faces of an OBJ, a PLY (ASCII or binary) and an
OFF file, each polygon of ``k`` corners counting ``k - 2`` triangles, as assimp splits it.
A polygon of more than :data:`MAX_POLYGON_CORNERS` corners is refused. The scan reads the
file's bytes once (files are no larger than the bound already checked; a binary STL's
first 84 bytes only).
"""

from __future__ import annotations

import io
import re
import struct
from collections.abc import Iterable
from pathlib import Path

from ...errors import GeometryError

__all__ = ["MAX_POLYGON_CORNERS", "polygon_triangles"]

MAX_POLYGON_CORNERS = 10_000
"""The most corners of one polygon of an OBJ, PLY or OFF file (assimp's triangulation takes
time with the square of the corners: one of 400,000 ran for minutes)."""

_ASCII_FACET = re.compile(rb"(?i)(?<![a-z])facet\b")
_OBJ_FACE = re.compile(rb"^[ \t]*f[ \t]+([^\r\n]*)", re.MULTILINE)
_PLY_SIZES = {"char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2,
              "int16": 2, "uint16": 2, "int": 4, "uint": 4, "int32": 4, "uint32": 4,
              "float": 4, "float32": 4, "double": 8, "float64": 8}
_PLY_CODES = {1: "B", 2: "H", 4: "I", 8: "Q"}
_PlyElements = list[tuple[str, int, list[list[str]]]]


def polygon_triangles(path: Path) -> int:
    """The triangles assimp makes of the STL, OBJ, PLY or OFF file at ``path`` (by its
    suffix), counted without building any; a :class:`GeometryError` naming the file for a
    polygon of more than :data:`MAX_POLYGON_CORNERS` corners, or a PLY file shorter than its
    header declares."""
    suffix = path.suffix.lower()
    with open(path, "rb") as handle:
        if suffix == ".stl":
            return _stl(handle)
        data = handle.read()
    corners = (_obj(data) if suffix == ".obj" else _ply(data, path) if suffix == ".ply"
               else _off(data))
    return _triangles(corners, path)


def _triangles(corners: Iterable[int], path: Path) -> int:
    """The triangles of polygons of ``corners`` corners each, none over the bound."""
    total = 0
    for count in corners:
        if count > MAX_POLYGON_CORNERS:
            raise GeometryError(f"cannot be read: a polygon of {count:,} corners, over the "
                                f"{MAX_POLYGON_CORNERS:,} pinframes reads", file=str(path))
        total += max(count - 2, 0)
    return total


def _stl(handle: io.BufferedReader) -> int:
    """A binary STL holds its count in bytes 80..84 (50 bytes per triangle after them); an
    ASCII one (``solid`` first, and not of that size) one ``facet`` per triangle."""
    size = handle.seek(0, io.SEEK_END)
    handle.seek(0)
    head = handle.read(84)
    if size >= 84:
        (count,) = struct.unpack_from("<I", head, 80)
        if size == 84 + 50 * count or not head.lstrip().lower().startswith(b"solid"):
            return int(count)
    return sum(1 for _ in _ASCII_FACET.finditer(head + handle.read()))


def _obj(data: bytes) -> Iterable[int]:
    for face in _OBJ_FACE.finditer(data):
        yield len(face.group(1).split(b"#", 1)[0].split())


def _ply(data: bytes, path: Path) -> Iterable[int]:
    """The corner count of each face of a PLY file, ASCII or binary."""
    end = data.find(b"end_header")
    if end < 0:
        raise GeometryError("cannot be read: a PLY file without 'end_header'", file=str(path))
    header = data[:end].decode("ascii", "replace").splitlines()
    body = data.find(b"\n", end) + 1
    layout = next((line.split()[1] for line in header
                   if line.startswith("format ") and len(line.split()) > 1), "ascii")
    elements: _PlyElements = []
    for line in header:
        words = line.split()
        if words[:1] == ["element"] and len(words) == 3 and words[2].isdigit():
            elements.append((words[1], int(words[2]), []))
        elif words[:1] == ["property"] and elements:
            elements[-1][2].append(words[1:])
    if layout == "ascii":
        return _ply_ascii(data, body, elements)
    return _ply_binary(data, body, elements, "<" if "little" in layout else ">", path)


def _ply_ascii(data: bytes, body: int, elements: _PlyElements) -> Iterable[int]:
    lines = io.BytesIO(data[body:])
    for name, count, _ in elements:
        for _, line in zip(range(count), iter(lines.readline, b""), strict=False):
            if name == "face":
                words = line.split()
                yield int(words[0]) if words and words[0].isdigit() else 0
        if name == "face":
            return


def _ply_binary(data: bytes, offset: int, elements: _PlyElements, order: str,
                path: Path) -> Iterable[int]:
    for name, count, properties in elements:
        if name != "face" and all(item[0] != "list" for item in properties):
            offset += count * sum(_PLY_SIZES.get(item[0], 0) for item in properties)
            continue
        for _ in range(count):
            for item in properties:
                if item[0] != "list" or len(item) < 3:
                    offset += _PLY_SIZES.get(item[0], 0)
                    continue
                size = _PLY_SIZES.get(item[1], 1)
                if offset + size > len(data):
                    raise GeometryError("cannot be read: a PLY file shorter than its header "
                                        "declares", file=str(path))
                (corners,) = struct.unpack_from(order + _PLY_CODES[size], data, offset)
                offset += size + corners * _PLY_SIZES.get(item[2], 4)
                if name == "face":
                    yield corners
        if name == "face":
            return


def _off(data: bytes) -> Iterable[int]:
    """The corner count of each face of an ASCII OFF file: a header line (``OFF``, or
    ``COFF`` and the like), the vertex, face and edge counts, the vertices, the faces;
    ``#`` starts a comment."""
    lines = (words for line in io.BytesIO(data)
             if (words := line.split(b"#", 1)[0].split()))
    header = next(lines, [])
    counts = (header[1:] or next(lines, [])) if header[:1] and header[0].endswith(
        b"OFF") else header
    if len(counts) < 2 or not (counts[0].isdigit() and counts[1].isdigit()):
        return
    vertices, faces = int(counts[0]), int(counts[1])
    for _ in zip(range(vertices), lines, strict=False):
        pass
    for _, words in zip(range(faces), lines, strict=False):
        yield int(words[0]) if words[0].isdigit() else 0
