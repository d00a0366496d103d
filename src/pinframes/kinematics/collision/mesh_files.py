"""Where the files named in a URDF are: ``package://``, ``model://``, ``file://``, relative names.

A URDF names its meshes as ROS does: ``package://PKG/path/in/package.stl``, ``file:///abs.stl``,
an absolute path, or a path relative to the URDF's folder; Gazebo's ``model://MODEL/path``
names a model folder as ``package://`` names a package. :class:`MeshFiles` resolves them
against, in this order,

1. the search folders given by the caller (Python ``package_dirs=``, CLI ``--package-dir``),
   then those given when the robot was read (remembered with its links),
2. the folders in the ``ROS_PACKAGE_PATH`` environment variable (``os.pathsep``-separated),
   and for ``model://`` those in ``GAZEBO_MODEL_PATH``,
3. the URDF's own folder and its ancestors.

A ``package://`` name is found as ROS finds the package: by the ``<name>`` in its
``package.xml``, crawling the search folders (and ``AMENT_PREFIX_PATH``'s share folders),
then among the URDF's ancestors, the folder's name as a fallback
(:mod:`~pinframes.kinematics.collision.ros_packages`). A ``model://`` name is a model folder
of that name in a search folder or beside an ancestor. The clearance query and the 3-D page
find their meshes here, and xacro's ``$(find PKG)`` its packages (:func:`find_package`). A
``package://`` or ``model://`` name that leaves its folder (``package://PKG/../../x.stl``)
is refused (:func:`outside_its_package`): a downloaded URDF must not reach a user's other
files through it (an absolute path names what it names).

:func:`mesh_file_problem` tells why a found mesh file must not be opened: mesh readers inflate
compressed files and archives without bound (trimesh opens ``.zip``, ``.tar.gz``, ``.bz2`` by
their names, pycollada a ``.dae`` that is a zip archive by its content), so only
uncompressed files of at most ``max_decompressed_bytes`` (given by the caller: the limits
live in a higher layer) are read.
"""

from __future__ import annotations

import os
import posixpath
import stat
from collections.abc import Iterable
from pathlib import Path

from ...values.geometry import FrameGeometry
from .ros_packages import PACKAGE_PATH_VARIABLE, package_folders, package_search_dirs

__all__ = ["MODEL_PATH_VARIABLE", "PACKAGE_PATH_VARIABLE", "MeshFiles", "find_package",
           "mesh_file_problem", "mesh_files_of", "outside_its_package", "package_search_dirs"]

MODEL_PATH_VARIABLE = "GAZEBO_MODEL_PATH"
"""Environment variable with folders of Gazebo models, searched for ``model://`` names."""

_SCHEMES = ("package://", "model://")
"""URI schemes whose first path part names a folder to look for (a package, a model)."""

HOW_TO_SEARCH = (f"give the folder that holds it with package_dirs=[...] (Python), "
                 f"--package-dir DIR (command line) or {PACKAGE_PATH_VARIABLE}")
"""What a warning about a mesh that was not found tells the user to do."""


_COMPRESSED_SUFFIXES = (".zip", ".zae", ".gz", ".tgz", ".bz2", ".tbz2", ".xz", ".txz",
                        ".lzma", ".zst", ".7z", ".tar", ".rar")
_COMPRESSED_MAGIC = {b"PK\x03\x04": "zip", b"\x1f\x8b": "gzip", b"BZh": "bzip2",
                     b"\xfd7zXZ\x00": "xz", b"7z\xbc\xaf\x27\x1c": "7z",
                     b"\x28\xb5\x2f\xfd": "zstd"}


def mesh_file_problem(path: Path, max_bytes: int | None) -> str | None:
    """Why the mesh file at ``path`` is not opened, or None to open it: a compressed file or
    an archive (by its name or its first bytes), no regular file, or a file of more than
    ``max_bytes`` bytes (the limit ``max_decompressed_bytes``; None: no bound on the size)."""
    if path.name.lower().endswith(_COMPRESSED_SUFFIXES):
        return ("is compressed or an archive: mesh files are read uncompressed only "
                "(unpack it and name the mesh inside)")
    try:
        with open(path, "rb", opener=_open_without_waiting) as handle:
            info = os.fstat(handle.fileno())
            if not stat.S_ISREG(info.st_mode):
                return "is not a regular file"
            head = handle.read(8)
    except OSError as exc:
        return f"cannot be read ({exc.strerror or exc})"
    if max_bytes is not None and info.st_size > max_bytes:
        return (f"takes {info.st_size:,} bytes, over the limit max_decompressed_bytes="
                f"{max_bytes:,}; if the file is trusted, raise it "
                "(limits=pinframes.Limits(max_decompressed_bytes=...) or "
                "--max-decompressed-bytes)")
    for magic, kind in _COMPRESSED_MAGIC.items():
        if head.startswith(magic):
            return (f"is {kind}-compressed data under a mesh name: mesh files are read "
                    "uncompressed only")
    return None


def _open_without_waiting(file: str, flags: int) -> int:
    """Open for reading without waiting for a FIFO's writer (fstat then refuses it)."""
    return os.open(file, flags | getattr(os, "O_NONBLOCK", 0))


