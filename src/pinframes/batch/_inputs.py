"""The files a run reads, and their checksums: what decides whether a run is recomputed.

Which files a run reads is what its file's format says
(:func:`pinframes.formats.files_read`: a scene its layers, robots and trajectories,
docs/scene-format.md; a frames.yaml the ``tile_maps.yaml`` beside it; other formats one
file). The run's file is read once for that and for the run's tree: :class:`RunInputs`
keeps it as an :class:`~pinframes.formats.InputFile`. A file that cannot be found has the
checksum ``"missing"``, so creating it later changes the run's checksums too.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from pathlib import Path

from ..formats import InputFile, files_read

__all__ = ["MISSING", "RunInputs", "checksums", "run_inputs"]

MISSING = "missing"
_BLOCK_BYTES = 1 << 20


@dataclass(frozen=True)
class RunInputs:
    """The files a run reads (absolute paths, the run's own file first), and the run's file
    as it was read to find them (hand it to ``pinframes.read``: it is not read again)."""

    files: list[Path]
    source: InputFile


def run_inputs(path: Path) -> RunInputs:
    """The inputs of the run whose file is ``path``, each once."""
    source = InputFile(path)
    return RunInputs(files_read(source), source)


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
