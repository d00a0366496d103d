"""Reading an input file once: its first bytes, its bytes, its text and its YAML.

An :class:`InputFile` reads what is asked of it at most once and keeps it: telling a file's
format looks at its first bytes (:meth:`InputFile.head`) and, for YAML formats, at its
document (:meth:`InputFile.yaml`); the reader that follows is handed the same
``InputFile`` and finds them there. It is an ``os.PathLike``, so every reader still takes a
path. Every way reading can fail is a :class:`~pinframes.errors.ReadError` naming the file.

Also the public door to the regular-file checks of ``_paths`` (only regular files are
read: a device never ends, a FIFO blocks): :func:`is_regular_file`,
:func:`regular_file_problem`.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from ..errors import ReadError
from ._paths import is_regular_file, path_argument, read_regular_file, regular_file_problem
from ._yaml_loader import Locate, parse_yaml

__all__ = ["HEAD_BYTES", "InputFile", "is_regular_file", "read_bytes", "read_text",
           "regular_file_problem"]

HEAD_BYTES = 4096
"""How many first bytes :meth:`InputFile.head` reads: what tells a file's format."""

_Parsed = TypeVar("_Parsed")


class InputFile(os.PathLike[str]):
    """A file to be read, read at most once, whatever asks for it.

    Parameters
    ----------
    path : str or path-like
        The file (an ``InputFile`` is taken as it is by :meth:`of`).

    Attributes
    ----------
    path : pathlib.Path
        The file; ``os.fspath`` gives the path as it was passed.
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self._file = path_argument(path)
        self.path = Path(self._file)
        self._head: bytes | None = None
        self._data: bytes | None = None
        self._parsed: dict[str, Any] = {}

    @classmethod
    def of(cls, path: str | os.PathLike[str]) -> InputFile:
        """``path`` itself if it is an ``InputFile`` (with what it has read), else a new one."""
        return path if isinstance(path, InputFile) else cls(path)

    def __fspath__(self) -> str:
        return self._file

    def __repr__(self) -> str:
        return f"InputFile({self._file!r})"

    def head(self) -> bytes:
        """The first :data:`HEAD_BYTES` bytes (all of a shorter file), reading no more.

        Raises
        ------
        ReadError
            Missing, a folder, not a regular file (a device, a FIFO) or unreadable.
        """
        if self._data is not None:
            return self._data[:HEAD_BYTES]
        if self._head is None:
            self._head = read_regular_file(self._file, size=HEAD_BYTES)
        return self._head

    def start(self) -> bytes:
        """:meth:`head` without a UTF-8 byte order mark and leading white space: where a
        format's content test looks for its marks (``#ASDF``, ``<robot``)."""
        return self.head().removeprefix(b"\xef\xbb\xbf").lstrip()

    def data(self) -> bytes:
        """All the bytes of the file (after :meth:`head`, only the rest is read).

        Raises
        ------
        ReadError
            As :meth:`head`.
        """
        if self._data is None:
            head = self._head
            if head is None:
                self._data = read_regular_file(self._file)
            elif len(head) < HEAD_BYTES:
                self._data = head
            else:
                self._data = head + read_regular_file(self._file, start=len(head))
            self._head = None
        return self._data

    def text(self) -> str:
        """The file as UTF-8 text (a leading byte order mark is dropped).

        Raises
        ------
        ReadError
            As :meth:`head`, and for content that is not UTF-8 text (binary data, another
            encoding); the message gives the byte offset.
        """
        return self.parsed("text", self._decoded)

    def yaml(self, locate: Locate | None = None) -> Any:
        """The file's one YAML document of plain data, parsed once
        (:func:`~pinframes.formats._yaml_loader.parse_yaml`: within the reader limits,
        duplicate keys and unknown tags refused). ``locate`` names the frame and field of
        an error in the document (only errors depend on it)."""
        return self.parsed("yaml", lambda: parse_yaml(self.text(), self._file, locate))

    def parsed(self, name: str, parse: Callable[[], _Parsed]) -> _Parsed:
        """What ``parse()`` returns, kept under ``name``: the file is parsed so only once."""
        if name not in self._parsed:
            self._parsed[name] = parse()
        result: _Parsed = self._parsed[name]
        return result

    def _decoded(self) -> str:
        try:
            return self.data().decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            raise ReadError(f"not UTF-8 text (byte {exc.start}): binary data or another "
                            "encoding", file=self._file) from None


def read_bytes(path: str | os.PathLike[str]) -> bytes:
    """The bytes of the file at ``path`` (:meth:`InputFile.data`).

    Raises
    ------
    ReadError
        The path is missing, a folder, not a regular file (a device, a FIFO) or not
        readable.
    ArgumentTypeError
        ``path`` is not a text path (``str`` or ``os.PathLike``).
    """
    return InputFile.of(path).data()


def read_text(path: str | os.PathLike[str]) -> str:
    """The text of the UTF-8 file at ``path`` (:meth:`InputFile.text`; a leading byte
    order mark is dropped).

    Raises
    ------
    ReadError
        As :func:`read_bytes`, and for content that is not UTF-8 text (binary data,
        another encoding); the message gives the byte offset.
    """
    return InputFile.of(path).text()
