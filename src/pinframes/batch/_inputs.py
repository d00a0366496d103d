"""The files a run reads, and their checksums: what decides whether a run is recomputed.

A scene reads other files (``layers[].file``, ``robots[].urdf``, ``robots[].trajectory``,
relative to the scene's folder; docs/scene-format.md), and a frames.yaml reads the
``tile_maps.yaml`` beside it; every other format is one file. A file that cannot be found
has the checksum ``"missing"``, so creating it later changes the run's checksums too.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from pathlib import Path

import yaml

__all__ = ["MISSING", "RunInputs", "checksums", "run_inputs"]

MISSING = "missing"
_SCENE_KEY = "pinframes_scene"
_BLOCK_BYTES = 1 << 20
# libyaml when PyYAML has it: a scene of a recorded run can hold thousands of keyframes
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


@dataclass(frozen=True)
class RunInputs:
    """The files a run reads (absolute paths, the run's own file first), and whether the
    run's file is a scene (so it is read as one without telling its format again)."""

    files: list[Path]
    is_scene: bool


def run_inputs(path: Path) -> RunInputs:
    """The inputs of the run whose file is ``path``."""
    path = path.resolve()
    if path.suffix.lower() not in (".yaml", ".yml"):
        return RunInputs([path], is_scene=False)
    try:
        content = yaml.load(path.read_bytes(), Loader=_LOADER)  # a safe loader
    except (OSError, yaml.YAMLError):
        return RunInputs([path], is_scene=False)  # reading the run will fail and say why
    if not isinstance(content, dict):
        return RunInputs([path], is_scene=False)
    if _SCENE_KEY not in content:
        return RunInputs([path, path.parent / "tile_maps.yaml"], is_scene=False)
    files = [path]
    for section, keys in (("layers", ("file",)), ("robots", ("urdf", "trajectory"))):
        entries = content.get(section)
        for entry in entries if isinstance(entries, list) else []:
            for key in keys:
                value = entry.get(key) if isinstance(entry, dict) else None
                if isinstance(value, str):
                    files.extend(run_inputs(path.parent / value).files if key == "file"
                                 else [(path.parent / value).resolve()])
    return RunInputs(list(dict.fromkeys(files)), is_scene=True)


def checksums(files: list[Path]) -> dict[str, str]:
    """SHA-256 (hex) of each file's bytes, keyed by its path; :data:`MISSING` if unreadable."""
    return {os.fspath(file): _sha256(file) for file in files}


def _sha256(file: Path) -> str:
    digest = hashlib.sha256()
    try:
        with open(file, "rb") as handle:
            while block := handle.read(_BLOCK_BYTES):
                digest.update(block)
    except OSError:
        return MISSING
    return digest.hexdigest()
