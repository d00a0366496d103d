"""Path arguments of readers and writers: what is accepted, and which files may be read.

Readers and writers take a ``str`` or an ``os.PathLike`` (``pathlib.Path``); anything else
(an int, None, bytes) is an :class:`~pinframes.errors.ArgumentTypeError`. Only regular
files are read (or symbolic links to them): a device such as ``/dev/zero`` never ends and a
FIFO blocks until someone writes, so both are refused, without opening a FIFO.
"""

from __future__ import annotations

import os
import stat
from typing import NoReturn

from ..errors import ArgumentTypeError, ReadError

__all__ = ["check_regular_file", "is_regular_file", "path_argument", "read_regular_file",
           "regular_file_problem"]


def path_argument(path: object, field: str = "path") -> str:
    """``path`` as a ``str``; an :class:`ArgumentTypeError` unless it is a text path."""
    if not isinstance(path, (str, os.PathLike)):
        raise ArgumentTypeError(f"expected a file path (str or os.PathLike), got "
                                f"{type(path).__name__}", field=field)
    file = os.fspath(path)
    if not isinstance(file, str):
        raise ArgumentTypeError(f"expected a text path, got {type(file).__name__}",
                                field=field)
    if "\0" in file:
        raise ArgumentTypeError("a file path cannot hold a NUL character", field=field)
    return file


def read_regular_file(path: object, size: int = -1) -> bytes:
    """The bytes of the regular file at ``path`` (its first ``size`` bytes if
    ``size >= 0``).

    Raises
    ------
    ArgumentTypeError
        ``path`` is not a text path.
    ReadError
        It is missing, a folder, not a regular file, or unreadable.
    """
    file = path_argument(path)
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer before fstat refuses it
        descriptor = os.open(file, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except FileNotFoundError:
        raise ReadError("no such file", file=file) from None
    except IsADirectoryError:
        raise ReadError("is a folder, not a file", file=file) from None
    except OSError as exc:
        raise ReadError(f"cannot read: {exc.strerror or exc}", file=file) from None
    mode = os.fstat(descriptor).st_mode
    if not stat.S_ISREG(mode):
        os.close(descriptor)
        _refuse_irregular(mode, file)
    with open(descriptor, "rb") as handle:
        try:
            return handle.read(size)
        except OSError as exc:
            raise ReadError(f"cannot read: {exc.strerror or exc}", file=file) from None


def is_regular_file(path: str | os.PathLike[str]) -> bool:
    """True when ``path`` names a regular file; False also for names the system refuses
    (too long, a path through a file), where ``Path.is_file`` raises ``OSError``."""
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except (OSError, ValueError):
        return False


def regular_file_problem(path: str | os.PathLike[str]) -> str | None:
    """Why ``path`` is no regular file to read (``"no such file"``, ``"is a folder, not a
    file"``, ...), or None when it is one; without opening it."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "no such file"
    except (OSError, ValueError) as exc:
        return f"cannot read: {getattr(exc, 'strerror', None) or exc}"
    if stat.S_ISREG(mode):
        return None
    return _IS_FOLDER if stat.S_ISDIR(mode) else _IRREGULAR


def check_regular_file(path: object) -> str:
    """``path`` as a ``str`` if it names a readable regular file, else a pinframes error."""
    file = path_argument(path)
    try:
        mode = os.stat(file).st_mode
    except FileNotFoundError:
        raise ReadError("no such file", file=file) from None
    except OSError as exc:
        raise ReadError(f"cannot read: {exc.strerror or exc}", file=file) from None
    if not stat.S_ISREG(mode):
        _refuse_irregular(mode, file)
    return file


_IS_FOLDER = "is a folder, not a file"
_IRREGULAR = "not a regular file (a device, FIFO or socket): refused"


def _refuse_irregular(mode: int, file: str) -> NoReturn:
    raise ReadError(_IS_FOLDER if stat.S_ISDIR(mode) else _IRREGULAR, file=file)
