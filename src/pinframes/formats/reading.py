"""Reading a whole input file; every way that can fail is a :class:`ReadError` naming it.

Also the public door to the regular-file checks of ``_paths`` (only regular files are
read: a device never ends, a FIFO blocks): :func:`is_regular_file`,
:func:`regular_file_problem`.
"""

from __future__ import annotations

import os

from ..errors import ReadError
from ._paths import is_regular_file, read_regular_file, regular_file_problem

__all__ = ["is_regular_file", "read_bytes", "read_text", "regular_file_problem"]


def read_bytes(path: str | os.PathLike[str], size: int = -1) -> bytes:
    """The bytes of the file at ``path`` (its first ``size`` bytes if ``size >= 0``).

    Raises
    ------
    ReadError
        The path is missing, a folder, not a regular file (a device, a FIFO) or not
        readable.
    ArgumentTypeError
        ``path`` is not a text path (``str`` or ``os.PathLike``).
    """
    return read_regular_file(path, size)


def read_text(path: str | os.PathLike[str]) -> str:
    """The text of the UTF-8 file at ``path`` (a leading byte order mark is dropped).

    Raises
    ------
    ReadError
        As :func:`read_bytes`, and for content that is not UTF-8 text (binary data,
        another encoding); the message gives the byte offset.
    """
    raw = read_bytes(path)
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise ReadError(f"not UTF-8 text (byte {exc.start}): binary data or another "
                        "encoding", file=os.fspath(path)) from None
