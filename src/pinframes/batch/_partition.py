"""The output folder: one Parquet file per run, written whole or not at all.

Layout of ``OUT``::

    OUT/poses/<run id>.parquet   the dataset (one file per run, one row group per chunk)
    OUT/manifest.jsonl           one record per run (see _manifest.py)
    OUT/.staging/                files being written; renamed into poses/ when complete

A run's file is written in ``.staging`` and renamed onto its place in ``poses/`` (the same
file system, so the rename is atomic and replaces an older version in one step): readers
of ``poses/`` never see a half-written file, and a worker killed mid-run leaves only a file
in ``.staging``, which the next batch removes. Run ids are percent-encoded in file names;
an id whose encoded name would pass :data:`MAX_NAME_BYTES` (28 CJK characters take 252
bytes) is cut and ends in ``+`` and a hash of the whole id (``+`` is always encoded, so no
short id gives such a name). The ``run`` column always holds the whole id.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import uuid
from pathlib import Path
from types import TracebackType
from urllib.parse import quote

import pyarrow as pa  # type: ignore[import-untyped]
import pyarrow.parquet as pq  # type: ignore[import-untyped]

__all__ = ["POSES_FOLDER", "PartitionWriter", "clear_staging", "partition_path"]

POSES_FOLDER = "poses"
_STAGING_FOLDER = ".staging"
_SUFFIX = ".parquet"
MAX_NAME_BYTES = 200
"""The longest partition file name written; file systems allow 255 bytes, and tools that
add a suffix of their own to a name keep working."""
_HASH_CHARACTERS = 16


def partition_path(out: Path, run_id: str) -> Path:
    """Where the poses of run ``run_id`` are in ``out``."""
    name = quote(run_id, safe="")
    if name[0] in "._":  # readers skip files starting so
        name = f"%{ord(name[0]):02X}{name[1:]}"
    if len(name) + len(_SUFFIX) > MAX_NAME_BYTES:
        keep = MAX_NAME_BYTES - len(_SUFFIX) - 1 - _HASH_CHARACTERS
        cut = name[:keep]
        cut = cut[:cut.rfind("%")] if "%" in cut[-2:] else cut  # no half of a %XX
        digest = hashlib.sha256(run_id.encode("utf-8")).hexdigest()[:_HASH_CHARACTERS]
        name = f"{cut}+{digest}"
    return out / POSES_FOLDER / f"{name}{_SUFFIX}"


def clear_staging(out: Path) -> None:
    """Make ``out``'s folders; remove files left in staging by runs that did not finish."""
    shutil.rmtree(out / _STAGING_FOLDER, ignore_errors=True)
    (out / _STAGING_FOLDER).mkdir(parents=True, exist_ok=True)
    (out / POSES_FOLDER).mkdir(parents=True, exist_ok=True)


class PartitionWriter:
    """Writes one run's tables (columns ``schema``) into staging; on a clean exit renames
    the file into place.

    Use as a context manager; an exception inside removes the staged file and leaves any
    earlier version of the run's file as it was.
    """

    def __init__(self, out: Path, run_id: str, schema: pa.Schema) -> None:
        self.target = partition_path(out, run_id)
        self._staged = out / _STAGING_FOLDER / f"{uuid.uuid4().hex}.parquet"
        self._file = open(self._staged, "wb")  # closed in __exit__
        self._writer = pq.ParquetWriter(self._file, schema)
        self.rows = 0

    def write(self, table: pa.Table) -> None:
        """Append ``table`` as one row group."""
        self._writer.write_table(table, row_group_size=max(table.num_rows, 1))
        self.rows += table.num_rows

    def __enter__(self) -> PartitionWriter:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 traceback: TracebackType | None) -> None:
        try:
            self._writer.close()
            self._file.flush()
            os.fsync(self._file.fileno())
        finally:
            self._file.close()
        if kind is None:
            os.replace(self._staged, self.target)
        else:
            self._staged.unlink(missing_ok=True)
