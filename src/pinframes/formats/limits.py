"""Bounds on the work a file may ask of a reader, so that a tiny hostile file fails fast.

A 600-byte YAML alias bomb expands to billions of nodes, an 848-byte ASDF time grid with a
1 ns step asks for 500 million samples, a 6 MB NPZ inflates to 6 GB, a 400-byte URDF of
nested XML entities describes millions of elements. Readers check these
bounds *before* they expand, allocate or decompress, and refuse with a
:class:`~pinframes.errors.FileFormatError` naming the file, the limit and how to raise it.
No real file comes near the defaults (the largest shipped or sample file uses well under
1 % of each); a user who needs more passes ``limits=Limits(...)`` to a reader, or the
matching ``--max-...`` option to the ``pinframes`` command.

Readers called from within another reader (the layers and trajectories of a scene) use the
limits of the outermost call: they are kept in a context variable for its duration, so each
thread (and each asyncio task) has its own.
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields
from typing import Any, TypeVar, cast

from ..errors import ArgumentTypeError, FileFormatError
from ..kinematics.collision.mesh_reader import MAX_TRIANGLES

__all__ = ["Limits", "checked_limits", "current_limits", "exceeded", "reader_with_limits",
           "using_limits"]

_Reader = TypeVar("_Reader", bound=Callable[..., Any])


@dataclass(frozen=True)
class Limits:
    """What one read may cost at most.

    Attributes
    ----------
    max_samples : int
        Time samples of one frame or joint trajectory: keyframes, the points of a regular
        time grid (``{start, end, freq}``), rows of a joint trajectory file, the transforms
        of a frame or joint states of a joint in a ROS bag.
    max_yaml_nodes : int
        YAML nodes of a document after expanding aliases (``*name`` counts the whole node
        it repeats, each time it is used); scalars, lists and mappings count one each.
    max_decompressed_bytes : int
        Bytes of all arrays of one NPZ file once decompressed, or of all that the arrays of
        an ASDF file's hierarchy decode to: each binary block once, at its decompressed
        size, and each array read from it; bytes of the messages read from a ROS bag, and
        (counted apart) all that its compressed chunks, messages or files inflate to.
    max_depth : int
        Nesting depth of a YAML document (lists and mappings inside each other), path
        segments of a frames.yaml key (``a/b/c`` has 3), and nesting depth of the XML
        elements of a URDF (``<robot><link><visual>`` has 3).
    max_xml_elements : int
        XML elements of a URDF or SRDF file (every start tag counts one; the largest robot
        of example-robot-data has 3,851), and the joints of an SRDF's groups once expanded
        (each group counts its joints).
    max_triangles : int
        Triangles of one mesh file after instancing (a COLLADA node instanced twice counts
        its triangles twice), counted before any is built, and of all the meshes of one
        clearance or 3-D page (a mesh counts once per link that uses it): past it the
        clearance is an error naming the frame, the 3-D page leaves the mesh out with a
        warning.
    max_xacro_seconds : int
        Seconds of processor time one xacro expansion may take (it runs in a child
        process, stopped after twice as many seconds of clock time); the largest xacro
        robot of the tests expands in 0.3 s.
    max_xacro_bytes : int
        Bytes of memory (address space) of the child process that expands a xacro file.
    """

    max_samples: int = 2_000_000
    max_yaml_nodes: int = 200_000
    max_decompressed_bytes: int = 1024**3
    max_depth: int = 1_000
    max_xml_elements: int = 1_000_000
    max_triangles: int = MAX_TRIANGLES
    max_xacro_seconds: int = 20
    max_xacro_bytes: int = 1024**3

    def __post_init__(self) -> None:
        for item in fields(self):
            value = getattr(self, item.name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ArgumentTypeError(f"expected a positive whole number, got {value!r}",
                                        field=item.name)


_DEFAULT = Limits()
_CURRENT: contextvars.ContextVar[Limits | None] = contextvars.ContextVar("pinframes_limits",
                                                                         default=None)


def current_limits() -> Limits:
    """The limits of the read in progress (the defaults outside any read)."""
    return _CURRENT.get() or _DEFAULT


@contextlib.contextmanager
def using_limits(limits: Limits | None) -> Iterator[Limits]:
    """Within this block :func:`current_limits` is ``limits`` (None: keep the current ones)."""
    limits = checked_limits(limits)
    token = _CURRENT.set(limits)
    try:
        yield limits
    finally:
        _CURRENT.reset(token)


def checked_limits(limits: Limits | None) -> Limits:
    """``limits``, or :func:`current_limits` for None; anything else is an
    :class:`~pinframes.errors.ArgumentTypeError`."""
    if limits is None:
        return current_limits()
    if not isinstance(limits, Limits):
        raise ArgumentTypeError(f"expected a pinframes.Limits, got {type(limits).__name__}",
                                field="limits")
    return limits


def reader_with_limits(reader: _Reader) -> _Reader:
    """Decorate a reader whose keyword argument ``limits`` applies to the whole read."""

    @functools.wraps(reader)
    def read(*args: Any, **kwargs: Any) -> Any:
        with using_limits(kwargs.get("limits")):
            return reader(*args, **kwargs)

    return cast(_Reader, read)


def exceeded(name: str, found: str, *, field: str | None = None,
             frame: str | None = None) -> FileFormatError:
    """The error for a file that needs more than the limit ``name`` allows."""
    limit = getattr(current_limits(), name)
    option = "--" + name.replace("_", "-")
    return FileFormatError(
        f"{found}, over the limit {name}={limit:,}; if the file is trusted, raise it "
        f"(limits=pinframes.Limits({name}=...) or {option})", frame=frame, field=field)
