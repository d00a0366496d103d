"""How fast ``pinframes.read`` reads files, beside a plain parse of the same bytes.

Cases, each read through ``pinframes.read`` (the format told from the file, as the CLI does):

- the bundled welding cell scene (``models/welding_cell/scene.yaml``: inline keyframes, five
  URDFs, a 2,001-row joint trajectory); reference: PyYAML's ``SafeLoader`` on the scene,
  ``ElementTree`` on each URDF and ``numpy.loadtxt`` on the trajectory;
- a scene of 5,000 inline keyframes (0.35 MB of YAML, 60,000 nodes); reference: ``SafeLoader``
  on it;
- an ASDF file of 3 frames moving with 100,000 keyframes each (weldx schema 0.1.0, 19 MB);
  reference: ``asdf.open`` and every array read;
- hostile YAML: a 2 MB scene of 300,000 nodes with the default ``max_yaml_nodes``
  (200,000): the time until pinframes refuses it, beside ``SafeLoader`` composing a 0.5 MB
  document of the same lines.

The references share no code with pinframes. Both thread settings, each in a child process
(``_machine.py``). Run from the repository root: ``python benchmarks/bench_read.py
[--quick]``.
"""

from __future__ import annotations

import json
import tempfile
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import yaml

import pinframes
from _machine import describe_machine, interleaved, print_table, quick_or_child, run_in_settings
from pinframes import FrameTree, Pose

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "models" / "welding_cell" / "scene.yaml"
REFERENCE = "plain parse"


def _plain_scene() -> None:
    """The bundled scene's files parsed without checks (paths as the scene names them)."""
    with open(SCENE, encoding="utf-8") as handle:
        content = yaml.load(handle, Loader=yaml.SafeLoader)
    for robot in content.get("robots", []):
        ET.parse(SCENE.parent / robot["urdf"])
        if "trajectory" in robot:
            np.loadtxt(SCENE.parent / robot["trajectory"], delimiter=",", skiprows=1,
                       comments="#")


def _keyframe_scene(folder: Path, count: int) -> Path:
    rows = "\n".join(f"      - {{time: {index * 0.01:.2f}, xyz: [{index * 1e-4:.4f}, 0.0, 0.1], "
                     f"quaternion: [0.0, 0.0, 0.0, 1.0]}}" for index in range(count))
    path = folder / "keyframes.yaml"
    path.write_text("pinframes_scene: 1\nframes:\n  - name: moving\n    parent: world\n"
                    f"    keyframes:\n{rows}\n", encoding="utf-8")
    return path


def _plain_yaml(path: Path) -> None:
    with open(path, encoding="utf-8") as handle:
        yaml.load(handle, Loader=yaml.SafeLoader)


def _asdf_file(folder: Path, frames: int, keyframes: int) -> Path:
    rng = np.random.default_rng(5)
    tree = FrameTree("world")
    parent = "world"
    times = np.linspace(0.0, 100.0, keyframes)
    for index in range(frames):
        quaternions = rng.normal(size=(keyframes, 4))
        quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
        tree.add(f"f{index}", parent, Pose(rng.normal(size=(keyframes, 3)), quaternions,
                                           times=times))
        parent = f"f{index}"
    path = folder / "large.asdf"
    pinframes.write(tree, path, schema="0.1.0")
    return path


def _plain_asdf(path: Path) -> None:
    import asdf

    def arrays(node: object) -> None:
        if isinstance(node, dict):
            for value in node.values():
                arrays(value)
        elif isinstance(node, list):
            for value in node:
                arrays(value)
        elif hasattr(node, "shape"):
            np.asarray(node).sum()

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with asdf.open(path, lazy_tree=False, memmap=False) as opened:
            arrays(opened.tree)


def _hostile_scene(folder: Path, megabytes: float) -> Path:
    """A scene of short lists of numbers: about 150,000 nodes per megabyte."""
    line = "  - [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]\n"
    path = folder / f"hostile_{megabytes}mb.yaml"
    count = int(megabytes * (1 << 20)) // len(line)
    path.write_text("pinframes_scene: 1\nextra:\n" + line * count, encoding="utf-8")
    return path


def _refused(path: Path) -> None:
    try:
        pinframes.read(path)
    except pinframes.FileFormatError as exc:
        assert "max_yaml_nodes" in str(exc), exc
        return
    raise AssertionError("the hostile scene was read")


def _plain_compose(path: Path) -> None:
    yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)


def child(quick: bool) -> None:
    repeats = 3 if quick else 9
    rows = []
    with tempfile.TemporaryDirectory() as folder_name:
        folder = Path(folder_name)
        rows += interleaved("bundled welding cell scene", {
            REFERENCE: _plain_scene, "pinframes.read": lambda: pinframes.read(SCENE)},
            repeats, reference=REFERENCE)
        keyframes = _keyframe_scene(folder, 5_000)
        rows += interleaved("scene of 5,000 keyframes", {
            REFERENCE: lambda: _plain_yaml(keyframes),
            "pinframes.read": lambda: pinframes.read(keyframes)}, max(3, repeats // 3),
            reference=REFERENCE)
        asdf_path = _asdf_file(folder, 3, 100_000)
        rows += interleaved("ASDF, 3 frames x 100,000 keyframes", {
            REFERENCE: lambda: _plain_asdf(asdf_path),
            "pinframes.read": lambda: pinframes.read(asdf_path)}, max(3, repeats // 3),
            reference=REFERENCE)
        hostile = _hostile_scene(folder, 2)
        sample = _hostile_scene(folder, 0.5)
        rows += interleaved("2 MB YAML, 300,000 nodes: refused", {
            REFERENCE: lambda: _plain_compose(sample),
            "pinframes.read": lambda: _refused(hostile)}, 3, reference=REFERENCE)
    for entry in rows:
        if entry["case"].startswith("2 MB") and entry["method"] == REFERENCE:
            entry["note"] = "(composes 0.5 MB)"
    print(json.dumps(rows))


def main() -> None:
    quick = quick_or_child(__doc__.splitlines()[0], child)
    if quick is None:
        return
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference=REFERENCE)


if __name__ == "__main__":
    main()
