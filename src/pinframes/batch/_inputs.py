"""The files a run reads, and their checksums: what decides whether a run is recomputed.

A scene reads other files (``layers[].file``, ``robots[].urdf``, ``robots[].trajectory``,
relative to the scene's folder; docs/scene-format.md), and a frames.yaml reads the
``tile_maps.yaml`` beside it; every other format is one file. A file that cannot be found
has the checksum ``"missing"``, so creating it later changes the run's checksums too.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import yaml

__all__ = ["MISSING", "checksums", "input_files"]

MISSING = "missing"
_SCENE_KEY = "pinframes_scene"
_BLOCK_BYTES = 1 << 20


def input_files(path: Path) -> list[Path]:
    """``path`` and the files reading it reads, in a stable order (absolute paths)."""
    path = path.resolve()
    if path.suffix.lower() not in (".yaml", ".yml"):
        return [path]
    try:
        content = yaml.safe_load(path.read_bytes())
    except (OSError, yaml.YAMLError):
        return [path]  # reading the run will fail and say why
    if not isinstance(content, dict):
        return [path]
    if _SCENE_KEY not in content:
        return [path, path.parent / "tile_maps.yaml"]
    files = [path]
    for section, keys in (("layers", ("file",)), ("robots", ("urdf", "trajectory"))):
        entries = content.get(section)
        for entry in entries if isinstance(entries, list) else []:
            for key in keys:
                value = entry.get(key) if isinstance(entry, dict) else None
                if isinstance(value, str):
                    files.extend(input_files(path.parent / value) if key == "file"
                                 else [(path.parent / value).resolve()])
    return list(dict.fromkeys(files))


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
