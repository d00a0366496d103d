"""``pinframes solve --flat`` as a user runs it on a real cell: ROS-Industrial's Yaskawa
MA2010 and MOTOPOS D500 (tests/data/ma2010_cell) in a scene, the positioner moved to each of
six placements, a whole girth seam given as the scene's arc curve (361 points, 8 mm/s), no
seed; with and without ``--tilt``. The CSV is measured with Pinocchio on the placed URDF
(tests/girth_cell.py), at the samples and between them (joints linear)."""

from __future__ import annotations

import math
import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

from girth_cell import (
    CELL,
    COUNT,
    DURATION,
    FLAT_TOLERANCE,
    HEIGHT,
    PACKAGES,
    PATH_TOLERANCE,
    PLACEMENTS,
    RADIUS,
    SPEED,
    TILT,
    TOLERANCE,
    measure,
    placed_cell,
)

FAST = ["aside_turned"]  # the others in the slow set


def scene(folder: Path, urdf: Path) -> Path:
    """A scene of the placed cell (prefix ``cell/``) and the seam on its workpiece."""
    path = folder / "girth.yaml"
    path.write_text(textwrap.dedent(f"""\
        pinframes_scene: 1
        name: girth
        frames:
          - name: seam
            parent: cell/workpiece
            curve:
              arc: {{centre: [0, 0, {HEIGHT!r}], axis: [0, 0, 1],
                    start: [{RADIUS!r}, 0, {HEIGHT!r}], angle: {2 * math.pi!r},
                    count: {COUNT}}}
              duration: {DURATION!r}
        robots:
          - name: cell
            urdf: {urdf}
            srdf: {CELL / "cell.srdf"}
            package_dirs: [{PACKAGES}]
            parent: world
            prefix: cell/
        """))
    return path


@pytest.mark.parametrize("tilt", [None, TILT], ids=["no_windows", "windows"])
@pytest.mark.parametrize("placement", [
    *FAST, *(pytest.param(name, marks=pytest.mark.slow) for name in PLACEMENTS
             if name not in FAST)])
def test_solve_flat_keeps_a_whole_girth_seam_flat(run_cli, tmp_path, placement, tilt):
    urdf = placed_cell(tmp_path, *PLACEMENTS[placement])
    windows = [] if tilt is None else ["--tilt", *map(str, tilt)]
    result = run_cli("solve", scene(tmp_path, urdf), "--frame", "cell/torch_tip",
                     "--target", "seam", "--free-axis", "z", "--joints", "cell",
                     "--flat", "seam", *windows, "-o", tmp_path / "joints.csv")
    assert result.returncode == 0, result.stderr
    counted = re.search(r"(\d+) samples, (\d+) reached", result.stderr)
    assert counted is not None, result.stderr
    with (tmp_path / "joints.csv").open() as file:
        names = file.readline().strip().split(",")[1:]
    rows = np.loadtxt(tmp_path / "joints.csv", delimiter=",", skiprows=1)
    assert int(counted[1]) == int(counted[2]) == rows.shape[0] >= COUNT
    assert len(names) == 8 and "d500_joint_2" in names  # the URDF's names
    seconds, positions = rows[:, 0], rows[:, 1:]
    measured = measure(urdf, names, seconds, positions)
    assert measured.face.max() <= FLAT_TOLERANCE  # PA all along: every sample flat
    assert measured.off_seam.max() <= 1e-5  # the CSV's digits
    limit = np.zeros(2) if tilt is None else np.asarray(tilt)
    assert np.all(np.abs(measured.tilt) <= limit + 1e-5)
    assert measured.off_circle_between.max() <= PATH_TOLERANCE + TOLERANCE
    assert measured.face_between.max() <= FLAT_TOLERANCE
    assert measured.speed_between.min() > 0.0  # the weld point never runs backwards
    np.testing.assert_allclose(measured.speed_between, SPEED, rtol=0.1)
