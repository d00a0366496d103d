"""Generate the pipe's and the torch's visual and collision geometry: URDFs and STL meshes.

Run from the repository root::

    python models/welding_cell/make_geometry.py [--out DIR]

It writes into ``geometry/`` beside itself (or into ``--out DIR``), the same bytes on every
run. Everything is made here from cylinders and tubes; nothing is copied. Each URDF has one
link and no joint: the scene mounts it on a frame of the cell (``scene.yaml``, ``robots``),
so it moves with that frame. Lengths in metres. (The fixtures and the faceplate are boxes and
cylinders only: ``scene.yaml`` gives them as its frames' ``geometry`` entries.)

Collision geometry is made of primitives (what coal measures exactly and fastest): the pipe
is a solid cylinder of its outer diameter and length; the torch is three cylinders along its
body and neck, the neck ending where the drawn neck ends, 15 mm before the wire tip.

- ``pipe.urdf`` (on ``workpiece``): the two pipe halves (outer diameter 219.1 mm, wall 8 mm),
  a mesh ``meshes/pipe.stl`` named relative to the URDF.
- ``torch.urdf`` (on ``robot/flange``): the torch body and its 22 degree neck, a mesh
  ``meshes/torch.stl``, ending 15 mm before the wire tip (``torch_tcp``).
"""

from __future__ import annotations

import argparse
import struct
from pathlib import Path

import numpy as np

PIPE_RADIUS = 0.21910 / 2
PIPE_WALL = 0.008
TCP_IN_FLANGE = np.array([0.0, -0.0599370549465, 0.398349416731])
NECK_START_IN_FLANGE = np.array([0.0, 0.0, 0.25])


def tube(start: np.ndarray, end: np.ndarray, outer: float, inner: float = 0.0,
         sections: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """A closed cylinder (``inner == 0``) or hollow tube from ``start`` to ``end``."""
    axis = end - start
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 * np.linalg.norm(axis) else \
        np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    v = np.cross(axis / np.linalg.norm(axis), u)
    angles = 2 * np.pi * np.arange(sections) / sections
    ring = np.outer(np.cos(angles), u) + np.outer(np.sin(angles), v)
    radii = (outer, inner) if inner > 0 else (outer,)
    vertices = [start + r * ring for r in radii] + [end + r * ring for r in radii]
    faces = []
    k = np.arange(sections)
    nxt = (k + 1) % sections
    layers = len(radii)

    def quads(a: np.ndarray, b: np.ndarray, flip: bool) -> None:
        first = np.stack([a + k, b + k, b + nxt], axis=1)
        second = np.stack([a + k, b + nxt, a + nxt], axis=1)
        for tri in (first, second):
            faces.append(tri[:, ::-1] if flip else tri)

    quads(0, layers * sections, False)  # outer wall, start to end
    if inner > 0:
        quads(sections, (layers + 1) * sections, True)  # inner wall
        quads(0, sections, True)  # start face ring
        quads(layers * sections, (layers + 1) * sections, False)  # end face ring
        points = np.concatenate(vertices)
    else:
        centres = np.array([start, end])
        points = np.concatenate([*vertices, centres])
        first_centre, last_centre = 2 * sections, 2 * sections + 1
        faces.append(np.stack([np.full(sections, first_centre), nxt, k], axis=1))
        faces.append(np.stack([np.full(sections, last_centre), sections + k,
                               sections + nxt], axis=1))
    return points, np.concatenate(faces)


def merge(*parts: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    vertices, faces, offset = [], [], 0
    for points, triangles in parts:
        vertices.append(points)
        faces.append(triangles + offset)
        offset += len(points)
    return np.concatenate(vertices), np.concatenate(faces)


def stl_bytes(vertices: np.ndarray, faces: np.ndarray, name: str) -> bytes:
    """A binary STL: 80-byte header, count, then normal and three corners per triangle."""
    corners = vertices[faces].astype(np.float32)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    records = np.zeros(len(faces), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)),
                                          ("a", "<u2")])
    records["n"], records["v"] = normals, corners
    header = f"pinframes {name}".encode().ljust(80, b" ")
    return header + struct.pack("<I", len(faces)) + records.tobytes()


