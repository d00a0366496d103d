"""xacro robot files (ROS's XML macros) expanded to URDF text with the ``xacro`` package,
only when the caller asks for it, in a bounded child process.

A xacro file is a program: ``$(eval ...)`` and ``${...}`` evaluate Python expressions,
includes and ``load_yaml`` read what they name. So a file is expanded only when the caller
asks (:func:`wants_expansion`): a file named ``*.xacro`` given directly, or ``xacro=True``
(``--xacro`` on the command line, ``xacro: true`` in a scene's robot entry). Any other file
with xacro content (``<xacro:`` elements, or the xacro namespace and ``${...}`` or ``$(...)``)
is a :class:`FileFormatError` saying how to opt in; a URDF that xacro wrote and that keeps
the namespace declaration, with nothing left to expand, is read as it is.

The expansion is the ``xacro`` package's own (the text its ``xacro`` command prints), run
in a child process (``_xacro_child.py``) that gets the file's text, its arguments and the
map of package names to folders, and nothing else: no environment variables (``$(env
NAME)`` is an error, ``$(optenv NAME DEFAULT)`` its default, so no value of the user's
environment ends up in a link name), at most ``max_xacro_seconds`` of processor time and
``max_xacro_bytes`` of memory (:class:`pinframes.Limits`), and only regular files to
include (a FIFO would block forever). ``$(find PKG)`` is the folder of the package whose
``package.xml`` names it (:func:`~pinframes.kinematics.collision.ros_packages.package_folders`:
the given ``package_dirs``, ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH``, the file's
ancestors), instead of ROS 2's ament index that the ``xacro`` package asks.
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from ...errors import FileFormatError, UnsupportedFeatureError, warn_at_caller
from ...kinematics.collision.ros_packages import (
    PACKAGE_PATH_VARIABLE,
    package_folders,
    package_search_dirs,
)
from ..limits import current_limits
from ..reading import read_text

__all__ = ["XACRO_OPT_IN", "expand_xacro", "is_xacro", "wants_expansion"]

XACRO_OPT_IN = ("if you trust it, read it with xacro=True (Python; a scene's robot entry: "
                "'xacro: true') or --xacro (command line)")
"""How a caller asks for an expansion, for messages."""

_XACRO_ELEMENT = re.compile(r"<\s*xacro:")
_XACRO_NAMESPACE = re.compile(r"xmlns:xacro\s*=")
_SUBSTITUTION = re.compile(r"\$[{(]")
_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_CHILD = Path(__file__).with_name("_xacro_child.py")


def is_xacro(text: str) -> bool:
    """Whether the XML ``text`` is a xacro file: a ``<xacro:`` element, or the xacro namespace
    and a ``${...}`` or ``$(...)`` substitution, outside comments."""
    text = _COMMENT.sub("", text)
    if _XACRO_ELEMENT.search(text):
        return True
    return bool(_XACRO_NAMESPACE.search(text) and _SUBSTITUTION.search(text))


def wants_expansion(source: str, text: str, xacro: bool | None) -> bool:
    """Whether the file ``source`` (its ``text``) is expanded: it is xacro and the caller
    asked, by ``xacro=True`` or (``xacro=None``) by naming a ``*.xacro`` file.

    Raises :class:`FileFormatError` for xacro content the caller did not ask to expand
    (naming the file and how to opt in)."""
    if not is_xacro(text):
        return False
    if xacro or (xacro is None and source.lower().endswith(".xacro")):
        return True
    raise FileFormatError(
        "holds xacro macros, and expanding them runs the file's code (xacro evaluates its "
        f"Python expressions), so pinframes expands only when asked: {XACRO_OPT_IN}",
        file=source, field="xacro")


def expand_xacro(path: str | os.PathLike[str], *, args: Mapping[str, Any] | None = None,
                 package_dirs: Iterable[str | os.PathLike[str]] = ()) -> str:
    """The URDF (or SRDF) text that the xacro file at ``path`` expands to; calling this is
    asking for the expansion, which runs the file's code (bounded as the module says).

    ``args`` give ``$(arg NAME)`` values (strings; numbers and booleans are written as xacro
    reads them); ``package_dirs`` are searched first for ``$(find PKG)``.

    Raises
    ------
    UnsupportedFeatureError
        The ``xacro`` package is not installed (``pip install "pinframes[ros]"``).
    FileFormatError
        A package that is found nowhere (naming it and where it was looked for), an
        argument without a value, an expansion over ``max_xacro_seconds`` or
        ``max_xacro_bytes``, or any other xacro error, naming the file.
    """
    source = os.fspath(path)
    try:
        import xacro  # noqa: F401 - the child imports it; tell a missing one here
    except ImportError:
        raise UnsupportedFeatureError(
            "is a xacro file; expanding it needs the xacro package: pip install "
            "'pinframes[ros]' (or pip install xacro)", file=source) from None
    start = Path(source).resolve()
    search_dirs = package_search_dirs(package_dirs)
    packages = package_folders(search_dirs, start)
    limits = current_limits()
    request = {"path": str(start), "text": read_text(path),
               "args": {str(name): _xacro_value(value) for name, value in (args or {}).items()},
               "packages": {name: str(folders[0]) for name, folders in packages.items()},
               "max_seconds": limits.max_xacro_seconds, "max_bytes": limits.max_xacro_bytes}
    answer = _run_child(request, source)
    if "error" in answer:
        raise _located_error(answer, source, [*search_dirs, *start.parents])
    for line in dict.fromkeys(answer["said"]):
        if line.strip():
            warn_at_caller(f"{source}: xacro: {_plain(line)}")
    text: str = answer["urdf"]
    return text


def _run_child(request: dict[str, Any], source: str) -> dict[str, Any]:
    """The child's answer to ``request``; a child stopped by its bounds is an error."""
    seconds, memory = request["max_seconds"], request["max_bytes"]
    environment = {name: os.environ[name] for name in ("SYSTEMROOT",) if name in os.environ}
    try:
        finished = subprocess.run(
            [sys.executable, "-I", "-B", str(_CHILD)], input=json.dumps(request),
            capture_output=True, text=True, encoding="utf-8", env=environment,
            cwd=Path(request["path"]).parent, timeout=2 * seconds + 5, check=False)
    except subprocess.TimeoutExpired:
        finished = None
    if finished is not None and finished.returncode == 0:
        try:
            answer: dict[str, Any] = json.loads(finished.stdout)
            return answer
        except ValueError:
            pass
    over_time = getattr(signal, "SIGXCPU", None)  # the processor-time limit's signal
    if finished is None or (over_time is not None and finished.returncode == -over_time):
        raise FileFormatError(
            f"xacro: the expansion was stopped after {seconds:,} s, over the limit "
            f"max_xacro_seconds={seconds:,} (a macro that calls itself, or a huge number); "
            "if the file is trusted, raise it (limits=pinframes.Limits(max_xacro_seconds=...) "
            "or --max-xacro-seconds)", file=source, field="xacro")
    said = " ".join(finished.stderr.split())[-300:] or f"exit status {finished.returncode}"
    if "MemoryError" in said:
        return {"error": "", "package": None, "memory": True}
    raise FileFormatError(f"xacro: the expansion failed ({said}); its "
                          f"memory was bounded to max_xacro_bytes={memory:,}", file=source,
                          field="xacro")


