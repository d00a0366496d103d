"""One table of file formats: which format a file is in, and reading or writing it.

Every format registers a :class:`FileFormat` (``pinframes.formats`` does so on import);
:func:`read` and :func:`write` (``pinframes.read`` / ``pinframes.write``) and every caller
that must pick a format (the CLI, scene layers, joint trajectory files) go through
:func:`detect_format`, the one place that tells formats apart, with the content tests each
format brings. A file is read once: detection reads it into an
:class:`~pinframes.formats.reading.InputFile` and :func:`read` hands that to the reader.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import FileFormatError, PinframesError, ReadError, WriteError
from ._content import is_text, other_content, other_document
from ._paths import check_regular_file, path_argument
from .limits import using_limits
from .reading import InputFile

__all__ = [
    "FileFormat",
    "detect_format",
    "file_format",
    "files_read",
    "formats_taking",
    "is_tree_folder",
    "read",
    "register_format",
    "registered_formats",
    "require_format",
    "write",
]

TREE = "tree"
"""Kind of the formats that hold a whole frame tree."""


@dataclass(frozen=True)
class FileFormat:
    """A file format pinframes reads or writes.

    Attributes
    ----------
    name : str
        What ``format=`` and the CLI's ``--to`` call it (``"asdf"``, ``"frames.yaml"``...);
        unique within its ``kind``.
    title : str
        Its name in messages (``"ASDF"``).
    suffixes : tuple of str
        Lower-case file name suffixes, with the dot.
    read : callable or None
        ``read(path, **options)``: a tree (or, for other kinds, what the format holds).
        ``path`` may be the :class:`~pinframes.formats.reading.InputFile` detection read;
        ``InputFile.of(path)`` gives it back with what it holds.
    write : callable or None
        ``write(tree, path, **options)``, atomic.
    write_options : tuple of str
        The keyword options ``write`` takes.
    head_test : callable or None
        ``head_test(source) -> bool``: whether the file is in this format, told from its
        first bytes (``source.head()``, ``source.start()``) and name alone. Asked, for a
        file that exists, of every format of every kind, in registration order.
    document_test : callable or None
        ``document_test(source) -> bool``: whether a text file is in this format, told
        from its YAML document (``source.yaml()``) and name; asked when no ``head_test``
        claimed the file, and among formats that share a suffix.
    looks_like : str
        How a file this format's ``head_test`` claims is named in messages
        (``"an ASDF file"``), when the caller wanted another format.
    unrecognised : str
        Why a file is not this format, for the message when no format recognises it.
    write_name_test : callable or None
        ``write_name_test(path) -> bool``, for formats that share a suffix: whether a file
        to be written at ``path`` takes this format; a name no format's test claims goes
        to the first format without one.
    files_read : callable or None
        ``files_read(source) -> list of Path``: the other files reading ``source`` opens
        (and those they open in turn), whether they exist or not; None: no other file.
    kind : str
        ``"tree"``, or another kind of file (``"joint trajectory"``, ``"poses"``).
    folder_test : callable or None
        For a format whose ``read`` also takes a folder (a ROS 2 bag):
        ``folder_test(path) -> bool``, whether the folder at ``path`` is one. None: the
        format reads files only.
    near_miss : callable or None
        ``near_miss(source) -> str or None``: for a text file no format claims, what it is
        when it is almost in this format and what it lacks (a scene without its
        ``pinframes_scene`` line), for the message that refuses it.
    """

    name: str
    title: str
    suffixes: tuple[str, ...]
    read: Callable[..., Any] | None = None
    write: Callable[..., None] | None = None
    write_options: tuple[str, ...] = ()
    head_test: Callable[[InputFile], bool] | None = None
    document_test: Callable[[InputFile], bool] | None = None
    looks_like: str = ""
    unrecognised: str = ""
    write_name_test: Callable[[Path], bool] | None = None
    files_read: Callable[[InputFile], list[Path]] | None = None
    kind: str = TREE
    folder_test: Callable[[Path], bool] | None = None
    near_miss: Callable[[InputFile], str | None] | None = None


_FORMATS: dict[tuple[str, str], FileFormat] = {}


def register_format(file_format: FileFormat) -> None:
    """Add ``file_format`` to the table (replacing a format of the same kind and name)."""
    _FORMATS[file_format.kind, file_format.name] = file_format


def registered_formats(kind: str = TREE) -> tuple[str, ...]:
    """Names of the registered formats of ``kind``, in registration order."""
    return tuple(entry.name for entry in _FORMATS.values() if entry.kind == kind)


def file_format(name: str, kind: str = TREE) -> FileFormat:
    """The registered format ``name``; a :class:`FileFormatError` for an unknown one."""
    entry = _FORMATS.get((kind, name)) if isinstance(name, str) else None
    if entry is None:
        raise FileFormatError(f"unknown format {name!r}; expected one of "
                              f"{', '.join(registered_formats(kind))}", field="format")
    return entry


def detect_format(
    path: str | os.PathLike[str], *, writing: bool = False, kind: str = TREE,
    among: Sequence[str] | None = None,
) -> str:
    """The format of ``path``: a tree file that exists is told by its content, whatever its
    name (the formats' ``head_test`` and ``document_test``); a file to be written (if
    ``writing``) and other kinds of files by the suffix; a tree to be written to a name
    without a suffix, or to a folder, goes to the format that writes folders (ROS 2 bags).

    Formats that share a suffix (``.yaml``: scene or frames.yaml) are told apart by their
    ``document_test`` (``write_name_test`` for a file to be written). ``among`` restricts
    the candidates to those format names. ``path`` may be an
    :class:`~pinframes.formats.reading.InputFile`: what detection reads stays in it.
    """
    source = InputFile.of(path)
    suffix = source.path.suffix.lower()
    allowed = [entry for entry in _FORMATS.values() if entry.kind == kind
               and (among is None or entry.name in among)]
    folder = kind == TREE and _is_folder(source.path, writing)
    if kind == TREE and not writing and folder:
        return _folder_format(source.path, allowed)
    if kind == TREE and not writing and source.path.is_file():
        return _format_by_content(source, allowed)
    if kind == TREE and writing and (not suffix or folder):
        folder_writers = [entry.name for entry in allowed
                          if entry.folder_test is not None and entry.write is not None]
        if folder_writers:  # a folder to be written (a ROS 2 bag)
            return folder_writers[0]
    candidates = [entry for entry in allowed if suffix in entry.suffixes]
    if not candidates:
        suffixes = list(dict.fromkeys(s for entry in allowed for s in entry.suffixes))
        expected = " or ".join([", ".join(suffixes[:-1]), suffixes[-1]] if len(suffixes) > 1
                               else suffixes)
        what = "file type" if kind == TREE else f"{kind} file type"
        raise FileFormatError(f"unknown {what} {suffix or '(none)'!r}; expected {expected}",
                              file=source)
    if len(candidates) == 1:
        return candidates[0].name
    if writing:  # the format whose name test claims the name, else the first without one
        named = [entry for entry in candidates if entry.write_name_test is not None
                 and entry.write_name_test(source.path)]
        unnamed = [entry for entry in candidates if entry.write_name_test is None]
        if named or unnamed:
            return (named or unnamed)[0].name
    for entry in candidates:
        if not writing and (entry.document_test is None or entry.document_test(source)):
            return entry.name
    raise FileFormatError("neither " + " nor ".join(
        f"a {entry.title} ({entry.unrecognised})" for entry in candidates), file=source)


def _format_by_content(source: InputFile, allowed: list[FileFormat]) -> str:
    """The format among ``allowed`` that the file holds: the first format of any kind whose
    ``head_test`` claims it, else (for text) the first whose ``document_test`` does; a file
    no allowed format claims is a :class:`FileFormatError` saying what it looks like."""
    for entry in _FORMATS.values():
        if entry.head_test is not None and entry.head_test(source):
            if entry in allowed:
                return entry.name
            raise _not_a_tree(source, entry.looks_like, allowed)
    other = other_content(source)
    if other is not None:
        raise _not_a_tree(source, other, allowed)
    for entry in allowed:
        if entry.document_test is not None and entry.document_test(source):
            return entry.name
    for entry in allowed:
        near = None if entry.near_miss is None else entry.near_miss(source)
        if near is not None:
            raise _not_a_tree(source, near, allowed)
    named = other_document(source)
    if named is not None:
        raise _not_a_tree(source, named, allowed)
    reasons = " nor ".join(f"a {entry.title} ({entry.unrecognised})" for entry in allowed
                           if entry.unrecognised)
    raise _not_a_tree(source, f"YAML or text, but neither {reasons}" if reasons else "text",
                      allowed)


def require_format(source: InputFile, name: str) -> None:
    """Refuse, before a reader parses it, a file that another format's content test claims
    or that is text of another kind (XML, CSV): a :class:`FileFormatError` saying what the
    file is and which reader takes it (``name``: the format of the reader that was called).
    Bytes that are no text are left to the reader's :class:`ReadError`."""
    wanted = file_format(name)
    for entry in _FORMATS.values():
        if entry is not wanted and entry.head_test is not None and entry.head_test(source):
            raise FileFormatError(f"this is {entry.looks_like}, not a {wanted.title} file"
                                  + _reader_of(entry), file=source)
    other = other_content(source) if is_text(source) else None
    if other is not None:
        raise FileFormatError(f"this looks like {other}, not a {wanted.title} file",
                              file=source)