def urdf(name: str, visuals: list[str], materials: dict[str, str],
         collisions: list[str]) -> str:
    colours = "".join(f'  <material name="{key}"><color rgba="{rgba}"/></material>\n'
                      for key, rgba in materials.items())
    body = "".join(f"    <visual>\n{v}    </visual>\n" for v in visuals) + "".join(
        f"    <collision>\n{c}    </collision>\n" for c in collisions)
    return (f'<?xml version="1.0"?>\n<!-- written by models/welding_cell/make_geometry.py -->\n'
            f'<robot name="{name}">\n{colours}  <link name="{name}">\n{body}  </link>\n'
            "</robot>\n")


def visual(origin: str, geometry: str, material: str) -> str:
    return collision(origin, geometry) + f'      <material name="{material}"/>\n'


def collision(origin: str, geometry: str) -> str:
    return f"      <origin {origin}/>\n      <geometry>{geometry}</geometry>\n"


def cylinder_between(start: np.ndarray, end: np.ndarray, radius: float) -> str:
    """A collision cylinder from ``start`` to ``end`` (both in the y-z plane of the link)."""
    axis = end - start
    roll = np.arctan2(-axis[1], axis[2]) + 0.0  # turns its z axis onto ``axis`` (no -0)
    middle = (start + end) / 2
    return collision(f'xyz="{middle[0]:.6f} {middle[1]:.6f} {middle[2]:.6f}" '
                     f'rpy="{roll:.9f} 0 0"',
                     f'<cylinder radius="{radius}" length="{np.linalg.norm(axis):.6f}"/>')


def files() -> dict[str, bytes | str]:
    steel = {"steel": "0.62 0.64 0.68 1.0"}
    pipe = merge(tube(np.array([0, 0, -0.29]), np.array([0, 0, -0.0015]), PIPE_RADIUS,
                      PIPE_RADIUS - PIPE_WALL),
                 tube(np.array([0, 0, 0.0015]), np.array([0, 0, 0.29]), PIPE_RADIUS,
                      PIPE_RADIUS - PIPE_WALL))
    neck_direction = (TCP_IN_FLANGE - NECK_START_IN_FLANGE)
    neck_end = TCP_IN_FLANGE - 0.015 * neck_direction / np.linalg.norm(neck_direction)
    torch = merge(tube(np.array([0, 0, 0.0]), np.array([0, 0, 0.06]), 0.035, sections=32),
                  tube(np.array([0, 0, 0.06]), NECK_START_IN_FLANGE, 0.022, sections=32),
                  tube(NECK_START_IN_FLANGE, neck_end, 0.011, sections=24))
    return {
        "pipe.urdf": urdf("pipe", [
            visual('xyz="0 0 0" rpy="0 0 0"', '<mesh filename="meshes/pipe.stl"/>', "steel")],
            steel, [collision('xyz="0 0 0" rpy="0 0 0"',
                              f'<cylinder radius="{PIPE_RADIUS}" length="0.58"/>')]),
        "torch.urdf": urdf("torch", [
            visual('xyz="0 0 0" rpy="0 0 0"', '<mesh filename="meshes/torch.stl"/>',
                   "torch_black")], {"torch_black": "0.12 0.12 0.13 1.0"}, [
            cylinder_between(np.array([0, 0, 0.0]), np.array([0, 0, 0.06]), 0.035),
            cylinder_between(np.array([0, 0, 0.06]), NECK_START_IN_FLANGE, 0.022),
            cylinder_between(NECK_START_IN_FLANGE, neck_end, 0.011)]),
        "meshes/pipe.stl": stl_bytes(*pipe, "pipe"),
        "meshes/torch.stl": stl_bytes(*torch, "torch"),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=Path(__file__).parent / "geometry")
    out = parser.parse_args().out
    for name, content in files().items():
        path = out / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content, encoding="utf-8")
        print(f"wrote {path} ({len(content)} bytes)")


if __name__ == "__main__":
    main()