def _model_dirs() -> list[Path]:
    """The folders of ``GAZEBO_MODEL_PATH``."""
    return [Path(folder) for folder in os.environ.get(MODEL_PATH_VARIABLE, "").split(os.pathsep)
            if folder]


def find_package(name: str, search_dirs: list[Path], start: Path | None) -> Path | None:
    """The folder of package ``name`` (what ``$(find name)`` gives), found in
    ``search_dirs`` and among ``start``'s ancestors (``start``: the file that asks) as
    :func:`~pinframes.kinematics.collision.ros_packages.package_folders` says; None if
    there is none."""
    places = package_folders(search_dirs, start).get(name)
    return None if not places else places[0]


def outside_its_package(fname: str) -> str | None:
    """Why the ``package://`` or ``model://`` name ``fname`` is refused (it leaves its
    package or model folder, or names none), or None for any other name."""
    scheme = next((scheme for scheme in _SCHEMES if fname.startswith(scheme)), None)
    if scheme is None:
        return None
    package, _, inside = fname[len(scheme):].partition("/")
    if package in ("", ".", "..") or "\\" in package:
        return f"names no {scheme[:-3]} folder ({package!r} is no {scheme[:-3]} name)"
    if "\\" in inside or posixpath.isabs(inside) or posixpath.normpath(
            inside or ".").split("/")[0] == "..":
        return (f"leaves its {scheme[:-3]} {package!r} (a '..' past its folder): refused; "
                "name a file inside it, or give an absolute path")
    return None


def _model_candidates(name: str, folders: list[Path]) -> list[Path]:
    """Where model ``name`` may be: each folder itself when it bears the name, then its
    sub-folder of that name."""
    found = []
    for folder in folders:
        if folder.name == name:
            found.append(folder)
        found.append(folder / name)
    return found


class MeshFiles:
    """Resolves the mesh names of one URDF file.

    Parameters
    ----------
    urdf_path : Path or None
        The URDF file (None for a URDF given as a string: only the search folders count).
    search_dirs : list of Path
        Folders searched before the URDF's folder (see :func:`package_search_dirs`).
    """

    def __init__(self, urdf_path: Path | None, search_dirs: list[Path]) -> None:
        ancestors = [] if urdf_path is None else list(urdf_path.resolve().parents)
        self._urdf_path = urdf_path
        self._search_dirs = list(search_dirs)
        self._urdf_dirs = ancestors
        self._packages: dict[str, list[Path]] | None = None

    def _package(self, name: str) -> list[Path]:
        """The folders that may be package ``name`` (the packages are looked for once)."""
        if self._packages is None:
            self._packages = package_folders(self._search_dirs, self._urdf_path)
        return self._packages.get(name, [])

    def find(self, fname: str) -> Path | None:
        """The existing file that ``fname`` names, or None."""
        for candidate in self.candidates(fname):
            if candidate.is_file():
                return candidate
        return None

    def looked_in(self, fname: str) -> str:
        """Where ``fname`` was looked for, for a message: ``looked in A, B, C`` (the first
        four places), or that there was no folder to look in."""
        places = self.candidates(fname)
        folders = [*self._search_dirs, *self._urdf_dirs]
        if fname.startswith("package://") and not places and folders:
            return (f"no package {fname[len('package://'):].partition('/')[0]!r} (no "
                    "package.xml of that name, nor a folder of that name in a search "
                    "folder) in " + ", ".join(map(str, folders[:4]))
                    + (" ..." if len(folders) > 4 else ""))
        if not places:
            return ("no folder to look in: the robot description has no file of its own (a "
                    "URDF string, or one read from a bag)")
        return "looked in " + ", ".join(map(str, places[:4]))

    def candidates(self, fname: str) -> list[Path]:
        """Every path where ``fname`` is looked for, in order."""
        scheme = next((scheme for scheme in _SCHEMES if fname.startswith(scheme)), None)
        if scheme is not None:
            if outside_its_package(fname) is not None:
                return []
            package, _, inside = fname[len(scheme):].partition("/")
            if scheme == "package://":
                return [folder / inside for folder in self._package(package)]
            folders = [*self._search_dirs, *_model_dirs(), *self._urdf_dirs]
            return [folder / inside for folder in _model_candidates(package, folders)]
        if fname.startswith("file://"):
            return [Path(fname[len("file://"):])]
        if os.path.isabs(fname):
            return [Path(fname)]
        folders = self._urdf_dirs[:1] + self._search_dirs
        return [folder / fname for folder in folders] or [Path(fname)]


def mesh_files_of(geometry: FrameGeometry,
                  package_dirs: Iterable[str | os.PathLike[str]] = ()) -> MeshFiles:
    """The mesh names of one recorded link: looked for in ``package_dirs`` (the caller's),
    then in the folders given when its robot was read (:attr:`FrameGeometry.package_dirs`),
    then as :class:`MeshFiles` says."""
    return MeshFiles(None if geometry.urdf is None else Path(geometry.urdf),
                     package_search_dirs([*package_dirs, *geometry.package_dirs]))
