"""The files a run reads, their checksums (what decides whether a run is recomputed), and
reading its tree.

A scene reads other files (``layers[].file``, ``robots[].urdf``, ``robots[].trajectory``,
relative to the scene's folder; docs/scene-format.md), and a frames.yaml reads the
``tile_maps.yaml`` beside it; a ROS 2 bag folder is its ``metadata.yaml`` and the storage
files it names; every other format is one file. A file that cannot be found has the
checksum ``"missing"``, so creating it later changes the run's checksums too; one that is
no regular file (``/dev/zero``, a FIFO) is never opened for reading and has the checksum
``"not a regular file"``: the reader then refuses it, naming it.
"""

from __future__ import annotations

import hashlib
import os
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml

from .. import FrameTree, Limits, read
from ..errors import PinframesError, ReadError
from ..formats.limits import current_limits
from ..formats.reading import read_bytes
from ..formats.rosbag import bag_files

__all__ = ["IRREGULAR", "MISSING", "RunInputs", "checksums", "read_run", "run_inputs"]

MISSING = "missing"
IRREGULAR = "not a regular file"
_SCENE_KEY = "pinframes_scene"
_BLOCK_BYTES = 1 << 20
# libyaml when PyYAML has it: a scene of a recorded run can hold thousands of keyframes
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_OPENING = (yaml.SequenceStartEvent, yaml.MappingStartEvent)
_CLOSING = (yaml.SequenceEndEvent, yaml.MappingEndEvent)


@dataclass(frozen=True)
class RunInputs:
    """The files a run reads (absolute paths, the run's own file first), and whether the
    run's file is a scene (so it is read as one without telling its format again)."""

    files: list[Path]
    is_scene: bool


def run_inputs(path: Path) -> RunInputs:
    """The inputs of the run whose file is ``path``, each once (layers that name each other
    in a circle are left for the reader to refuse)."""
    root = path.resolve()
    if root.is_dir():
        return RunInputs(_folder_files(root), False)
    is_scene, pending = _named_files(root)
    files = {root: None}
    pending.reverse()  # (a file, whether to look into it for the files it names), last first
    while pending:
        file, look_inside = pending.pop()
        if file in files:
            continue
        files[file] = None
        if look_inside:
            pending.extend(reversed(_named_files(file)[1]))
    return RunInputs(list(files), is_scene)


def read_run(path: Path, inputs: RunInputs, limits: Limits) -> FrameTree:
    """The tree of the run whose file is ``path`` and whose inputs are ``inputs``, read
    under ``limits``: the one place that knows how a run is read."""
    return read(path, format="scene" if inputs.is_scene else None, limits=limits)


def _folder_files(folder: Path) -> list[Path]:
    """The files of a bag folder (the folder itself if its metadata cannot be read: reading
    the run will fail and say why)."""
    try:
        return bag_files(folder)
    except PinframesError:
        return [folder]


def _named_files(file: Path) -> tuple[bool, list[tuple[Path, bool]]]:
    """Whether ``file`` is a scene, and the files it names (with whether they are layers,
    which may name more)."""
    if file.suffix.lower() not in (".yaml", ".yml"):
        return False, []
    content = _load(file)
    if not isinstance(content, dict):
        return False, []  # reading the run will fail and say why
    if _SCENE_KEY not in content:
        return False, [(file.parent / "tile_maps.yaml", False)]
    named = []
    for section, keys in (("layers", ("file",)), ("robots", ("urdf", "trajectory"))):
        entries = content.get(section)
        for entry in entries if isinstance(entries, list) else []:
            for key in keys:
                value = entry.get(key) if isinstance(entry, dict) else None
                if isinstance(value, str):
                    named.append(((file.parent / value).resolve(), key == "file"))
    return True, named


def _load(file: Path) -> Any:
    """The YAML document in ``file``, or None if it cannot be read, is not YAML, or nests
    deeper than the limit ``max_depth``: libyaml's composer recurses in C, and a few hundred
    kilobytes of ``[`` would crash the worker. The depth is measured on the parser's events
    first, which come one at a time; aliases cost nothing here (they share their node)."""
    try:
        raw = read_bytes(file)
        depth, deepest = 0, current_limits().max_depth
        for event in yaml.parse(raw, Loader=_LOADER):
            if isinstance(event, _OPENING):
                depth += 1
                if depth > deepest:
                    return None
            elif isinstance(event, _CLOSING):
                depth -= 1
        return yaml.load(raw, Loader=_LOADER)  # a safe loader
    except (ReadError, yaml.YAMLError):
        return None


def checksums(files: list[Path]) -> dict[str, str]:
    """SHA-256 (hex) of each file's bytes, keyed by its path; :data:`MISSING` if unreadable,
    :data:`IRREGULAR` for a device, FIFO or socket (never read: ``/dev/zero`` never ends)."""
    return {os.fspath(file): _sha256(file) for file in files}


def _sha256(file: Path) -> str:
    digest = hashlib.sha256()
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer before fstat tells what it is
        descriptor = os.open(file, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return MISSING
    with open(descriptor, "rb") as handle:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            return IRREGULAR
        try:
            while block := handle.read(_BLOCK_BYTES):
                digest.update(block)
        except OSError:
            return MISSING
    return digest.hexdigest()
