"""Tiny files that ask for huge work, as data: the reader, the file's bytes, the message.

Each of them once took seconds to minutes and gigabytes (or never ended); each must now end
with a pinframes error at once. ``test_resource_bounds.py`` reads them in a child process
with capped memory and CPU time.
"""

from __future__ import annotations

import io
import struct
import zipfile
from dataclasses import dataclass

import numpy as np

from weldx_asdf.asdf_texts import HEADER, lcs, legacy_hierarchy, time_grid


@dataclass(frozen=True)
class ResourceCase:
    id: str
    reader: str  # a key of readers.READERS
    content: bytes
    error: str  # the pinframes error class's name
    message: str


def alias_bomb(levels: int = 9, width: int = 10, indent: str = "") -> str:
    """YAML anchors ``b0`` .. ``b{levels-1}``, each a list of ``width`` aliases of the one
    before: ``b{levels-1}`` expands to ``width ** levels`` scalars (a billion by default)."""
    lines = [f"{indent}b0: &b0 [{', '.join(['x'] * width)}]"]
    lines += [f"{indent}b{level}: &b{level} [{', '.join([f'*b{level - 1}'] * width)}]"
              for level in range(1, levels)]
    return "\n".join(lines) + "\n"


def asdf_bytes(body: str) -> bytes:
    return (HEADER + body.strip("\n") + "\n...\n").encode()


def _moving_legacy(time: str) -> str:
    coordinates = lcs(version="1.0.0", coordinates=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                      time=time)
    return legacy_hierarchy("h", "root", [("a", "root", coordinates)])


def forged_npz(declared_bytes: int) -> bytes:
    """An NPZ of a few hundred bytes whose ``positions`` member declares ``declared_bytes``
    bytes once inflated (its ``.npy`` header promises as much): a decompression bomb as
    its ZIP directory describes it, without making the gigabytes."""
    rows = (declared_bytes - 128) // 8
    header = np.lib.format.header_data_from_array_1_0(np.zeros((1, 1)))
    header["shape"] = (rows, 1)
    buffer = io.BytesIO()
    np.lib.format.write_array_header_1_0(buffer, header)
    member = buffer.getvalue() + bytes(1024)
    archive = io.BytesIO()
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as zipped:
        for name, array in (("times", np.array([0.0, 1.0])), ("joint_names", np.array(["j"]))):
            saved = io.BytesIO()
            np.save(saved, array)
            zipped.writestr(f"{name}.npy", saved.getvalue())
        zipped.writestr("positions.npy", member)
    data = bytearray(archive.getvalue())
    declared = len(member) - 1024 + rows * 8
    local = zipfile.ZipFile(io.BytesIO(bytes(data))).getinfo("positions.npy").header_offset
    central = data.rindex(b"positions.npy") - 46  # the name ends the central header
    # the uncompressed size: byte 22 of the local header, byte 24 of the central one
    struct.pack_into("<I", data, local + 22, declared)
    struct.pack_into("<I", data, central + 24, declared)
    return bytes(data)


def entity_bomb(element: bool) -> str:
    """A URDF whose DTD nests entity definitions tenfold (text) or eightfold (elements): the
    link's name expands to 30 GB of text, or its body to 8**7 (two million) elements."""
    if element:
        base, count, levels = "<a/>" * 8, 8, 7
    else:
        base, count, levels = "lol" * 10, 10, 10
    entities = [f'<!ENTITY e0 "{base}">'] + [
        f'<!ENTITY e{level} "{f"&e{level - 1};" * count}">' for level in range(1, levels)]
    body = f"<link name='l'>&e{levels - 1};</link>" if element else (
        f"<link name='&e{levels - 1};'/>")
    return (f"<?xml version='1.0'?><!DOCTYPE robot [{''.join(entities)}]>"
            f"<robot name='r'>{body}</robot>")


RESOURCE_CASES = [
    ResourceCase("alias-bomb", "frames.yaml", (
        "version: 1.0\n" + alias_bomb()
        + "frames:\n  m: {relative_to: ~, pose: {x: *b8}}\n").encode(),
        "FileFormatError", "max_yaml_nodes"),
    ResourceCase("self-reference", "frames.yaml",
                 b"version: 1.0\nframes: &f\n  m: *f\n", "FileFormatError", "contains itself"),
    ResourceCase("alias-bomb", "scene", (
        "pinframes_scene: 1\n" + alias_bomb()
        + "frames:\n  - {name: a, parent: world, translation: *b8}\n").encode(),
        "FileFormatError", "max_yaml_nodes"),
    ResourceCase("self-reference", "scene", (
        b"pinframes_scene: 1\nroot: world\nlayers: &l [*l]\n"),
        "FileFormatError", "contains itself"),
    ResourceCase("grid-1ns", "asdf", asdf_bytes(_moving_legacy(
        time_grid("P0DT0H0M0S", "P0DT0H0M0.5S", "1N", legacy=True))),
        "FileFormatError", "max_samples"),
    ResourceCase("grid-century-1ns", "asdf", asdf_bytes(_moving_legacy(
        time_grid("P0DT0H0M0S", "P36500DT0H0M0S", "1N", legacy=True))),
        "FileFormatError", "max_samples"),
    ResourceCase("alias-bomb", "asdf", asdf_bytes(
        "junk:\n" + alias_bomb(indent="  ") + _moving_legacy(
            time_grid("P0DT0H0M0S", "P0DT0H0M1S", "1S", legacy=True))),
        "FileFormatError", "max_yaml_nodes"),
    ResourceCase("self-reference", "asdf", asdf_bytes(
        "junk: &j {self: *j}\n" + _moving_legacy(
            time_grid("P0DT0H0M0S", "P0DT0H0M1S", "1S", legacy=True))),
        "FileFormatError", "contains itself"),
    ResourceCase("decompression-bomb", "npz", forged_npz(3 * 1024**3), "FileFormatError",
                 "max_decompressed_bytes"),
    ResourceCase("arc-of-10^8-points", "scene", (  # 3.2 GB, then a MemoryError
        b"pinframes_scene: 1\nframes:\n  - {name: seam, parent: world, curve: {arc: {centre: "
        b"[0, 0, 0], axis: [0, 0, 1], start: [1, 0, 0], angle: 1, count: 100000000}, "
        b"speed: 1}}\n"), "FileFormatError", "max_samples"),
    *(ResourceCase(f"{kind}-entity-bomb", reader, entity_bomb(kind == "element").encode(),
                   "FileFormatError", "DOCTYPE")
      for kind in ("text", "element") for reader in ("urdf", "attach_urdf")),
]