def _plain(line: str) -> str:
    """A line xacro printed, without its terminal colour codes."""
    return re.sub(r"\x1b\[[0-9;]*m", "", line).strip()


def _xacro_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def _located_error(answer: dict[str, Any], source: str, looked: list[Path]) -> FileFormatError:
    """A pinframes error for the child's failure, naming the file (and a missing package)."""
    if answer["memory"]:
        limit = current_limits().max_xacro_bytes
        return FileFormatError(
            f"xacro: the expansion ran out of memory, over the limit max_xacro_bytes="
            f"{limit:,}; if the file is trusted, raise it (limits=pinframes.Limits("
            "max_xacro_bytes=...) or --max-xacro-bytes)", file=source, field="xacro")
    if answer["package"] is not None:
        package = answer["package"]
        where = ", ".join(map(str, looked[:4])) + (" ..." if len(looked) > 4 else "")
        return FileFormatError(
            f"$(find {package}): package {package!r} not found (no package.xml of that "
            f"name in {where}); give the folder that holds it with package_dirs=[...] "
            f"(Python), --package-dir DIR (command line) or {PACKAGE_PATH_VARIABLE}",
            file=source, field="xacro")
    message = answer["error"]
    if "Undefined substitution argument" in message:
        message += "; give it with xacro_args={...} (Python) or --xacro-arg NAME:=VALUE"
    if "environment variable" in message:
        message += ("; pinframes expands xacro without the environment: give the value as "
                    "a xacro argument instead")
    return FileFormatError(f"xacro: {message}", file=source, field="xacro")
