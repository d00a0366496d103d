"""Atomic file writes: write beside the target, then rename over it."""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import stat
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO

from ..errors import PinframesError, WriteError
from ._paths import path_argument

__all__ = ["atomic_path", "atomic_write", "remove_stale_temporaries", "temporary_name"]

_TEMPORARY_PREFIX = ".pinframes-"
_TEMPORARY_SUFFIX = ".tmp"


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO]:
    """Open a temporary file in the target's folder; on success rename it onto ``path``.

    The folder must exist (no folders are created). A symbolic link is kept: the file it
    points to is replaced. If the body raises, or writing fails, the temporary file is
    removed and any existing file at ``path`` is left untouched; failures of the file
    system are :class:`~pinframes.errors.WriteError` naming ``path``.
    """
    file = path_argument(path)
    target = Path(os.path.realpath(file)) if os.path.islink(file) else Path(file)
    folder = target.parent if str(target.parent) else Path(".")
    _check_target(target, folder, file)
    remove_stale_temporaries(folder)
    try:
        fd, tmp_name = _create_temporary(folder)
    except OSError as exc:
        raise WriteError(f"cannot create a file here: {exc.strerror}", file=file) from exc
    try:
        try:
            _keep_mode_of(target, fd)
            handle = os.fdopen(fd, mode, encoding=None if "b" in mode else "utf-8")
        except BaseException:
            os.close(fd)
            raise
        with handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp_name, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp_name)
        if isinstance(exc, OSError) and not isinstance(exc, PinframesError):
            raise WriteError(f"cannot write: {exc.strerror or exc}", file=file) from exc
        raise


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str], *, folder: bool = False,
                replaceable: Callable[[Path], str | None] | None = None) -> Iterator[Path]:
    """A fresh temporary name beside ``path``, for writers that create their file (with
    ``folder``: their folder) themselves, such as rosbags' bag writers; on success it is
    renamed onto ``path``.

    Nothing exists at the temporary name when the body starts. If the body raises, whatever
    it made there is removed and ``path`` is left untouched. A folder replaces an existing
    one only when that is empty, or when ``replaceable`` (the writer's own test, such as
    "a ROS 2 bag and nothing else") finds nothing in it that is not the writer's: it returns
    None, else the reason, which the :class:`~pinframes.errors.WriteError` gives. The old
    folder is moved aside, the new one renamed in and the old one deleted. A symbolic link
    to a folder that is not empty is refused: what it points to is never emptied.
    """
    file = path_argument(path)
    target = Path(os.path.realpath(file)) if os.path.islink(file) else Path(file)
    parent = target.parent if str(target.parent) else Path(".")
    if folder:
        _check_folder_target(target, parent, file, os.path.islink(file), replaceable)
    else:
        _check_target(target, parent, file)
    remove_stale_temporaries(parent)
    temporary = parent / temporary_name()
    try:
        yield temporary
        if folder and target.is_dir():
            aside = parent / temporary_name()
            os.replace(target, aside)
            os.replace(temporary, target)
            shutil.rmtree(aside, ignore_errors=True)
        else:
            os.replace(temporary, target)
    except BaseException as exc:
        _remove(temporary)
        if isinstance(exc, OSError) and not isinstance(exc, PinframesError):
            raise WriteError(f"cannot write: {exc.strerror or exc}", file=file) from exc
        raise


def temporary_name(suffix: str = "") -> str:
    """A fresh name for a temporary file or folder of this process: one that
    :func:`remove_stale_temporaries` deletes once the process no longer runs (``suffix``
    goes before the ending, for names whose ending a library insists on)."""
    return (f"{_TEMPORARY_PREFIX}{os.getpid()}-{secrets.token_hex(6)}{suffix}"
            f"{_TEMPORARY_SUFFIX}")


def _remove(path: Path) -> None:
    """Delete the file or folder ``path`` if it exists."""
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            os.unlink(path)


