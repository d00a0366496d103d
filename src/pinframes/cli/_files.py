"""Which format a file is in, and reading or writing a tree in any supported format.

A file to be read is told by its content (:mod:`pinframes.tree_file_kind`), whatever its
name. A file to be written is told by its name: ``.asdf``, ``.urdf``, and ``.yaml``/``.yml``,
a frames.yaml when its name starts with ``frames``, else a scene.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import pinframes

from ..errors import (
    FileFormatError,
    FrameNotFoundError,
    ReadError,
    UnsupportedFeatureError,
    near_misses,
)
from ..tree import FrameTree
from ..tree_file_kind import TREE_FORMATS, tree_format_of

__all__ = ["FORMATS", "detect_format", "read_tree", "require_frames", "write_tree"]

FORMATS = TREE_FORMATS


def detect_format(path: str | Path, *, writing: bool = False) -> str:
    """One of :data:`FORMATS` for ``path``: for a file to be read told by its content
    (:func:`~pinframes.tree_file_kind.tree_format_of`), for one to be written by its name."""
    path = Path(path)
    if not writing:
        return tree_format_of(path)
    suffix = path.suffix.lower()
    if suffix == ".asdf":
        return "asdf"
    if suffix == ".urdf":
        return "urdf"
    if suffix not in (".yaml", ".yml"):
        raise FileFormatError(f"unknown file type {suffix or '(none)'!r}; expected .yaml "
                              "(scene or frames.yaml), .asdf or .urdf", file=path)
    return "frames.yaml" if path.name.lower().startswith("frames") else "scene"


def read_tree(path: str | Path, fmt: str | None = None) -> FrameTree:
    """Read the tree in ``path``, in format ``fmt`` (default: told from the file)."""
    if not Path(path).is_file():
        raise ReadError("is a folder, not a file" if Path(path).is_dir() else "no such file",
                        file=path)
    return _function("read", fmt or detect_format(path))(path)


def require_frames(tree: FrameTree, path: str | Path, *names: str | None) -> None:
    """Raise a :class:`FrameNotFoundError` naming ``path`` for a name not in ``tree``."""
    for name in names:
        if name is not None and name not in tree:
            raise FrameNotFoundError("no frame of this name in the file"
                                     + near_misses(name, tree.frames), file=path, frame=name)


def write_tree(tree: FrameTree, path: str | Path, fmt: str | None = None, *,
               schema: str | None = None, time: Any = None,
               slash_replacement: str | None = None) -> None:
    """Write ``tree`` to ``path`` in ``fmt`` (default: told from the name), atomically.

    ``schema`` is the ASDF schema version; ``time`` writes the poses at that time for the
    formats that cannot hold motion or when a static snapshot is wanted (not ASDF);
    ``slash_replacement`` stands for ``/`` in frames.yaml keys where a name's ``/`` would
    put a frame under another.
    """
    fmt = fmt or detect_format(path, writing=True)
    if schema is not None and fmt != "asdf":
        raise FileFormatError(f"--schema is for ASDF files, not {fmt}", file=path)
    if slash_replacement is not None:
        if fmt != "frames.yaml":
            raise FileFormatError(f"--slash-replacement is for frames.yaml files, not {fmt}",
                                  file=path)
        _function("write", fmt)(tree, path, time=time, slash_replacement=slash_replacement)
        return
    if fmt == "asdf":
        if time is not None:
            raise FileFormatError("--time is not for ASDF files, which keep the motion",
                                  file=path)
        _function("write", fmt)(tree, path, **({} if schema is None else {"schema": schema}))
        return
    _function("write", fmt)(tree, path, time=time)


def _function(verb: str, fmt: str) -> Callable[..., Any]:
    """``pinframes.read_asdf`` and friends, looked up when needed."""
    name = f"{verb}_{fmt.replace('.', '_')}"
    function = getattr(pinframes, name, None)
    if function is None:
        raise UnsupportedFeatureError(f"this pinframes has no {name}()")
    return function
