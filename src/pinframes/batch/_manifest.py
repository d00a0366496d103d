"""The manifest: one JSON record per run in ``OUT/manifest.jsonl``.

Each record: ``run`` (id), ``file``, ``status`` (``ok``, ``error``: the input is bad,
``failed``: something else went wrong), ``samples`` (rows written), ``error`` (the message),
``checksums`` (SHA-256 of every input file, by path), ``options`` (digest of the query
options), ``limits`` (the reader limits the run was read under, by name), ``seconds``
(compute time on the worker), ``finished`` (UTC).

JSON Lines rather than Parquet, because the driver appends each record as soon as its run
finishes: an interrupted batch keeps every finished run's record without rewriting the
file (a Parquet file cannot be appended to), and a torn last line is ignored. At the end of
a batch the file is rewritten atomically with one line per run, runs of earlier batches
kept. ``pandas.read_json(path, lines=True)`` reads it as a table.
"""

from __future__ import annotations

import json
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ..formats.atomic import atomic_write

__all__ = ["MANIFEST_NAME", "Manifest"]

MANIFEST_NAME = "manifest.jsonl"


class Manifest:
    """The records of ``out``'s manifest by run id (the last record of a run wins)."""

    def __init__(self, out: Path) -> None:
        self.path = out / MANIFEST_NAME
        self.records: dict[str, dict[str, Any]] = {}
        if self.path.is_file():
            lines = self.path.read_text(encoding="utf-8").splitlines()
            for number, line in enumerate(lines, start=1):
                try:
                    record = json.loads(line)
                except json.JSONDecodeError:
                    if number == len(lines):
                        break  # the driver stopped while appending: that run is redone
                    raise
                self.records[record["run"]] = record

    def append(self, record: dict[str, Any]) -> None:
        """Add ``record`` to the file at once (and to :attr:`records`)."""
        self.records[record["run"]] = record
        with open(self.path, "a", encoding="utf-8") as handle:
            handle.write(json.dumps(record, sort_keys=True) + "\n")

    def rewrite(self, order: Iterable[str]) -> None:
        """Rewrite the file with one line per run: runs in ``order`` first, then others."""
        order = list(dict.fromkeys(order))
        ids = [run for run in order if run in self.records]
        ids += sorted(set(self.records) - set(order))
        with atomic_write(self.path, "w") as handle:
            for run in ids:
                handle.write(json.dumps(self.records[run], sort_keys=True) + "\n")