def _reader_of(entry: FileFormat) -> str:
    """Which reader takes a file of ``entry``'s format, for a message."""
    if entry.kind == TREE:
        return "; pinframes.read() and the command line read it"
    return ""


def _not_a_tree(source: InputFile, kind: str, allowed: list[FileFormat]) -> FileFormatError:
    titles = [entry.title for entry in allowed]
    known = ", ".join(titles[:-1]) + " and " + titles[-1] if len(titles) > 1 else titles[0]
    return FileFormatError(f"this looks like {kind}; pinframes reads trees from {known} "
                           "files", file=source)


def files_read(path: str | os.PathLike[str], *, among: Sequence[str] | None = None
               ) -> list[Path]:
    """Every file reading the tree file ``path`` opens, resolved, each once: ``path``
    first (unless it is a folder that names its files), then what its format's
    ``files_read`` names. A file whose format (``among`` those names, if given) cannot be
    told, or that cannot be read, names no other file (reading it will say why)."""
    source = InputFile.of(path)
    try:
        entry = file_format(detect_format(source, among=among))
        named = entry.files_read(source) if entry.files_read is not None else []
    except PinframesError:
        named = []
    itself = [] if named and source.path.is_dir() else [source.path]  # a bag folder: its files
    return list(dict.fromkeys(file.resolve() for file in [*itself, *named]))


