"""The manifest: one JSON record per run in ``OUT/manifest.jsonl``.

Each record: ``run`` (id), ``file``, ``status`` (``ok``, ``error``: the input is bad,
``failed``: something else went wrong), ``samples`` (rows written), ``error`` (the message),
``checksums`` (SHA-256 of every input file, by path), ``options`` (digest of the query
options), ``limits`` (the reader limits the run was read under, by name), ``seconds``
(compute time on the worker), ``finished`` (UTC).

JSON Lines rather than Parquet, because the driver appends each record as soon as its run
finishes: an interrupted batch keeps every finished run's record without rewriting the
file (a Parquet file cannot be appended to). A line that is no record (torn by an
interrupted append, or edited by hand) is skipped with a :class:`ManifestWarning` naming it,
so its run is computed again, and the next record starts on a line of its own. At the end
of a batch the file is rewritten atomically with one line per run, runs of earlier batches
kept. ``pandas.read_json(path, lines=True)`` reads it as a table.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..errors import ManifestWarning, warn_at_caller
from ..formats.atomic import atomic_write

__all__ = ["MANIFEST_NAME", "Manifest"]

MANIFEST_NAME = "manifest.jsonl"


class Manifest:
    """The records of ``out``'s manifest by run id (the last record of a run wins)."""

    def __init__(self, out: Path) -> None:
        self.path = out / MANIFEST_NAME
        self.records: dict[str, dict[str, Any]] = {}
        self.skipped_lines: list[int] = []
        """Numbers (from 1) of the lines that are no record."""
        content = self.path.read_bytes() if self.path.is_file() else b""
        self._ends_line = content.endswith(b"\n") or not content
        for number, line in enumerate(content.splitlines(), start=1):
            if line.strip():
                record = _record(line)
                if record is None:
                    self.skipped_lines.append(number)
                else:
                    self.records[record["run"]] = record
        if self.skipped_lines:
            warn_at_caller(
                f"{self.path}: line{'s' if len(self.skipped_lines) > 1 else ''} "
                f"{', '.join(map(str, self.skipped_lines))} "
                f"{'are' if len(self.skipped_lines) > 1 else 'is'} no run record (torn by "
                "an interrupted batch, or edited): skipped, so those runs are computed "
                "again", ManifestWarning)

    def append(self, record: dict[str, Any]) -> None:
        """Add ``record`` to the file at once (and to :attr:`records`), on a line of its
        own even after a torn last line."""
        self.records[record["run"]] = record
        with open(self.path, "a", encoding="utf-8") as handle:
            if not self._ends_line:
                handle.write("\n")
                self._ends_line = True
            handle.write(json.dumps(record, sort_keys=True) + "\n")

    def rewrite(self, order: Iterable[str]) -> None:
        """Rewrite the file with one line per run: runs in ``order`` first, then others."""
        order = list(dict.fromkeys(order))
        ids = [run for run in order if run in self.records]
        ids += sorted(set(self.records) - set(order))
        with atomic_write(self.path, "w") as handle:
            for run in ids:
                handle.write(json.dumps(self.records[run], sort_keys=True) + "\n")


def _record(line: bytes) -> dict[str, Any] | None:
    """The run record on ``line``: a JSON object with a text ``run``; else None."""
    try:
        record = json.loads(line.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError):
        return None
    if not isinstance(record, dict) or not isinstance(record.get("run"), str):
        return None
    return record
