"""Reading a whole input file; every way that can fail is a :class:`ReadError` naming it."""

from __future__ import annotations

import os

from ..errors import ArgumentTypeError, ReadError

__all__ = ["read_bytes", "read_text"]


def read_bytes(path: str | os.PathLike[str]) -> bytes:
    """The bytes of the file at ``path``.

    Raises
    ------
    ReadError
        The path is missing, a folder or not readable.
    ArgumentTypeError
        ``path`` is not a path.
    """
    try:
        file = os.fspath(path)
    except TypeError:
        raise ArgumentTypeError(f"expected a file path, got {type(path).__name__}",
                                field="path") from None
    try:
        with open(file, "rb") as handle:
            return handle.read()
    except FileNotFoundError:
        raise ReadError("no such file", file=file) from None
    except IsADirectoryError:
        raise ReadError("is a folder, not a file", file=file) from None
    except (OSError, ValueError) as exc:  # ValueError: a NUL character in the path
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise ReadError(f"cannot read: {reason}", file=file) from None


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
