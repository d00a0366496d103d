"""The bundled cell's geometry: generated files up to date, and the pipe where the seam is."""

from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np

from pinframes import read_scene
from pinframes.view import GeometryWarning, load_geometry

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell"
SEAM_RADIUS = 0.10955  # models/README.md: the seam is a half circle of this radius


def test_generated_files_are_what_make_geometry_writes(tmp_path):
    subprocess.run([sys.executable, str(CELL / "make_geometry.py"), "--out", str(tmp_path)],
                   check=True, capture_output=True)
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*") if p.is_file())
    assert written == sorted(p.relative_to(CELL / "geometry")
                             for p in (CELL / "geometry").rglob("*") if p.is_file())
    for name in written:
        assert (tmp_path / name).read_bytes() == (CELL / "geometry" / name).read_bytes(), name


def test_every_link_of_the_cell_has_geometry_and_the_pipe_carries_the_seam():
    tree = read_scene(CELL / "scene.yaml")
    with warnings.catch_warnings():
        warnings.simplefilter("error", GeometryWarning)
        pieces = load_geometry(tree)
    frames = {piece.frame for piece in pieces}
    assert frames == {"robot/base_link", *(f"robot/link_{i}" for i in range(1, 7)),
                      "fixtures", "faceplate", "pipe", "torch"}
    (pipe,) = [piece for piece in pieces if piece.frame == "pipe"]
    radial = np.hypot(pipe.vertices[:, 0], pipe.vertices[:, 1])
    np.testing.assert_allclose(radial.max(), SEAM_RADIUS, atol=1e-6)
    # the torch tip at every sample lies on the pipe's outer surface, in the seam plane
    tip = tree.pose("torch_tcp", relative_to="pipe").translation
    np.testing.assert_allclose(np.hypot(tip[:, 0], tip[:, 1]), SEAM_RADIUS, atol=1e-6)
    np.testing.assert_allclose(tip[:, 2], 0.0, atol=1e-6)
