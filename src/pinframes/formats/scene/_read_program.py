"""``read_program``: a scene file's cell and its ``program:`` section, as a program ready
to plan."""

from __future__ import annotations

import os
from collections.abc import Iterable

from ...program import WeldProgram
from ..limits import Limits
from ._reader import read_scene
from .program_section import scene_program

__all__ = ["read_program"]


def read_program(path: str | os.PathLike[str], *, limits: Limits | None = None,
                 package_dirs: Iterable[str | os.PathLike[str]] = ()) -> WeldProgram:
    """Read the scene at ``path`` (as :func:`read_scene` does, with ``limits`` and
    ``package_dirs``) and make its ``program:`` section a :class:`WeldProgram` on the
    scene's tree (``program.tree``); plan it with ``program.plan()``.

    Raises :class:`~pinframes.errors.FileFormatError` for a scene without a program or a
    malformed one (naming the field), and the errors of the moves, naming the move.
    """
    tree = read_scene(path, limits=limits, package_dirs=package_dirs)
    return scene_program(tree, path)
