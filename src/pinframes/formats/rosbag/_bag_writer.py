"""Bags written with rosbags' own writers, atomically, in the kind the name asks for.

- ``name.bag``: a ROS 1 bag (``tf2_msgs/TFMessage`` registered from its ``.msg`` definition,
  since rosbags' Noetic store lacks it; its MD5 sum is the standard one);
- ``name.mcap``: one MCAP file, schemas in the ``ros2msg`` encoding, messages in CDR (what
  Foxglove and ``ros2 bag`` open);
- ``name.db3``: one ROS 2 SQLite file;
- any other name (no suffix, or an existing bag folder): a ROS 2 bag folder with
  ``metadata.yaml`` and one MCAP file.

Latched topics (``/tf_static``, ``/robot_description``) are offered with transient-local
durability in ROS 2 and marked latching in ROS 1, as tf2 and ``robot_state_publisher``
publish them. Stamps are ns since the epoch and cannot be negative.
"""

from __future__ import annotations

import contextlib
import os
import shutil
from functools import cache
from pathlib import Path
from types import TracebackType
from typing import Any, Literal

from ...errors import InvalidTimeError, PinframesError, UnsupportedFeatureError, WriteError
from .._paths import path_argument
from ..atomic import atomic_path, temporary_name
from ._storage import FOLDER, MCAP, ROS1, SQLITE3, not_a_bag_folder

__all__ = ["BagWriter", "check_stamps", "output_kind", "typestore"]

TF_TYPE = "tf2_msgs/msg/TFMessage"
_SUFFIXES = {".bag": ROS1, ".mcap": MCAP, ".db3": SQLITE3}
_ROS2_VERSION: Literal[8] = 8  # the oldest rosbag2 metadata version rosbags writes
MAX_STAMP_NS = (2**31 - 1) * 1_000_000_000
"""The last stamp a ROS 2 ``builtin_interfaces/Time`` holds (its ``sec`` is an int32)."""


def output_kind(path: str | os.PathLike[str]) -> str:
    """The kind of bag a path to be written names (see the module docstring)."""
    return _SUFFIXES.get(Path(path_argument(path)).suffix.lower(), FOLDER)


class BagWriter:
    """A bag being written; use it in a ``with`` block (the bag appears at its path when
    the block ends without an error, and not at all otherwise).

    Attributes
    ----------
    path : Path
        Where the bag goes.
    kind : str
        ``ROS 1 bag``, ``MCAP``, ``ROS 2 SQLite (.db3)`` or ``ROS 2 bag folder``.
    ros_version : int
        1 or 2: which message definitions and serialisation.
    types : dict
        rosbags' message classes by type name, to build messages with.
    """

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path_argument(path))
        self.kind = output_kind(self.path)
        self.ros_version = 1 if self.kind == ROS1 else 2
        self._store = typestore(self.ros_version)
        self.types: dict[str, Any] = self._store.types
        self._connections: dict[str, Any] = {}
        self._writer: Any = None
        self._atomic: Any = None
        self._scratch: Path | None = None

    def __enter__(self) -> BagWriter:
        from rosbags.rosbag1 import Writer as Ros1Writer
        from rosbags.rosbag2 import StoragePlugin
        from rosbags.rosbag2 import Writer as Ros2Writer

        self._atomic = atomic_path(self.path, folder=self.kind == FOLDER,
                                   replaceable=not_a_bag_folder)
        temporary: Path = self._atomic.__enter__()
        self._temporary = temporary
        try:
            if self.kind == ROS1:
                self._writer = Ros1Writer(temporary)
            else:  # written in a scratch folder, then moved out (the folder or its file)
                scratch = temporary.parent / temporary_name("-scratch")
                scratch.mkdir()
                self._scratch = scratch
                plugin = StoragePlugin.SQLITE3 if self.kind == SQLITE3 else StoragePlugin.MCAP
                self._writer = Ros2Writer(self._scratch_bag(), version=_ROS2_VERSION,
                                          storage_plugin=plugin)
            self._writer.open()
        except BaseException as exc:
            failure = self._write_error(exc)
            self._finish(failure)
            raise failure from (None if failure is exc else exc)
        return self

    def topic(self, name: str, message_type: str, *, latched: bool = False) -> None:
        """Declare the topic ``name`` carrying ``message_type`` (once per topic)."""
        if self.ros_version == 1:
            self._connections[name] = self._writer.add_connection(
                name, message_type, typestore=self._store, latching=1 if latched else None)
        else:
            qos = [_latched_qos()] if latched else []
            self._connections[name] = self._writer.add_connection(
                name, message_type, typestore=self._store, offered_qos_profiles=qos)

    def write(self, topic: str, stamp_ns: int, message: Any) -> None:
        """Serialise ``message`` (a rosbags message object of the topic's type) and store
        it at the receive time ``stamp_ns`` (ns since the epoch)."""
        connection = self._connections[topic]
        self.write_raw(topic, stamp_ns, self.serialise(message, connection.msgtype))

    def serialise(self, message: Any, message_type: str) -> bytes:
        """The bytes of ``message`` in this bag's serialisation (ROS 1 or CDR)."""
        if self.ros_version == 1:
            return bytes(self._store.serialize_ros1(message, message_type))
        return bytes(self._store.serialize_cdr(message, message_type))

    def write_raw(self, topic: str, stamp_ns: int, data: bytes) -> None:
        """Store serialised ``data`` on ``topic`` at the receive time ``stamp_ns``."""
        try:
            self._writer.write(self._connections[topic], stamp_ns, data)
        except Exception as exc:
            failure = self._write_error(exc)
            if failure is exc:
                raise
            raise failure from exc

    def _write_error(self, error: BaseException) -> BaseException:
        """``error`` as the :class:`~pinframes.errors.WriteError` naming the bag when the
        file system, SQLite or rosbags' writer refused to write (a full disk, a name too
        long); any other error unchanged."""
        if isinstance(error, PinframesError) or not isinstance(error, _storage_errors()):
            return error
        reason = error.strerror if isinstance(error, OSError) and error.strerror else error
        return WriteError(f"cannot write the {self.kind}: {reason}", file=self.path)

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 traceback: TracebackType | None) -> None:
        self._finish(error)

    def _scratch_bag(self, scratch: Path | None = None) -> Path:
        """The bag folder rosbags writes in the scratch folder: named as the bag to be
        written (its storage file takes that name), or ``bag`` for a storage file."""
        folder = scratch or self._scratch
        assert folder is not None
        return folder / (self.path.name if self.kind == FOLDER else "bag")

    def _finish(self, error: BaseException | None) -> None:
        """Close the bag and move it in place, or (after ``error``) drop what was written."""
        writer, self._writer = self._writer, None
        scratch, self._scratch = self._scratch, None
        try:
            if error is None and writer is not None:
                writer.close()
                if self.kind == FOLDER:
                    os.replace(self._scratch_bag(scratch), self._temporary)
                elif scratch is not None:
                    suffix = ".mcap" if self.kind == MCAP else ".db3"
                    os.replace(self._scratch_bag(scratch) / f"bag{suffix}", self._temporary)
            elif writer is not None:
                with contextlib.suppress(Exception):
                    writer.abort()
        except BaseException as failure:
            error = self._write_error(failure)
            if error is failure:
                raise
            raise error from failure
        finally:
            if scratch is not None:
                shutil.rmtree(scratch, ignore_errors=True)
            self._atomic.__exit__(None if error is None else type(error), error,
                                  None if error is None else error.__traceback__)


