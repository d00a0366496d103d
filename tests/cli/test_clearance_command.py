"""``pinframes clearance``: a cube sliding into a block, against the distances by hand."""

from __future__ import annotations

import csv
import io
import json
import textwrap

import numpy as np
import pytest

SCENE = """\
    pinframes_scene: 1
    name: slide
    frames:
      - name: slider
        parent: world
        keyframes:
          - {time: 0, xyz: [0, 0, 0]}
          - {time: 12, xyz: [1.2, 0, 0]}
      - {name: wall, parent: world, xyz: [1.0, 0, 0]}
    robots:
      - {name: cube, urdf: cube.urdf, parent: slider}
      - {name: block, urdf: block.urdf, parent: wall}
    """


def one_box(name: str, size: float) -> str:
    return (f'<robot name="{name}"><link name="{name}"><collision><geometry>'
            f'<box size="{size} {size} {size}"/></geometry></collision></link></robot>')


@pytest.fixture
def slide(tmp_path):
    """A 0.2 m cube sliding along x at 0.1 m/s into a 0.4 m block centred at x = 1 m."""
    (tmp_path / "cube.urdf").write_text(one_box("cube", 0.2))
    (tmp_path / "block.urdf").write_text(one_box("block", 0.4))
    path = tmp_path / "slide.yaml"
    path.write_text(textwrap.dedent(SCENE))
    return path


def expected_distance(seconds):
    """The gap between the faces, then minus the shortest way out of the overlap."""
    x = 0.1 * np.asarray(seconds)
    gap = 1.0 - x - 0.3
    depth = np.minimum.reduce([(x + 0.1) - 0.8, 1.2 - (x - 0.1), np.full_like(x, 0.3)])
    return np.where(gap >= 0, gap, -depth)


def test_summary_on_stderr_and_the_table_on_stdout(run_cli, slide):
    result = run_cli("clearance", slide, "cube", "block", "--step", "0.5")
    assert result.returncode == 0, result.stderr
    assert result.stderr.strip() == (
        "pinframes: smallest clearance -300.0 mm between cube and block at 10.000 s; first "
        "contact at 7.000 s (25 samples, 1 x 1 frames)")
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    assert list(rows[0]) == ["time_s", "distance_m", "frame_a", "frame_b", "point_a_x_m",
                             "point_a_y_m", "point_a_z_m", "point_b_x_m", "point_b_y_m",
                             "point_b_z_m"]
    seconds = np.array([float(row["time_s"]) for row in rows])
    np.testing.assert_allclose(seconds, np.arange(0.0, 12.5, 0.5))
    np.testing.assert_allclose([float(row["distance_m"]) for row in rows],
                               expected_distance(seconds), atol=1e-9)
    assert {(row["frame_a"], row["frame_b"]) for row in rows} == {("cube", "block")}
    apart = [row for row in rows if float(row["time_s"]) < 7]
    np.testing.assert_allclose([float(row["point_b_x_m"]) for row in apart], 0.8, atol=1e-9)


def test_json_file_lists_sides_and_units(run_cli, slide, tmp_path):
    out = tmp_path / "table.json"
    # "s*" matches slider, which has no geometry: a pattern leaves it out
    result = run_cli("clearance", slide, "cube,s*", "b*", "--times", "0", "5s", "-o", out)
    assert result.returncode == 0, result.stderr
    assert result.stdout == ""
    document = json.loads(out.read_text())
    assert document["frames_a"] == ["cube"]
    assert document["frames_b"] == ["block"] and document["geometry"] == "collision"
    np.testing.assert_allclose([s["distance_m"] for s in document["samples"]],
                               expected_distance([0.0, 5.0]), atol=1e-9)


def test_a_frame_without_geometry_is_an_error_naming_it(run_cli, slide):
    result = run_cli("clearance", slide, "wall", "block")
    assert result.returncode == 1
    assert result.stderr.startswith("pinframes: error: frame 'wall': field 'geometry': ")
    assert run_cli("clearance", slide, "cube").returncode == 2  # B missing: usage error
