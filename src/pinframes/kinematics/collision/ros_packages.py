"""ROS packages found as ROS finds them: folders that hold a ``package.xml``, by its ``<name>``.

A package is named by the ``<name>`` of its ``package.xml``, not by its folder: the folder
``panda_description`` of moveit_resources holds the package
``moveit_resources_panda_description``, a git clone ``Universal_Robots_ROS2_Description``
the package ``ur_description``. :func:`package_folders` maps every package name to the
folders that may be it, first the one ``$(find PKG)`` gives, in this order:

1. the search folders (the caller's, then ``ROS_PACKAGE_PATH``'s, then the ``share``
   folder of each ``AMENT_PREFIX_PATH`` prefix), crawled as ROS crawls a workspace: down
   to :data:`MAX_CRAWL_DEPTH` folders deep, at most :data:`MAX_CRAWL_FOLDERS` folders per
   search folder, not into a package (packages do not nest), a hidden folder or one
   marked ``COLCON_IGNORE``, ``CATKIN_IGNORE`` or ``AMENT_IGNORE``; then, as a fallback by
   folder name, a search folder itself or its sub-folder of that name (a folder of meshes
   needs no ``package.xml`` when the caller names its parent);
2. the asking file's ancestor folders and their sub-folders that hold a ``package.xml``:
   by its name, then by the folder's name. A folder without a ``package.xml`` is never a
   package found among the ancestors, so ``$(find etc)`` is not ``/etc``.

A mesh name is looked for in each folder of its package in turn (a search folder given
with a few meshes of a package comes before the package found beside the URDF).
"""

from __future__ import annotations

import functools
import os
import re
import stat
from collections.abc import Iterable
from pathlib import Path

from ...errors import warn_at_caller

__all__ = ["MAX_CRAWL_DEPTH", "MAX_CRAWL_FOLDERS", "PACKAGE_PATH_VARIABLE",
           "PREFIX_PATH_VARIABLE", "package_folders", "package_name", "package_search_dirs"]

PACKAGE_PATH_VARIABLE = "ROS_PACKAGE_PATH"
"""Environment variable with extra search folders, as ROS 1 users set it."""

PREFIX_PATH_VARIABLE = "AMENT_PREFIX_PATH"
"""Environment variable with ROS 2 install prefixes; packages are in each ``share`` folder."""

MAX_CRAWL_DEPTH = 6
"""Folders below a search folder that the crawl goes down (a workspace's
``src/repository/group/package`` is 3)."""

MAX_CRAWL_FOLDERS = 20_000
"""Folders looked into per search folder; past it the crawl stops with a warning."""

_IGNORE_MARKERS = ("COLCON_IGNORE", "CATKIN_IGNORE", "AMENT_IGNORE")
_MANIFEST = "package.xml"
_MANIFEST_BYTES = 65_536
_COMMENT = re.compile(r"<!--.*?-->", re.DOTALL)
_NAME = re.compile(r"<name>\s*([A-Za-z0-9_][A-Za-z0-9_.-]*)\s*</name>")


def package_search_dirs(package_dirs: Iterable[str | os.PathLike[str]] = ()) -> list[Path]:
    """The caller's folders, then those of ``ROS_PACKAGE_PATH``, then the ``share`` folders
    of ``AMENT_PREFIX_PATH`` (empty entries ignored)."""
    paths = os.environ.get(PACKAGE_PATH_VARIABLE, "").split(os.pathsep)
    prefixes = os.environ.get(PREFIX_PATH_VARIABLE, "").split(os.pathsep)
    shares = [os.path.join(prefix, "share") for prefix in prefixes if prefix]
    return [Path(folder) for folder in [*package_dirs, *paths, *shares] if str(folder)]


def package_name(folder: Path) -> str | None:
    """The ``<name>`` in ``folder/package.xml``; None without a readable one (a FIFO, a
    file over 64 KiB or one without a name is no manifest)."""
    try:
        descriptor = os.open(folder / _MANIFEST, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError:
        return None
    with open(descriptor, "rb") as handle:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            return None
        head = handle.read(_MANIFEST_BYTES + 1)
    if len(head) > _MANIFEST_BYTES:
        return None
    found = _NAME.search(_COMMENT.sub("", head.decode("utf-8", "replace")))
    return None if found is None else found.group(1)


def package_folders(search_dirs: list[Path], start: Path | None) -> dict[str, list[Path]]:
    """Every package name to the folders that may be it, in the order the module says (the
    first is the package); ``start`` is the file that asks (its ancestors are looked in),
    None for none."""
    found: dict[str, list[Path]] = {}

    def add(name: str, place: Path) -> None:
        places = found.setdefault(name, [])
        if place not in places:
            places.append(place)

    for folder in search_dirs:
        for name, place in _crawled(folder.resolve()).items():
            add(name, place)
    for folder in search_dirs:
        for place in [folder, *_subfolders(folder)]:
            add(place.name, place)
    ancestors = [] if start is None else list(start.resolve().parents)
    with_manifest: list[Path] = []
    for ancestor in ancestors:
        for folder in [ancestor, *_subfolders(ancestor)]:
            declared = package_name(folder)
            if declared is not None:
                add(declared, folder)
                with_manifest.append(folder)
    for place in with_manifest:
        add(place.name, place)
    return found


def _subfolders(folder: Path) -> list[Path]:
    """The folders in ``folder`` (none if it cannot be listed), by name."""
    try:
        with os.scandir(folder) as entries:
            return sorted(Path(entry.path) for entry in entries if _is_folder(entry))
    except OSError:
        return []


def _is_folder(entry: os.DirEntry) -> bool:
    try:
        return entry.is_dir()
    except OSError:
        return False


def _crawled(folder: Path) -> dict[str, Path]:
    """The packages below ``folder`` (remembered until the folder changes)."""
    try:
        changed = folder.stat().st_mtime_ns
    except OSError:
        return {}
    return _crawl(folder, changed)


@functools.lru_cache(maxsize=64)
def _crawl(folder: Path, changed: int) -> dict[str, Path]:
    """Breadth first from ``folder``: a folder with a ``package.xml`` is a package (its
    sub-folders are not looked into); ``changed`` (its modification time) keys the cache."""
    found: dict[str, Path] = {}
    level, seen = [folder], {folder}
    for depth in range(MAX_CRAWL_DEPTH + 1):
        below: list[Path] = []
        for place in level:
            if len(seen) > MAX_CRAWL_FOLDERS:
                warn_at_caller(f"{folder}: stopped looking for ROS packages after "
                               f"{MAX_CRAWL_FOLDERS:,} folders; give the folder that holds "
                               "the package itself")
                return found
            name = package_name(place)
            if name is not None:
                found.setdefault(name, place)
                continue
            if depth == MAX_CRAWL_DEPTH or any((place / marker).exists()
                                               for marker in _IGNORE_MARKERS):
                continue
            for inner in _subfolders(place):
                real = inner.resolve()
                if not inner.name.startswith(".") and real not in seen:
                    seen.add(real)
                    below.append(inner)
        level = below
    return found