def check_stamps(first_ns: int, last_ns: int, ros1: bool, what: str) -> None:
    """Refuse stamps a bag cannot hold: before the epoch (a tree without a reference time
    whose times are negative), or past what a ROS time holds."""
    if first_ns < 0:
        raise InvalidTimeError(
            f"{what} starts before 1970-01-01 (a stamp of {first_ns / 1e9:g} s): bags hold "
            "stamps from the epoch on; give the tree a reference time (time_ref=, --time-ref), "
            "or write later times",
            field="times")
    limit = (2**32 - 1) * 1_000_000_000 if ros1 else MAX_STAMP_NS
    if last_ns > limit:
        raise InvalidTimeError(f"{what} ends after the last time a ROS {1 if ros1 else 2} "
                               "stamp holds", field="times")


@cache
def typestore(ros_version: int) -> Any:
    """rosbags' message types: ROS 2 (the latest definitions), or ROS 1 Noetic with
    ``tf2_msgs/TFMessage`` added."""
    try:
        from rosbags.typesys import Stores, get_types_from_msg, get_typestore
    except ImportError:
        raise UnsupportedFeatureError("writing ROS bags needs the rosbags package: "
                                      "pip install 'pinframes[ros]'") from None
    if ros_version == 2:
        return get_typestore(Stores.LATEST)
    store = get_typestore(Stores.ROS1_NOETIC)
    store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", TF_TYPE))
    return store


@cache
def _storage_errors() -> tuple[type[BaseException], ...]:
    """What writing a bag raises when its storage refuses: the file system's errors,
    SQLite's and rosbags' writer errors."""
    import sqlite3

    from rosbags.rosbag1 import WriterError as Ros1WriterError
    from rosbags.rosbag2 import WriterError as Ros2WriterError

    return OSError, sqlite3.Error, Ros1WriterError, Ros2WriterError


def _latched_qos() -> Any:
    """Reliable, transient-local, keep-last-1: the QoS of ``/tf_static`` publishers."""
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    never = QosTime(0, 0)
    return Qos(QosHistory.KEEP_LAST, 1, QosReliability.RELIABLE, QosDurability.TRANSIENT_LOCAL,
               never, never, QosLiveliness.AUTOMATIC, never, False)
