"""Mesh files and geometry from elsewhere: compressed containers are not opened, mesh files
are bounded by max_decompressed_bytes, points without triangles and numbers that cannot be
drawn are left out with a GeometryWarning, and the page's data stays strict JSON."""

from __future__ import annotations

import bz2
import io
import json
import re
import struct
import tarfile
import warnings
import zipfile
from pathlib import Path

import numpy as np
import pytest

from pinframes import FrameTree, Limits, Pose, read_urdf
from pinframes.errors import GeometryError, InvalidTimeError
from pinframes.view import MAX_PAGE_POSES, GeometryWarning, load_geometry, view_html


def stl_tetrahedron() -> bytes:
    """A binary STL of one tetrahedron (four triangles), written by hand."""
    corners = np.array([[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]], np.float32)
    triangles = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    body = b"".join(struct.pack("<3f", 0, 0, 0) + corners[list(t)].tobytes() + b"\0\0"
                    for t in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles)) + body


def urdf_with_meshes(folder: Path, meshes: dict[str, bytes], shapes: str = "") -> Path:
    """A URDF whose link ``base`` shows every file of ``meshes`` (written beside it) and a
    small box, plus the ``shapes`` (URDF geometry elements) on link ``extra``."""
    visuals = "".join(f'<visual><geometry><mesh filename="{name}"/></geometry></visual>'
                      for name in meshes)
    for name, content in meshes.items():
        (folder / name).write_bytes(content)
    extra = "".join(f"<visual><geometry>{shape}</geometry></visual>" for shape in
                    shapes.split("|") if shape)
    path = folder / "robot.urdf"
    path.write_text(
        f'<robot name="r"><link name="base">{visuals}<visual><geometry>'
        '<box size="0.1 0.1 0.1"/></geometry></visual></link>'
        f'<link name="extra">{extra}</link><joint name="j" type="fixed"><parent link="base"/>'
        '<child link="extra"/></joint></robot>', encoding="utf-8")
    return path


def geometry_and_warnings(urdf: Path, **options):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pieces = load_geometry(read_urdf(urdf), **options)
    return pieces, [str(w.message) for w in caught if w.category is GeometryWarning]


def collada_tetrahedron() -> bytes:
    """The tetrahedron as COLLADA, written by trimesh (what a .dae inside a zip holds)."""
    import trimesh

    mesh = trimesh.load(io.BytesIO(stl_tetrahedron()), file_type="stl", force="mesh")
    return trimesh.exchange.dae.export_collada(mesh)


def compressed(kind: str, inside: bytes, name_inside: str = "part.stl") -> bytes:
    if kind == "bz2":
        return bz2.compress(inside)
    buffer = io.BytesIO()
    if kind == "zip":
        with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.writestr(name_inside, inside)
    else:
        with tarfile.open(fileobj=buffer, mode="w:gz") as archive:
            info = tarfile.TarInfo("part.stl")
            info.size = len(inside)
            archive.addfile(info, io.BytesIO(inside))
    return buffer.getvalue()


@pytest.mark.parametrize(("name", "kind"), [("part.stl.bz2", "bz2"), ("part.zip", "zip"),
                                            ("part.tar.gz", "tar.gz"), ("part.dae", "zip")])
def test_compressed_meshes_are_not_opened(tmp_path, name, kind):
    """trimesh inflates the first three by their names, pycollada a .dae zip by its content;
    each holds a real mesh, which would be drawn if the container were opened."""
    inside = (compressed(kind, collada_tetrahedron(), "part.dae") if name.endswith(".dae")
              else compressed(kind, stl_tetrahedron()))
    urdf = urdf_with_meshes(tmp_path, {name: inside})
    pieces, said = geometry_and_warnings(urdf)
    assert [piece.source for piece in pieces] == ["box"]
    assert len(said) == 1 and name in said[0] and "compressed" in said[0]


def test_a_mesh_file_over_max_decompressed_bytes_is_not_opened(tmp_path):
    urdf = urdf_with_meshes(tmp_path, {"part.stl": stl_tetrahedron()})
    size = len(stl_tetrahedron())
    pieces, said = geometry_and_warnings(urdf, limits=Limits(max_decompressed_bytes=size - 1))
    assert [piece.source for piece in pieces] == ["box"]
    assert len(said) == 1 and f"max_decompressed_bytes={size - 1:,}" in said[0]
    pieces, said = geometry_and_warnings(urdf, limits=Limits(max_decompressed_bytes=size))
    assert sorted(piece.source for piece in pieces) == ["box", "part.stl"] and said == []


def test_a_point_cloud_mesh_is_a_warning(tmp_path):
    urdf = urdf_with_meshes(tmp_path, {"cloud.obj": b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"})
    pieces, said = geometry_and_warnings(urdf)
    assert [piece.source for piece in pieces] == ["box"]
    assert len(said) == 1 and "cloud.obj" in said[0]  # assimp's reason: no meshes remaining
    with pytest.warns(GeometryWarning, match="cloud.obj"):
        page = view_html(read_urdf(urdf))  # the page of the robot is made as well
    assert "pinframes-data" in page


def page_data(page: str) -> dict:
    """The page's embedded data, parsed as strict JSON (NaN and Infinity refused)."""
    text = re.search(r'<script type="application/json" id="pinframes-data">(.*?)</script>',
                     page, re.S).group(1)

    def refuse(constant: str) -> None:
        raise AssertionError(f"{constant} in the page's JSON")

    return json.loads(text, parse_constant=refuse)


def test_geometry_and_frames_that_cannot_be_drawn_are_left_out(tmp_path):
    urdf = urdf_with_meshes(tmp_path, {}, '<cylinder radius="nan" length="0.2"/>|'
                                          '<box size="1e308 1e308 1e308"/>|<sphere radius="0.05"/>')
    tree = FrameTree("world")
    tree.attach_urdf(urdf, "world")
    tree.add("far", "world", Pose([1e200, 0.0, 0.0]))
    tree.add("near", "world", Pose([0.5, 0.0, 0.0]))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        data = page_data(view_html(tree))
    said = [str(w.message) for w in caught if w.category is GeometryWarning]
    assert any("'far' is not drawn" in message for message in said)
    assert sum("link 'extra'" in message for message in said) == 2  # cylinder and box
    assert [label["text"] for label in data["labels"]] == ["world", "base", "extra", "near"]
    assert np.all(np.isfinite(data["centre"])) and 0.1 <= data["radius"] < 10


def test_the_page_bounds_times_times_frames_before_computing_poses():
    tree = FrameTree("world")
    for index in range(60):
        tree.add(f"f{index}", "world", Pose([[0.01 * index, 0.0, 0.0],
                                             [0.01 * index, 1.0, 0.0]], times=[0.0, 1.0]))
    times = np.linspace(0.0, 1.0, 20_000)  # within the times a page animates
    assert len(times) * 61 > MAX_PAGE_POSES
    with pytest.raises(InvalidTimeError, match="61 frames") as error:
        view_html(tree, times=times)
    assert error.value.field == "times"
    page_data(view_html(tree, times=times, frames=["f0", "f1"]))  # fewer frames fit


def test_the_clearance_query_does_not_open_compressed_meshes_either(tmp_path):
    urdf = urdf_with_meshes(tmp_path, {"part.stl.bz2": compressed("bz2", stl_tetrahedron())})
    tree = FrameTree("world")
    tree.attach_urdf(urdf, "world")
    with pytest.raises(GeometryError, match="compressed") as error:
        tree.clearance("base", "extra", geometry="visual")
    assert error.value.frame == "base" and error.value.file.endswith("part.stl.bz2")
