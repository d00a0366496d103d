"""Which kind of ROS bag a path holds, and its raw messages, read with rosbags.

Four kinds (docs/ros-bags.md): a ROS 1 ``.bag`` file, a ROS 2 bag folder (``metadata.yaml`` beside
its ``.db3`` or ``.mcap`` files), and the two ROS 2 storage files on their own (an MCAP
file, a SQLite ``.db3`` file). Files are told by their first bytes, never by their names.
Whatever rosbags raises on a truncated or corrupt bag becomes a
:class:`~pinframes.errors.FileFormatError` naming the bag. Compressed chunks, messages and
files are inflated within ``max_decompressed_bytes`` (:mod:`._inflation`), and a ``.db3``
file's schema is checked before rosbags reads a row (:mod:`._sqlite_schema`).
"""

from __future__ import annotations

import contextlib
import importlib
import os
import struct
import tempfile
import zlib
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import TracebackType
from typing import Any

import yaml

from ...errors import FileFormatError, PinframesError, ReadError, UnsupportedFeatureError
from .._paths import path_argument
from ..reading import InputFile
from ._inflation import InflationBudget, bound_rosbags_chunks
from ._sqlite_schema import check_stored_values

__all__ = ["BAG_KINDS", "BagTopic", "OpenBag", "bag_files", "bag_kind", "bag_kind_of_head",
           "not_a_bag_folder", "rosbags_missing"]

ROS1 = "ROS 1 bag"
MCAP = "MCAP"
SQLITE3 = "ROS 2 SQLite (.db3)"
FOLDER = "ROS 2 bag folder"
BAG_KINDS = (ROS1, MCAP, SQLITE3, FOLDER)
"""The kinds of bags, as messages name them."""

METADATA_FILE = "metadata.yaml"
_STORAGES = {"sqlite3": SQLITE3, "mcap": MCAP}
_MAGIC = ((b"#ROSBAG V2.0\n", ROS1), (b"\x89MCAP0\r\n", MCAP), (b"SQLite format 3\x00", SQLITE3))
HEAD_BYTES = 16
"""How many first bytes tell a bag file's kind."""


def bag_kind_of_head(head: bytes) -> str | None:
    """The kind of bag file whose first bytes are ``head`` (at least :data:`HEAD_BYTES`),
    or None."""
    return next((kind for magic, kind in _MAGIC if head.startswith(magic)), None)


def bag_kind(path: str | os.PathLike[str]) -> str:
    """The kind of bag at ``path`` (one of :data:`BAG_KINDS`).

    Raises
    ------
    ReadError
        Nothing at ``path``.
    FileFormatError
        A folder without ``metadata.yaml``, or a file that is no bag.
    """
    file = Path(path_argument(path))
    if file.is_dir():
        if not (file / METADATA_FILE).is_file():
            raise FileFormatError(f"a folder without {METADATA_FILE}: not a ROS 2 bag",
                                  file=file)
        return FOLDER
    try:
        with open(file, "rb") as handle:
            head = handle.read(HEAD_BYTES)
    except FileNotFoundError:
        raise ReadError("no such file", file=file) from None
    except OSError as exc:
        raise ReadError(f"cannot read: {exc.strerror or exc}", file=file) from None
    kind = bag_kind_of_head(head)
    if kind is None:
        raise FileFormatError("not a ROS bag: a ROS 1 .bag starts with '#ROSBAG V2.0', an "
                              "MCAP file with its magic bytes, a .db3 file is SQLite",
                              file=file)
    return kind


def bag_files(path: str | os.PathLike[str]) -> list[Path]:
    """The files a bag is read from: the file itself, or a folder's ``metadata.yaml`` and
    the storage files it names (those it names but that are missing too)."""
    file = Path(path_argument(path))
    if not file.is_dir():
        return [file]
    metadata = _folder_metadata(file)
    return [file / METADATA_FILE] + [file / name for name in _storage_names(file, metadata)]


def not_a_bag_folder(folder: Path) -> str | None:
    """Why the existing folder ``folder`` is not a ROS 2 bag that a writer may replace whole
    (None when it is one): its ``metadata.yaml`` must be a regular file that parses as
    rosbag2 metadata, and every other entry a regular file that metadata lists as storage.
    The reason names the first entry that is not the bag's."""
    metadata = folder / METADATA_FILE
    if metadata.is_symlink() or not metadata.is_file():
        return f"it holds no regular file {METADATA_FILE}"
    try:
        storage = set(_storage_names(folder, _folder_metadata(folder)))
    except PinframesError as exc:
        return f"its {METADATA_FILE} is not rosbag2 metadata ({exc.message})"
    for entry in sorted(os.scandir(folder), key=lambda entry: entry.name):
        if entry.name == METADATA_FILE:
            continue
        if entry.name not in storage or not entry.is_file(follow_symlinks=False):
            return f"{entry.name!r} is not one of the storage files its {METADATA_FILE} lists"
    return None


