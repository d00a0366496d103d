"""Mesh files written by hand for the tests: binary STL and COLLADA, plain numpy."""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

CUBE_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
CUBE_TRIANGLES = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                           [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
"""A cube of edge 2 centred on the origin, its triangles turned outwards (the last two:
the face at z = +1)."""


def write_stl(path: Path, vertices: np.ndarray, triangles: np.ndarray) -> Path:
    """A binary STL: 80-byte header, count, then per triangle a zero normal, three corners
    and a zero attribute word."""
    corners = np.asarray(vertices, dtype="<f4")[np.asarray(triangles)]
    with open(path, "wb") as handle:
        handle.write(b"written by the pinframes tests".ljust(80, b" "))
        handle.write(struct.pack("<I", len(triangles)))
        for triangle in corners:
            handle.write(struct.pack("<3f", 0.0, 0.0, 0.0) + triangle.tobytes() + b"\0\0")
    return path


def write_cube_stl(path: Path, edge: float, open_top: bool = False) -> Path:
    triangles = CUBE_TRIANGLES[:-2] if open_top else CUBE_TRIANGLES
    return write_stl(path, CUBE_CORNERS * edge / 2, triangles)


def nested_instances_dae(levels: int, fan: int = 2) -> str:
    """A COLLADA file of one triangle (corners (0,0,0), (1,0,0), (0,1,0)) in a node that
    ``levels`` nodes above it each instance ``fan`` times, each level moving its copies 1 m
    up: ``fan ** levels`` triangles, every one at ``z = levels`` m."""
    nodes = ['<node id="n0"><instance_geometry url="#tri"/></node>']
    for level in range(1, levels + 1):
        instances = f'<instance_node url="#n{level - 1}"/>' * fan
        nodes.append(f'<node id="n{level}"><translate>0 0 1</translate>{instances}</node>')
    return f"""<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
<library_geometries><geometry id="tri"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common>
</source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_nodes>{"".join(nodes)}</library_nodes>
<library_visual_scenes><visual_scene id="s"><node id="root">
<instance_node url="#n{levels}"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"""
