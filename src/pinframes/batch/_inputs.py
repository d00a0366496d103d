"""The files a run reads, their checksums (what decides whether a run is recomputed), and
reading its tree.

Which files a run reads is what its file's format says
(:func:`pinframes.formats.files_read`: a scene its layers, robots and trajectories,
docs/scene-format.md; a frames.yaml the ``tile_maps.yaml`` beside it; a ROS 2 bag folder its
``metadata.yaml`` and the storage files it names; other formats one file). The run's file
is read once for that and for the run's tree: :class:`RunInputs` keeps it as an
:class:`~pinframes.formats.InputFile`. A file that cannot be found has the checksum
``"missing"``, so creating it later changes the run's checksums too; one that is no regular
file (``/dev/zero``, a FIFO) is never opened for reading and has the checksum
``"not a regular file"``: the reader then refuses it, naming it.
"""

from __future__ import annotations

import hashlib
import os
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import FrameTree, Limits, read
from ..formats import InputFile, detect_format, files_read

__all__ = ["IRREGULAR", "MISSING", "RunInputs", "checksums", "read_run", "run_inputs"]

MISSING = "missing"
IRREGULAR = "not a regular file"
_BLOCK_BYTES = 1 << 20
_ROBOT_FORMATS = ("urdf", "scene")
"""Formats whose reader expands xacro files when asked (``xacro=``)."""


@dataclass(frozen=True)
class RunInputs:
    """The files a run reads (absolute paths, the run's own file first), and the run's file
    as it was read to find them (:func:`read_run` reads the tree from it, not again)."""

    files: list[Path]
    source: InputFile


def run_inputs(path: Path) -> RunInputs:
    """The inputs of the run whose file (or bag folder) is ``path``, each once."""
    source = InputFile(path)
    return RunInputs(files_read(source), source)


def read_run(inputs: RunInputs, limits: Limits, xacro: bool = False) -> FrameTree:
    """The tree of the run whose inputs are ``inputs``, read under ``limits``: the one place
    that knows how a run is read. Without ``xacro`` no xacro file is expanded (that runs the
    file's code, on every worker): a run's robot file or scene robot with xacro content is
    refused, naming it; with it, the xacro content of both is expanded."""
    expansion: dict[str, Any] = ({"xacro": xacro} if detect_format(inputs.source)
                                 in _ROBOT_FORMATS else {})
    tree: FrameTree = read(inputs.source, limits=limits, **expansion)
    return tree


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
