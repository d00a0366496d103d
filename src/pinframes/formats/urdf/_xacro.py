"""xacro robot files (ROS's XML macros) expanded to URDF text with the ``xacro`` package.

A file is xacro when it holds ``<xacro:`` elements, or declares the xacro namespace and uses
``${...}`` or ``$(...)``, whatever its name (a URDF that xacro wrote often keeps the namespace
declaration: with nothing left to expand it is read as it is). ``$(arg NAME)`` takes
``args`` (then the file's ``<xacro:arg default>``);
``$(find PKG)`` is the package folder that
:func:`~pinframes.kinematics.collision.mesh_files.find_package` finds in the given
``package_dirs``, then ``ROS_PACKAGE_PATH``, then the xacro file's ancestor folders, instead
of ROS 2's ament index that the ``xacro`` package asks. The expansion is the ``xacro``
package's own (the text its ``xacro`` command prints). A xacro file is a program: includes,
YAML loads and expressions read what it names, so expand only files you trust.
"""

from __future__ import annotations

import io
import os
import re
import threading
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager, redirect_stderr
from pathlib import Path
from typing import Any

from ...errors import FileFormatError, UnsupportedFeatureError, warn_at_caller
from ...kinematics.collision.mesh_files import (
    PACKAGE_PATH_VARIABLE,
    find_package,
    package_search_dirs,
)

__all__ = ["expand_xacro", "is_xacro"]

_XACRO_ELEMENT = re.compile(r"<\s*xacro:")
_XACRO_NAMESPACE = re.compile(r"xmlns:xacro\s*=")
_SUBSTITUTION = re.compile(r"\$[{(]")
_LOCK = threading.Lock()  # the xacro package keeps its state in module globals


def is_xacro(text: str) -> bool:
    """Whether the XML ``text`` is a xacro file: a ``<xacro:`` element, or the xacro namespace
    and a ``${...}`` or ``$(...)`` substitution."""
    if _XACRO_ELEMENT.search(text):
        return True
    return bool(_XACRO_NAMESPACE.search(text) and _SUBSTITUTION.search(text))


class _PackageNotFound(Exception):
    def __init__(self, package: str, looked: list[Path]) -> None:
        super().__init__(package)
        self.package, self.looked = package, looked


def expand_xacro(path: str | os.PathLike[str], *, args: Mapping[str, Any] | None = None,
                 package_dirs: Iterable[str | os.PathLike[str]] = ()) -> str:
    """The URDF text that the xacro file at ``path`` expands to.

    ``args`` give ``$(arg NAME)`` values (strings; numbers and booleans are written as xacro
    reads them); ``package_dirs`` are searched first for ``$(find PKG)``.

    Raises
    ------
    UnsupportedFeatureError
        The ``xacro`` package is not installed (``pip install "pinframes[ros]"``).
    FileFormatError
        A package that is found nowhere (naming it and where it was looked for), an
        argument without a value, or any other xacro error, naming the file.
    """
    source = os.fspath(path)
    try:
        import xacro
        from xacro import substitution_args
    except ImportError:
        raise UnsupportedFeatureError(
            "is a xacro file; expanding it needs the xacro package: pip install "
            "'pinframes[ros]' (or pip install xacro)", file=source) from None
    search_dirs = [folder.resolve() for folder in package_search_dirs(package_dirs)]
    start = Path(source).resolve()

    def find(package: str) -> str:
        found = find_package(package, search_dirs, start)
        if found is None:
            raise _PackageNotFound(package, [*search_dirs, *start.parents])
        return str(found)

    mappings = {str(name): _xacro_value(value) for name, value in (args or {}).items()}
    said = io.StringIO()  # xacro prints its warnings: they become pinframes warnings
    with _LOCK, _finding_with(substitution_args, find), redirect_stderr(said):
        xacro.all_includes.clear()  # xacro lists every file it reads there, never emptied
        try:
            document = xacro.process_file(str(start), mappings=mappings)
        except Exception as exc:  # xacro wraps everything in XacroException
            raise _located_error(exc, source) from None
    for line in dict.fromkeys(said.getvalue().splitlines()):
        if line.strip():
            warn_at_caller(f"{source}: xacro: {_plain(line)}")
    text: str = document.toprettyxml(indent="  ")
    return text


def _plain(line: str) -> str:
    """A line xacro printed, without its terminal colour codes."""
    return re.sub(r"\x1b\[[0-9;]*m", "", line).strip()


@contextmanager
def _finding_with(substitution_args: Any, find: Any) -> Iterator[None]:
    """xacro's ``$(find)`` answered by ``find`` while inside."""
    saved = substitution_args._eval_find
    substitution_args._eval_find = find
    try:
        yield
    finally:
        substitution_args._eval_find = saved


def _xacro_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _located_error(error: Exception, source: str) -> FileFormatError:
    """A pinframes error for what xacro raised, naming the file (and a missing package)."""
    cause: BaseException | None = error
    while cause is not None and not isinstance(cause, _PackageNotFound):
        cause = getattr(cause, "exc", None) or cause.__cause__ or cause.__context__
    if isinstance(cause, _PackageNotFound):
        looked = ", ".join(map(str, cause.looked[:4])) + (" ..." if len(cause.looked) > 4
                                                          else "")
        return FileFormatError(
            f"$(find {cause.package}): package {cause.package!r} not found (looked in "
            f"{looked}); give the folder that holds it with package_dirs=[...] (Python), "
            f"--package-dir DIR (command line) or {PACKAGE_PATH_VARIABLE}", file=source,
            field="xacro")
    message = " ".join(str(error).split())
    if "Undefined substitution argument" in message:
        message += "; give it with xacro_args={...} (Python) or --xacro-arg NAME:=VALUE"
    return FileFormatError(f"xacro: {message}", file=source, field="xacro")
