"""Published meshes that other readers take: pinframes reads them as assimp (coal's loader,
Pinocchio's reader) does."""

from __future__ import annotations

from pathlib import Path

import coal
import numpy as np

from pinframes.kinematics.collision.mesh_reader import read_mesh

DATA = Path(__file__).resolve().parents[1] / "data"


def test_a_collada_file_with_a_blank_line_before_its_xml_declaration():
    path = DATA / "doosan" / "H2017_2_2.dae"
    assert not path.read_bytes().startswith(b"<")  # as Doosan publishes it
    vertices, triangles = read_mesh(path).merged()
    loaded = coal.MeshLoader().load(str(path), np.ones(3))
    assert triangles.shape[0] == loaded.num_tris
    expected = np.array(loaded.vertices(), dtype=float).reshape(-1, 3)
    np.testing.assert_allclose(vertices.min(axis=0), expected.min(axis=0), atol=1e-9)
    np.testing.assert_allclose(vertices.max(axis=0), expected.max(axis=0), atol=1e-9)
