"""``pinframes view`` and the page that ``pinframes demo`` writes beside its PNG."""

from __future__ import annotations

import base64
import json
import re

import numpy as np
import pytest
import umsgpack

from pinframes.cli import main
from pinframes.cli.demo import bundled_scene


def commands(page_path) -> tuple[dict, list[dict]]:
    text = page_path.read_text()
    data = json.loads(re.search(r'id="pinframes-data">(.*?)</script>', text, re.S).group(1))
    return data, [umsgpack.unpackb(base64.b64decode(c)) for c in data["commands"]]


def track_times(decoded: list[dict], path_end: str) -> np.ndarray:
    (animation,) = [c for c in decoded if c["type"] == "set_animation"]
    (clip,) = [a["clip"] for a in animation["animations"] if a["path"].endswith(path_end)]
    return np.frombuffer(clip["tracks"][0]["times"].data, dtype=np.float32)


def test_view_of_the_bundled_scene_on_a_grid(run_cli, tmp_path):
    out = tmp_path / "cell.html"
    result = run_cli("view", bundled_scene(), "--step", "0.5", "--path", "torch_tcp",
                     "workpiece", "-o", out)
    assert result.returncode == 0, result.stderr
    assert f"wrote {out}" in result.stderr
    data, decoded = commands(out)
    assert data["duration"] == 20.0
    np.testing.assert_allclose(track_times(decoded, "torch_tcp"), np.arange(41) * 0.5)
    assert any(c["type"] == "set_object" and c["path"].endswith("/paths/path:torch_tcp")
               for c in decoded)
    meshes = [c for c in decoded if c["type"] == "set_object" and "/geometry/" in c["path"]]
    assert len(meshes) == 8 + 3 + 4 + 1 + 1  # robot, fixtures, faceplate and jaws, pipe, torch


def test_view_names_an_unknown_frame(run_cli, tmp_path):
    result = run_cli("view", bundled_scene(), "--frames", "nope", "-o", tmp_path / "x.html")
    assert result.returncode == 1
    assert "frame 'nope'" in result.stderr
    assert not (tmp_path / "x.html").exists()


def test_view_finds_packages_in_package_dir(run_cli, tmp_path):
    package = tmp_path / "workspace" / "parts"
    package.mkdir(parents=True)
    (package / "plate.stl").write_bytes(_box_stl())
    urdf = tmp_path / "robot" / "robot.urdf"
    urdf.parent.mkdir()
    urdf.write_text('<robot name="r"><link name="base"><visual><geometry>'
                    '<mesh filename="package://parts/plate.stl"/></geometry></visual></link>'
                    "</robot>")
    missing = run_cli("view", urdf, "-o", tmp_path / "a.html")
    assert missing.returncode == 0
    assert "package://parts/plate.stl" in missing.stderr and "--package-dir" in missing.stderr
    found = run_cli("view", urdf, "-o", tmp_path / "b.html", "--package-dir",
                    tmp_path / "workspace")
    assert found.returncode == 0 and "GeometryWarning" not in found.stderr
    _, decoded = commands(tmp_path / "b.html")
    meshes = [c["path"] for c in decoded if c["type"] == "set_object" and "/geometry/" in c["path"]]
    assert meshes == ["/pinframes/frames/frame:base/geometry/0"]


@pytest.mark.slow  # seconds of CPU (subprocesses): CI's slow set
def test_demo_without_meshcat_writes_the_rest_and_says_what_the_extra_adds(
        tmp_path, monkeypatch, capsys):
    import pinframes.view._page as page_module

    monkeypatch.setattr(page_module.importlib.util, "find_spec", lambda name: None)
    assert main(["demo", "--out", str(tmp_path)]) == 0
    messages = capsys.readouterr().err
    assert 'no 3-D page: the 3-D page needs meshcat: pip install "pinframes[view]"' in messages
    # everything but the page: the plot, the poses, the ROS recording (ros extra installed)
    # and the cell's planned program
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cell_run.mcap", "program_run.csv",
                                                          "torch_path.png", "torch_poses.csv"]


def _box_stl() -> bytes:
    """A binary STL of one triangle (enough for a mesh), written by hand."""
    header = b"pinframes test".ljust(80, b" ")
    triangle = np.array([0, 0, 1, 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0], dtype="<f4").tobytes()
    return header + (1).to_bytes(4, "little") + triangle + b"\0\0"
