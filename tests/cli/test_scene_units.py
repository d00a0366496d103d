"""A scene written in millimetres or degrees is read, with one warning per kind of unit
naming the frame, the field and the likely unit."""

from __future__ import annotations

import textwrap
import warnings
from pathlib import Path

import pytest

from pinframes import UnitWarning, read_scene

MILLIMETRES_AND_DEGREES = """\
    pinframes_scene: 1
    frames:
      - {name: table, parent: world, xyz: [550, 0, 300], rpy: [0, 0, 90]}
      - name: seam
        parent: table
        curve: {points: [[0, 0, 5], [100, 0, 5]], normals: [0, 0, 1], duration: 10}
    tools:
      - {name: tip, parent: table, xyz: [200, 0, 0], rpy: [180, 0, 0]}
    """


@pytest.fixture
def cell_in_millimetres(tmp_path: Path) -> Path:
    path = tmp_path / "cell.yaml"
    path.write_text(textwrap.dedent(MILLIMETRES_AND_DEGREES))
    return path


def test_millimetres_and_degrees_warn_once_each_naming_frame_field_and_unit(
        cell_in_millimetres):
    with pytest.warns(UnitWarning) as caught:
        tree = read_scene(cell_in_millimetres)
    assert len(tree) == 4  # read as written
    messages = [str(warning.message) for warning in caught if warning.category is UnitWarning]
    assert len(messages) == 2
    length, angle = messages
    assert "frame 'table'" in length and "'frames[0].xyz'" in length
    assert "millimetres" in length and "626.498 m" in length  # |(550, 0, 300)|
    assert "frame 'table'" in angle and "'frames[0].rpy'" in angle
    assert "degrees" in angle and "90 rad" in angle


def test_the_command_line_prints_them_as_warning_lines(run_cli, cell_in_millimetres):
    result = run_cli("info", cell_in_millimetres)
    assert result.returncode == 0, result.stderr
    lines = [line for line in result.stderr.splitlines() if line]
    assert len(lines) == 2
    assert all(line.startswith("pinframes: warning: ") for line in lines)


def test_a_curve_in_millimetres_is_named(tmp_path):
    path = tmp_path / "seam.yaml"
    path.write_text(textwrap.dedent("""\
        pinframes_scene: 1
        frames:
          - name: seam
            parent: world
            curve: {points: [[0, 0, 0], [0, 250, 0]], normals: [0, 0, 1], speed: 8}
        """))
    with pytest.warns(UnitWarning, match=r"frame 'seam': field 'frames\[0\]\.curve\.points'"):
        read_scene(path)


def test_a_cell_in_metres_and_radians_reads_without_a_unit_warning():
    bundled = Path(__file__).resolve().parents[2] / "models" / "welding_cell" / "scene.yaml"
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitWarning)
        read_scene(bundled)
