"""A ROS 2 ``.db3`` file checked for values SQLite computes when they are read.

A bag's bytes are bounded by its file, except where SQLite makes them up on reading: a
virtual generated column (``data BLOB GENERATED ALWAYS AS (zeroblob(2000000000))``) or a
virtual table. rosbag2 writes neither; a file that has one is refused, from its schema
alone, before any row is read.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

from ...errors import FileFormatError

__all__ = ["check_stored_values"]

_VIRTUAL_GENERATED = 2
"""``PRAGMA table_xinfo``'s ``hidden`` for a generated column computed on reading."""


def check_stored_values(database: Path, bag: Path) -> None:
    """Refuse ``database`` (a file of ``bag``) if any of its tables is virtual or has a
    column computed when read; a :class:`FileFormatError` naming the bag and the column."""
    uri = f"{database.resolve().as_uri()}?mode=ro&immutable=1"
    try:
        connection = sqlite3.connect(uri, uri=True)
    except sqlite3.Error as exc:
        raise _corrupt(database, exc, bag) from None
    try:
        tables = connection.execute(
            "SELECT name, sql FROM sqlite_master WHERE type = 'table'").fetchall()
        for table, sql in tables:
            if str(sql or "").lstrip().upper().startswith("CREATE VIRTUAL"):
                raise FileFormatError("a virtual table, whose rows SQLite makes up when they "
                                      "are read; rosbag2 writes none", file=bag,
                                      field=str(table))
            for column in connection.execute("SELECT name, hidden FROM pragma_table_xinfo(?)",
                                             (table,)):
                if column[1] == _VIRTUAL_GENERATED:
                    raise FileFormatError(
                        "a generated column, which SQLite computes when it is read (of any "
                        "size); rosbag2 stores its values", file=bag,
                        field=f"{table}.{column[0]}")
    except sqlite3.Error as exc:
        raise _corrupt(database, exc, bag) from None
    finally:
        connection.close()


def _corrupt(database: Path, error: sqlite3.Error, bag: Path) -> FileFormatError:
    return FileFormatError(f"cannot open it (truncated or corrupt bag?): {database.name}: "
                           f"{error}", file=bag)
