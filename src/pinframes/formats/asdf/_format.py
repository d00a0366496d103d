"""ASDF in the registry: its content test and its reader and writer, which load the asdf
package only when an ASDF file is read or written (telling a file's format, and importing
pinframes, never does)."""

from __future__ import annotations

import os
from typing import Any

from ...tree import FrameTree
from .._registry import FileFormat
from ..reading import InputFile

__all__ = ["ASDF_FORMAT"]


def _read_asdf(path: str | os.PathLike[str], **options: Any) -> FrameTree:
    from ._reader import read_asdf

    return read_asdf(path, **options)


def _write_asdf(tree: FrameTree, path: str | os.PathLike[str], **options: Any) -> None:
    from ._writer import write_asdf

    write_asdf(tree, path, **options)


def _is_asdf(source: InputFile) -> bool:
    """A file that starts with ``#ASDF``."""
    return source.start().startswith(b"#ASDF")


ASDF_FORMAT = FileFormat("asdf", "ASDF", (".asdf",), _read_asdf, _write_asdf, ("schema", "key"),
                         head_test=_is_asdf, looks_like="an ASDF file")
"""weldx ASDF files: told by their first bytes, read and written by ``read_asdf`` and
``write_asdf``."""
