"""One table of file formats: which format a file is in, and reading or writing it.

Every format registers a :class:`FileFormat` (``pinframes.formats`` does so on import);
:func:`read` and :func:`write` (``pinframes.read`` / ``pinframes.write``) and every caller
that must pick a format (the CLI, scene layers, joint trajectory files) go through
:func:`detect_format`, the one place that tells formats apart.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import FileFormatError, ReadError
from ._content import format_by_content
from ._paths import check_regular_file, path_argument
from ._yaml_loader import load_yaml
from .limits import using_limits

__all__ = [
    "FileFormat",
    "Peek",
    "detect_format",
    "file_format",
    "formats_taking",
    "read",
    "register_format",
    "registered_formats",
    "write",
]

TREE = "tree"
"""Kind of the formats that hold a whole frame tree."""


class Peek:
    """The content of a file whose format is being detected, loaded at most once."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._yaml: tuple[Any] | None = None

    def yaml(self) -> Any:
        """The file parsed as YAML (a :class:`FileFormatError` when it is not YAML)."""
        if self._yaml is None:
            self._yaml = (load_yaml(self.path),)
        return self._yaml[0]


@dataclass(frozen=True)
class FileFormat:
    """A file format pinframes reads or writes.

    Attributes
    ----------
    name : str
        What ``format=`` and the CLI's ``--to`` call it (``"asdf"``, ``"frames.yaml"``...).
    title : str
        Its name in messages (``"ASDF"``).
    suffixes : tuple of str
        Lower-case file name suffixes, with the dot.
    read : callable or None
        ``read(path, **options)``: a tree (or, for other kinds, what the format holds).
    write : callable or None
        ``write(tree, path, **options)``, atomic.
    write_options : tuple of str
        The keyword options ``write`` takes.
    recognise : callable or None
        ``recognise(peek, writing) -> bool``, asked only when several formats share a
        suffix, in registration order; None: the format takes every such file.
    unrecognised : str
        Why a file is not this format, for the message when no format recognises it.
    kind : str
        ``"tree"``, or another kind of file (``"joint trajectory"``).
    folders : bool
        Whether ``read`` also takes a folder (a ROS 2 bag); ``recognise`` is then asked
        whether a folder is one.
    """

    name: str
    title: str
    suffixes: tuple[str, ...]
    read: Callable[..., Any] | None = None
    write: Callable[..., None] | None = None
    write_options: tuple[str, ...] = ()
    recognise: Callable[[Peek, bool], bool] | None = None
    unrecognised: str = ""
    kind: str = TREE
    folders: bool = False


_FORMATS: dict[str, FileFormat] = {}


def register_format(file_format: FileFormat) -> None:
    """Add ``file_format`` to the table (replacing a format of the same name)."""
    _FORMATS[file_format.name] = file_format


def registered_formats(kind: str = TREE) -> tuple[str, ...]:
    """Names of the registered formats of ``kind``, in registration order."""
    return tuple(name for name, entry in _FORMATS.items() if entry.kind == kind)


def file_format(name: str, kind: str = TREE) -> FileFormat:
    """The registered format ``name``; a :class:`FileFormatError` for an unknown one."""
    entry = _FORMATS.get(name) if isinstance(name, str) else None
    if entry is None or entry.kind != kind:
        raise FileFormatError(f"unknown format {name!r}; expected one of "
                              f"{', '.join(registered_formats(kind))}", field="format")
    return entry


def detect_format(
    path: str | os.PathLike[str], *, writing: bool = False, kind: str = TREE,
    among: Sequence[str] | None = None,
) -> str:
    """The format of ``path``: a tree file that exists is told by its content, whatever its
    name (:func:`~pinframes.formats._content.format_by_content`); a file to be written (if
    ``writing``) and other kinds of files by the suffix.

    Formats that share a suffix (``.yaml``: scene or frames.yaml) are told apart by their
    ``recognise`` test. ``among`` restricts the candidates to those format names.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    allowed = [entry for entry in _FORMATS.values() if entry.kind == kind
               and (among is None or entry.name in among)]
    if kind == TREE and not writing and path.is_dir():
        return _folder_format(path, allowed)
    if kind == TREE and not writing and path.is_file():
        peek = Peek(path)
        return format_by_content(path, allowed, lambda yaml_formats: next(
            (entry.name for entry in yaml_formats
             if entry.recognise is None or entry.recognise(peek, False)), None))
    candidates = [entry for entry in allowed if suffix in entry.suffixes]
    if not candidates:
        suffixes = list(dict.fromkeys(s for entry in allowed for s in entry.suffixes))
        expected = " or ".join([", ".join(suffixes[:-1]), suffixes[-1]] if len(suffixes) > 1
                               else suffixes)
        what = "file type" if kind == TREE else f"{kind} file type"
        raise FileFormatError(f"unknown {what} {suffix or '(none)'!r}; expected {expected}",
                              file=path)
    if len(candidates) == 1:
        return candidates[0].name
    peek = Peek(path)
    for entry in candidates:
        if entry.recognise is None or entry.recognise(peek, writing):
            return entry.name
    raise FileFormatError("neither " + " nor ".join(
        f"a {entry.title} ({entry.unrecognised})" for entry in candidates), file=path)


def read(path: str | os.PathLike[str], format: str | None = None, **options: Any) -> Any:
    """Read the tree in ``path``, in ``format`` (default: told from the file).

    ``options`` go to the format's reader (``key=`` for ASDF); ``limits=`` (a
    :class:`pinframes.Limits`) bounds the read, for every format.
    """
    with using_limits(options.pop("limits", None)):
        entry = file_format(format) if format is not None else None
        if not (entry is None or entry.folders) or not Path(path_argument(path)).is_dir():
            check_regular_file(path)
        entry = entry or file_format(detect_format(path))
        if entry.read is None:
            raise FileFormatError(f"pinframes does not read {entry.title} files", file=path)
        return entry.read(path, **options)


def write(tree: Any, path: str | os.PathLike[str], format: str | None = None,
          **options: Any) -> None:
    """Write ``tree`` to ``path`` in ``format`` (default: told from the name), atomically.

    ``options`` go to the format's writer: ``time=`` for the formats that store one pose
    per frame, ``schema=`` for ASDF. An option the format does not take is a
    :class:`FileFormatError`.
    """
    _check_path(path)
    entry = file_format(format) if format is not None else file_format(
        detect_format(path, writing=True))
    if entry.write is None:
        raise FileFormatError(f"pinframes does not write {entry.title} files", file=path)
    for option in options:
        if option not in entry.write_options:
            raise FileFormatError(
                f"{entry.title} files take no {option!r} option (they take "
                f"{', '.join(entry.write_options) or 'none'})", file=path, field=option)
    entry.write(tree, path, **options)


def formats_taking(option: str) -> list[FileFormat]:
    """The tree formats whose writer takes ``option``."""
    return [entry for entry in _FORMATS.values()
            if entry.kind == TREE and option in entry.write_options]


def _folder_format(path: Path, allowed: Sequence[FileFormat]) -> str:
    """The format that reads the folder ``path``: the first registered that reads folders
    and whose ``recognise`` test takes this one."""
    peek = Peek(path)
    readers = [entry for entry in allowed if entry.folders]
    for entry in readers:
        if entry.recognise is None or entry.recognise(peek, False):
            return entry.name
    why = "; ".join(entry.unrecognised for entry in readers if entry.unrecognised)
    raise ReadError("is a folder, not a file" + (f" ({why})" if why else ""), file=path)


def _check_path(path: object) -> None:
    path_argument(path)