def _check_folder_target(target: Path, parent: Path, file: str, linked: bool,
                         replaceable: Callable[[Path], str | None] | None) -> None:
    """Refuse to replace a file, a folder that is not empty behind a symbolic link, or one
    that ``replaceable`` does not accept."""
    if os.path.basename(os.path.normpath(file)) in (".", "..", "", os.sep):
        raise WriteError("names the current folder, its parent or the root, not a bag "
                         "folder of its own: give it a name (such as run)", file=file)
    try:
        if target.exists() and not target.is_dir():
            raise WriteError("exists and is not a folder", file=file)
        empty = not target.is_dir() or not any(target.iterdir())
    except OSError as exc:
        if isinstance(exc, PinframesError):
            raise
        raise WriteError(f"cannot write: {exc.strerror or exc}", file=file) from None
    if not empty and linked:
        raise WriteError(f"is a symbolic link to a folder that is not empty "
                         f"({os.fspath(target)}): pinframes never replaces a folder through "
                         "a link; write to the folder's own path or to a new name", file=file)
    if not empty:
        problem = "it is no output of this writer" if replaceable is None else replaceable(
            target)
        if problem is not None:
            raise WriteError(f"a folder that is not empty and not a ROS 2 bag: {problem}; "
                             "pinframes replaces only a bag folder holding nothing else "
                             "(write to a new name)", file=file)
    if not parent.is_dir():
        raise WriteError(f"the folder does not exist: {os.fspath(parent)}", file=file)


def _check_target(target: Path, folder: Path, file: str) -> None:
    """Refuse a target that exists and is no regular file (a folder, a FIFO, a device such
    as ``/dev/null``, which a rename would replace), or a missing folder."""
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:  # a name too long, a path through a file
        raise WriteError(f"cannot write: {exc.strerror or exc}", file=file) from None
    if mode is not None and stat.S_ISDIR(mode):
        raise WriteError("is a folder, not a file", file=file)
    if mode is not None and not stat.S_ISREG(mode):
        raise WriteError("exists and is not a regular file (a device, FIFO or socket): "
                         "pinframes replaces only regular files", file=file)
    if not folder.is_dir():
        raise WriteError(f"the folder does not exist: {os.fspath(folder)}", file=file)


def remove_stale_temporaries(folder: Path) -> None:
    """Delete temporary files (and folders) in ``folder`` that writers killed before their
    rename left behind: those of our naming whose process no longer runs."""
    try:
        entries = [entry.name for entry in os.scandir(folder)
                   if entry.name.startswith(_TEMPORARY_PREFIX)
                   and entry.name.endswith(_TEMPORARY_SUFFIX)]
    except OSError:
        return
    for name in entries:
        pid = name[len(_TEMPORARY_PREFIX):].split("-", 1)[0]
        if pid.isdigit() and not _running(int(pid)):
            _remove(folder / name)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # it runs, as another user
        return True
    return True


def _create_temporary(folder: Path) -> tuple[int, str]:
    """A new empty file in ``folder`` and its name, created with mode 0o666 so that the
    kernel applies the process's umask (and the folder's default ACL) as it does to any new
    file; the process umask is never changed, so other threads' files keep theirs.

    A short name of our own: legal names up to 255 bytes get a temporary name that fits, and
    the writer's process id tells a later write whether it was left behind.
    """
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        name = os.path.join(folder, f"{_TEMPORARY_PREFIX}{os.getpid()}-"
                                    f"{secrets.token_hex(6)}{_TEMPORARY_SUFFIX}")
        try:
            return os.open(name, flags, 0o666), name
        except FileExistsError:
            continue
    raise FileExistsError(f"no free temporary name in {os.fspath(folder)}")


def _keep_mode_of(target: Path, fd: int) -> None:
    """Give the file ``fd`` the permissions of ``target`` when it exists (a replaced file
    keeps its mode); a new file keeps the mode it was created with."""
    try:
        mode = stat.S_IMODE(target.stat().st_mode)
    except FileNotFoundError:
        return
    os.fchmod(fd, mode)