def read(path: str | os.PathLike[str], format: str | None = None, **options: Any) -> Any:
    """Read the tree in ``path``, in ``format`` (default: told from the file), reading
    the file once (``path`` may be an :class:`~pinframes.formats.reading.InputFile`).

    ``options`` go to the format's reader (``key=`` for ASDF); ``limits=`` (a
    :class:`pinframes.Limits`) bounds the read, for every format.
    """
    with using_limits(options.pop("limits", None)):
        entry = file_format(format) if format is not None else None
        folder_reader = entry is None or entry.folder_test is not None
        if not (folder_reader and Path(path_argument(path)).is_dir()):
            check_regular_file(path)
        source = InputFile.of(path)
        entry = entry or file_format(detect_format(source))
        if entry.read is None:
            raise FileFormatError(f"pinframes does not read {entry.title} files", file=path)
        return entry.read(source, **options)


def write(tree: Any, path: str | os.PathLike[str], format: str | None = None,
          **options: Any) -> None:
    """Write ``tree`` to ``path`` in ``format`` (default: told from the name), atomically.

    ``options`` go to the format's writer: ``time=`` for the formats that store one pose
    per frame, ``schema=`` for ASDF, ``times=`` and ``time_ref=`` for ROS bags (``.mcap``,
    ``.bag``, ``.db3``, or a name without a suffix: a ROS 2 bag folder). An option the
    format does not take is a :class:`FileFormatError`.
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
    """The format that reads the folder ``path``: the first registered whose
    ``folder_test`` takes it."""
    readers = [entry for entry in allowed if entry.folder_test is not None]
    for entry in readers:
        if entry.folder_test is not None and entry.folder_test(path):
            return entry.name
    why = "; ".join(entry.unrecognised for entry in readers if entry.unrecognised)
    raise ReadError("is a folder, not a file" + (f" ({why})" if why else ""), file=path)


def is_tree_folder(path: str | os.PathLike[str]) -> bool:
    """Whether a format reads the folder ``path`` as one tree (a ROS 2 bag folder)."""
    folder = Path(path)
    return folder.is_dir() and any(entry.folder_test(folder) for entry in _FORMATS.values()
                                   if entry.folder_test is not None and entry.kind == TREE)


def _is_folder(path: Path, writing: bool) -> bool:
    """Whether ``path`` is a folder; a path the system cannot look at (a name too long, a
    path through a file) is a :class:`WriteError` or :class:`ReadError` naming it."""
    try:
        return stat.S_ISDIR(os.stat(path).st_mode)
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError as exc:
        error = WriteError if writing else ReadError
        raise error(f"cannot {'write' if writing else 'read'}: {exc.strerror or exc}",
                    file=path) from None


def _check_path(path: object) -> None:
    path_argument(path)