def rosbags_missing() -> UnsupportedFeatureError:
    """The error for a bag read without the rosbags package."""
    return UnsupportedFeatureError("reading ROS bags needs the rosbags package: "
                                   "pip install 'pinframes[ros]'")


@dataclass(frozen=True)
class BagTopic:
    """A topic of a bag: its message type (``tf2_msgs/msg/TFMessage``), message count and
    the MD5 sum of its definition (ROS 1; empty otherwise)."""

    name: str
    message_type: str
    count: int
    md5sum: str


class OpenBag:
    """A bag open for reading; use it in a ``with`` block.

    Attributes
    ----------
    path : Path
        The bag (file or folder).
    kind : str
        One of :data:`BAG_KINDS`.
    ros_version : int
        1 (ROS 1 serialisation) or 2 (CDR).
    topics : dict of str to BagTopic
        The bag's topics by name.
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path_argument(path))
        self.kind = bag_kind(self.path)
        self.ros_version = 1 if self.kind == ROS1 else 2
        self._folder = _check_folder(self.path) if self.kind == FOLDER else None
        self._reader: Any = None
        self._message_codec: str | None = None
        self._budget = InflationBudget(self.path)
        self._cleanup = contextlib.ExitStack()
        self.topics: dict[str, BagTopic] = {}

    def __enter__(self) -> OpenBag:
        try:
            from rosbags import rosbag1, rosbag2
        except ImportError:
            raise rosbags_missing() from None
        bound_rosbags_chunks()
        self._cleanup.enter_context(self._budget.active())
        try:
            with self._translated_errors("cannot open it"):
                self._reader = self._opened(rosbag1, rosbag2)
        except BaseException:
            self._cleanup.close()
            raise
        topics: dict[str, BagTopic] = {}
        for connection in self._reader.connections:
            known = topics.get(connection.topic)
            count = connection.msgcount + (known.count if known else 0)
            topics[connection.topic] = BagTopic(connection.topic, connection.msgtype, count,
                                                connection.digest if self.kind == ROS1 else "")
        self.topics = dict(sorted(topics.items()))
        return self

    def _opened(self, rosbag1: Any, rosbag2: Any) -> Any:
        """rosbags' reader of the bag, open; a compressed folder's files inflated first,
        its compressed messages left for :meth:`messages` to inflate."""
        if self.kind == ROS1:
            reader = rosbag1.Reader(self.path)
        elif self.kind == FOLDER:
            reader = rosbag2.Reader(self._uncompressed_folder())
        else:  # a storage file on its own, whatever its name
            if self.kind == SQLITE3:
                check_stored_values(self.path, self.path)
            suffix = ".mcap" if self.kind == MCAP else ".db3"
            reader = rosbag2.Reader.STORAGE_PLUGINS[suffix](self.path)
        reader.open()
        self._cleanup.callback(reader.close)
        if self.kind == FOLDER and reader.storage.metadata.compression_mode == "message":
            self._message_codec = "zstd"
            reader.storage.metadata = reader.storage.metadata._replace(compression_mode=None)
        return reader

    def _uncompressed_folder(self) -> Path:
        """The bag folder, or (``compression_mode: file``) a temporary copy of it whose
        files are inflated within the budget."""
        assert self._folder is not None
        names = _storage_names(self.path, self._folder)
        if str(self._folder.get("compression_mode", "")).lower() != "file":
            if self._folder.get("storage_identifier") == "sqlite3":
                for name in names:
                    check_stored_values(self.path / name, self.path)
            return self.path
        codec = str(self._folder.get("compression_format", ""))
        if codec != "zstd":
            raise FileFormatError(f"files compressed with {codec!r}; ROS 2 compresses them "
                                  "with zstd", file=self.path / METADATA_FILE,
                                  field="rosbag2_bagfile_information.compression_format")
        copy = Path(self._cleanup.enter_context(
            tempfile.TemporaryDirectory(prefix="pinframes-bag-")))
        inflated = [Path(name).stem for name in names]
        for name, target in zip(names, inflated, strict=True):
            self._budget.inflate_file(self.path / name, copy / target, codec)
            if self._folder.get("storage_identifier") == "sqlite3":
                check_stored_values(copy / target, self.path)
        metadata = {**self._folder, "relative_file_paths": inflated, "compression_mode": "",
                    "compression_format": ""}
        (copy / METADATA_FILE).write_text(
            yaml.safe_dump({"rosbag2_bagfile_information": metadata}), encoding="utf-8")
        return copy

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 traceback: TracebackType | None) -> None:
        self._reader = None
        try:
            self._cleanup.close()
        except Exception:  # closing a corrupt bag may fail too; the first error counts
            if kind is None:
                raise

    def messages(self, topics: Sequence[str]) -> Iterator[tuple[str, int, bytes]]:
        """``(topic, receive time in ns, serialised message)`` of ``topics``, in the bag's
        order (receive time)."""
        connections = [c for c in self._reader.connections if c.topic in set(topics)]
        if not connections:
            return
        with self._translated_errors("a corrupt message"):
            for connection, received_ns, raw in self._reader.messages(connections):
                if self._message_codec is not None:
                    raw = self._budget.inflate(raw, self._message_codec)
                yield connection.topic, received_ns, bytes(raw)

    def _translated_errors(self, what: str) -> _TranslatedErrors:
        return _TranslatedErrors(self.path, what)


class _TranslatedErrors:
    """Turns what rosbags raises on a broken bag into a FileFormatError naming it."""

    def __init__(self, path: Path, what: str) -> None:
        self.path = path
        self.what = what

    def __enter__(self) -> None:
        return None

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 traceback: TracebackType | None) -> None:
        if (error is None or isinstance(error, PinframesError)
                or not isinstance(error, _broken_bag_errors())):
            return
        if isinstance(error, FileNotFoundError):
            raise ReadError(f"a file of the bag is missing: {error}", file=self.path) from None
        detail = str(error).strip() or type(error).__name__
        if isinstance(error, MemoryError):
            detail = "a record length larger than the memory (corrupt length?)"
        if isinstance(error, AssertionError):  # rosbags asserts its records match the index
            detail = ("a record disagrees with the bag's index (a corrupt time, size or "
                      "field)")
        raise FileFormatError(f"{self.what} (truncated or corrupt bag?): {detail}",
                              file=self.path) from None


def _broken_bag_errors() -> tuple[type[BaseException], ...]:
    """The exceptions rosbags and the libraries below it raise on bytes that are not a
    well-formed bag."""
    from rosbags.rosbag1 import ReaderError as Ros1ReaderError
    from rosbags.rosbag2 import ReaderError as Ros2ReaderError

    broken: list[type[BaseException]] = [
        Ros1ReaderError, Ros2ReaderError, OSError, EOFError, ValueError, KeyError, IndexError,
        ArithmeticError, TypeError, AttributeError, struct.error, zlib.error,
        RuntimeError,  # lz4's decompression errors
        AssertionError,  # rosbags' ROS 1 reader checks records against its index by assert
        MemoryError]  # rosbags reads a record whose corrupt length asks for terabytes
    for module, name in (("apsw", "Error"), ("backports.zstd", "ZstdError"),
                         ("compression.zstd", "ZstdError")):  # rosbags' SQLite and zstd
        try:
            broken.append(getattr(importlib.import_module(module), name))
        except ImportError:
            pass
    return tuple(broken)


def _folder_metadata(folder: Path) -> dict[str, Any]:
    """The ``rosbag2_bagfile_information`` of a bag folder, read with pinframes' own YAML
    reader (its limits apply)."""
    content = InputFile(folder / METADATA_FILE).yaml()
    information = (content.get("rosbag2_bagfile_information")
                   if isinstance(content, dict) else None)
    if not isinstance(information, dict):
        raise FileFormatError("expected a mapping 'rosbag2_bagfile_information'",
                              file=folder / METADATA_FILE, field="rosbag2_bagfile_information")
    return information


def _storage_names(folder: Path, information: dict[str, Any]) -> list[str]:
    names = information.get("relative_file_paths")
    if not isinstance(names, list) or not all(isinstance(name, str) for name in names):
        raise FileFormatError("expected a list of file names", file=folder / METADATA_FILE,
                              field="rosbag2_bagfile_information.relative_file_paths")
    return [Path(name).name for name in names]


def _check_folder(folder: Path) -> dict[str, Any]:
    """The metadata of a bag folder that names a storage rosbags reads and files that
    exist."""
    information = _folder_metadata(folder)
    storage = information.get("storage_identifier")
    if storage not in _STORAGES:
        raise FileFormatError(
            f"unknown storage {storage!r}; pinframes reads ROS 2 bags stored as "
            f"{' or '.join(_STORAGES)}", file=folder / METADATA_FILE,
            field="rosbag2_bagfile_information.storage_identifier")
    missing = [name for name in _storage_names(folder, information)
               if not (folder / name).is_file()]
    if missing:
        raise ReadError(f"the bag's files {', '.join(missing)} are missing", file=folder)
    return information
