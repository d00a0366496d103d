"""Atomic file writes: write beside the target, then rename over it."""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from ..errors import PinframesError, WriteError

__all__ = ["atomic_write"]


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO]:
    """Open a temporary file in the target's folder; on success rename it onto ``path``.

    The folder must exist (no folders are created). A symbolic link is kept: the file it
    points to is replaced. If the body raises, or writing fails, the temporary file is
    removed and any existing file at ``path`` is left untouched; failures of the file
    system are :class:`~pinframes.errors.WriteError` naming ``path``.
    """
    target = Path(os.path.realpath(path)) if os.path.islink(path) else Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if target.is_dir():
        raise WriteError("is a folder, not a file", file=os.fspath(path))
    if not folder.is_dir():
        raise WriteError(f"the folder does not exist: {os.fspath(folder)}",
                         file=os.fspath(path))
    try:
        fd, tmp_name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise WriteError(f"cannot create a file here: {exc.strerror}",
                         file=os.fspath(path)) from exc
    try:
        try:
            os.fchmod(fd, _mode_for(target))
            handle = os.fdopen(fd, mode, **({} if "b" in mode else {"encoding": "utf-8"}))
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
            raise WriteError(f"cannot write: {exc.strerror or exc}",
                             file=os.fspath(path)) from exc
        raise


def _mode_for(target: Path) -> int:
    """The permissions of the file being replaced, else what a new file gets (0o666 - umask);
    ``mkstemp`` alone would leave every written file readable by its owner only."""
    try:
        return stat.S_IMODE(target.stat().st_mode)
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask
