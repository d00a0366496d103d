"""Where the mesh files named in a URDF are: ``package://``, ``file://`` and relative names.

A URDF names its meshes as ROS does: ``package://PKG/path/in/package.stl``, ``file:///abs.stl``,
an absolute path, or a path relative to the URDF's folder. :class:`MeshFiles` resolves them
against, in this order,

1. the search folders given by the caller (Python ``package_dirs=``, CLI ``--package-dir``),
2. the folders in the ``ROS_PACKAGE_PATH`` environment variable (``os.pathsep``-separated),
3. the URDF's own folder and its ancestors.

A search folder may be a package itself (its name is ``PKG``) or hold packages as its
sub-folders (``folder/PKG``), as ``ROS_PACKAGE_PATH`` entries do. The clearance query finds
its meshes here, and so does the 3-D page (for which it also serves yourdfpy as its
``filename_handler``: names that cannot be found map to ``""``, which yourdfpy skips).
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

__all__ = ["PACKAGE_PATH_VARIABLE", "MeshFiles", "package_search_dirs"]

PACKAGE_PATH_VARIABLE = "ROS_PACKAGE_PATH"
"""Environment variable with extra search folders, as ROS users set it."""

HOW_TO_SEARCH = (f"give the folder that holds it with package_dirs=[...] (Python), "
                 f"--package-dir DIR (command line) or {PACKAGE_PATH_VARIABLE}")
"""What a warning about a mesh that was not found tells the user to do."""


def package_search_dirs(package_dirs: Iterable[str | os.PathLike[str]] = ()) -> list[Path]:
    """The caller's folders, then those of ``ROS_PACKAGE_PATH`` (empty entries ignored)."""
    from_environment = os.environ.get(PACKAGE_PATH_VARIABLE, "").split(os.pathsep)
    return [Path(folder) for folder in [*package_dirs, *from_environment] if str(folder)]


class MeshFiles:
    """Resolves the mesh names of one URDF file; remembers what it could not find.

    Parameters
    ----------
    urdf_path : Path or None
        The URDF file (None for a URDF given as a string: only the search folders count).
    search_dirs : list of Path
        Folders searched before the URDF's folder (see :func:`package_search_dirs`).
    """

    def __init__(self, urdf_path: Path | None, search_dirs: list[Path]) -> None:
        ancestors = [] if urdf_path is None else list(urdf_path.resolve().parents)
        self._search_dirs = list(search_dirs)
        self._urdf_dirs = ancestors
        self._skipped: set[str] = set()

    def __call__(self, fname: str) -> str:
        """yourdfpy's ``filename_handler``: the file for ``fname``, or ``""`` to skip it."""
        if fname in self._skipped:
            return ""
        found = self.find(fname)
        return "" if found is None else str(found)

    def skip(self, fname: str) -> None:
        """Treat ``fname`` as missing from now on (it could not be read)."""
        self._skipped.add(fname)

    def find(self, fname: str) -> Path | None:
        """The existing file that ``fname`` names, or None."""
        for candidate in self.candidates(fname):
            if candidate.is_file():
                return candidate
        return None

    def candidates(self, fname: str) -> list[Path]:
        """Every path where ``fname`` is looked for, in order."""
        if fname.startswith("package://"):
            package, _, inside = fname[len("package://"):].partition("/")
            found = []
            for folder in [*self._search_dirs, *self._urdf_dirs]:
                if folder.name == package:
                    found.append(folder / inside)
                found.append(folder / package / inside)
            return found
        if fname.startswith("file://"):
            return [Path(fname[len("file://"):])]
        if os.path.isabs(fname):
            return [Path(fname)]
        folders = self._urdf_dirs[:1] + self._search_dirs
        return [folder / fname for folder in folders] or [Path(fname)]
