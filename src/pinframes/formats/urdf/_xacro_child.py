"""The child process that expands one xacro file (run as a script by ``_xacro.py``).

It reads one JSON request from standard input (``path``, ``text``, ``args``, ``packages``:
package name -> folder, ``max_seconds``, ``max_bytes``), bounds its own processor time and
address space, expands the text with the ``xacro`` package and writes one JSON answer to
standard output: ``{"urdf": text, "said": [lines xacro printed]}`` or ``{"error": message,
"package": name or None, "memory": bool}``. It imports nothing of pinframes, and its
parent gives it no environment variables: ``$(env NAME)`` is an error and
``$(optenv NAME DEFAULT)`` its default. ``$(find PKG)`` is answered from ``packages``
only, and a file an include or ``load_yaml`` names must be a regular file (a FIFO would
block the read forever).
"""

from __future__ import annotations

import io
import json
import os
import stat
import sys
from contextlib import redirect_stderr
from typing import Any

_RESERVE = bytearray(4 << 20)  # given back on MemoryError, so the answer can be written


class _PackageNotFound(Exception):
    def __init__(self, package: str) -> None:
        super().__init__(package)
        self.package = package


def _bound(max_seconds: int, max_bytes: int) -> None:
    """Limit this process's processor time and address space (where the system can)."""
    try:
        import resource
    except ImportError:  # Windows: the parent's clock alone bounds the time
        return
    resource.setrlimit(resource.RLIMIT_CPU, (max_seconds, max_seconds + 1))
    resource.setrlimit(resource.RLIMIT_AS, (max_bytes, max_bytes))


def _regular_file(file: Any, mode: str = "r", *args: Any, **kwargs: Any) -> Any:
    """``open`` for xacro's reads: a FIFO, device or folder is refused without waiting."""
    descriptor = os.open(file, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    if not stat.S_ISREG(os.fstat(descriptor).st_mode):
        os.close(descriptor)
        raise OSError(0, "is not a regular file (xacro reads files only)", os.fspath(file))
    if hasattr(os, "O_NONBLOCK"):  # reads of a regular file do not wait anyway
        os.set_blocking(descriptor, True)
    return open(descriptor, mode, *args, **kwargs)


def _expand(request: dict[str, Any]) -> dict[str, Any]:
    import xacro
    from xacro import substitution_args

    packages: dict[str, str] = request["packages"]

    def find(package: str) -> str:
        if package not in packages:
            raise _PackageNotFound(package)
        return packages[package]

    substitution_args._eval_find = find
    substitution_args._eval_dict["find"] = find
    xacro.open = _regular_file  # the module's reads (includes, load_yaml) go through it
    said = io.StringIO()
    with redirect_stderr(said):
        xacro.init_stacks(request["path"])
        document = xacro.parse(request["text"])
        xacro.process_doc(document, mappings=request["args"])
        text = document.toprettyxml(indent="  ")
    return {"urdf": text, "said": said.getvalue().splitlines()}


def _failure(error: BaseException) -> dict[str, Any]:
    """The answer for what the expansion raised (xacro wraps errors in its own)."""
    cause: BaseException | None = error
    plain: BaseException | None = None  # the cause that says what went wrong plainly
    seen = set()
    while cause is not None and id(cause) not in seen:
        seen.add(id(cause))
        if isinstance(cause, _PackageNotFound):
            return {"error": str(error), "package": cause.package, "memory": False}
        if isinstance(cause, MemoryError):
            return {"error": "", "package": None, "memory": True}
        if plain is None and (isinstance(cause, OSError)
                              or type(cause).__name__ == "SubstitutionException"):
            plain = cause
        cause = getattr(cause, "exc", None) or cause.__cause__ or cause.__context__
    if isinstance(plain, OSError):  # an include or YAML file that cannot be read
        message = f"{plain.filename}: {plain.strerror}"
    else:  # a $(env) or $(arg) that has no value says so plainly; xacro's own message
        message = str(plain if plain is not None else error)
    return {"error": " ".join(message.split()) or type(error).__name__, "package": None,
            "memory": False}


def main() -> None:
    global _RESERVE
    request = json.loads(sys.stdin.read())
    _bound(request["max_seconds"], request["max_bytes"])
    try:
        answer = _expand(request)
    except MemoryError:
        _RESERVE = bytearray()
        answer = {"error": "", "package": None, "memory": True}
    except BaseException as error:  # every failure is the parent's to report
        _RESERVE = bytearray()
        answer = _failure(error)
    sys.stdout.write(json.dumps(answer))


if __name__ == "__main__":
    main()
