"""Exceptions raised by pinframes, and the warnings it gives.

Every error carries, where known, the ``file`` it came from, the ``frame`` or ``joint`` it
concerns and the ``field`` that is wrong, and puts them at the front of its message::

    scene.yaml: frame 'torch': field 'pose.yaw': expected a number, got 'abc'
    run.csv: joint 'robot/joint_3': field 'line 4': expected a number, got 'abc'

Each class also subclasses the built-in exception a caller would naturally catch
(``ValueError``, ``KeyError``, ``TypeError``, ``OSError``).
"""

from __future__ import annotations

import difflib
import os
import sys
import warnings
from collections.abc import Iterable
from types import FrameType

__all__ = [
    "ArgumentTypeError",
    "BagWarning",
    "BrokenMimicWarning",
    "CollisionError",
    "DataNotFoundError",
    "ExtrapolationError",
    "ExtrapolationWarning",
    "FileFormatError",
    "FrameExistsError",
    "FrameNotFoundError",
    "FramesYamlWarning",
    "GeometryError",
    "GeometryWarning",
    "InvalidDataError",
    "InvalidPoseError",
    "InvalidTimeError",
    "JointError",
    "JointJumpError",
    "JointLimitWarning",
    "JointNotFoundError",
    "JointSpeedError",
    "JointWithoutSamplesWarning",
    "ManifestWarning",
    "NameNotFoundError",
    "PinframesError",
    "ReadError",
    "ReferenceTimeError",
    "TargetNotReachedError",
    "TreeStructureError",
    "UnitWarning",
    "UnsupportedFeatureError",
    "WriteError",
    "joint_not_found",
    "near_misses",
    "warn_at_caller",
]


class PinframesError(Exception):
    """Base class of every pinframes error.

    Attributes
    ----------
    message : str
        What is wrong, without the location prefix.
    file : str or None
        The file the bad input came from.
    frame : str or None
        The frame (or key, link) concerned.
    joint : str or None
        The robot joint concerned (a joint trajectory's column, a URDF joint).
    field : str or None
        The field within that frame or joint, dotted for nested fields (``pose.yaw``).
    """

    def __init__(
        self,
        message: str,
        *,
        file: str | os.PathLike[str] | None = None,
        frame: str | None = None,
        field: str | None = None,
        joint: str | None = None,
    ) -> None:
        self.message = message
        self.file = os.fspath(file) if file is not None else None
        self.frame = frame
        self.joint = joint
        self.field = field
        super().__init__(str(self))

    def __str__(self) -> str:
        parts = []
        if self.file is not None:
            parts.append(self.file)
        if self.frame is not None:
            parts.append(f"frame {self.frame!r}")
        if self.joint is not None:
            parts.append(f"joint {self.joint!r}")
        if self.field is not None:
            parts.append(f"field {self.field!r}")
        parts.append(self.message)
        return ": ".join(parts)

    def located(
        self,
        *,
        file: str | os.PathLike[str] | None = None,
        frame: str | None = None,
        field: str | None = None,
        joint: str | None = None,
    ) -> PinframesError:
        """Return a copy of this error with missing location parts filled in."""
        return type(self)(
            self.message,
            file=self.file if self.file is not None else file,
            frame=self.frame if self.frame is not None else frame,
            field=self.field if self.field is not None else field,
            joint=self.joint if self.joint is not None else joint,
        )


class NameNotFoundError(PinframesError, KeyError):
    """A name the tree does not hold: a frame, a robot joint or a data set. Every lookup
    that misses raises one of its kinds below; catch this class (or ``KeyError``) for all."""


class FrameNotFoundError(NameNotFoundError):
    """A frame name that the tree does not hold."""


class FrameExistsError(PinframesError, ValueError):
    """A frame name that the tree already holds."""


class TreeStructureError(PinframesError, ValueError):
    """An operation that would break the tree: a cycle, removing the root, orphaned children."""


class InvalidPoseError(PinframesError, ValueError):
    """A pose that is not a rigid transform: wrong shape, non-finite, not a rotation."""


class InvalidDataError(PinframesError, ValueError):
    """Points, vectors or other measured or spatial data that is not what it must be: wrong
    shape, non-finite values, bad triangles or attributes."""


class InvalidTimeError(PinframesError, ValueError):
    """Times that cannot be read, are not strictly increasing or do not match the data."""


class ReferenceTimeError(PinframesError, ValueError):
    """Reference times that cannot be combined (weldx ``get_cs`` rules)."""


class ExtrapolationError(PinframesError, ValueError):
    """A query time outside a frame's keyframes under ``extrapolation="error"``, or an
    unknown extrapolation policy."""


class JointError(PinframesError, ValueError):
    """A robot joint that is unknown, mis-specified or driven with bad values."""


class JointNotFoundError(NameNotFoundError, JointError):
    """A robot joint name that the tree does not hold: a :class:`NameNotFoundError` (a
    ``KeyError``) like every missed lookup, and still a :class:`JointError` (a
    ``ValueError``), which unknown joint names raised before."""


class JointJumpError(JointError):
    """A step between two samples of ``solve_joints(..., strict=True)`` that jumps (the
    message names the time, the joint and the step against the path's usual step)."""


class JointSpeedError(JointError):
    """A joint that ``solve_joints(..., strict=True)`` moves faster than its URDF velocity
    limit allows (the message names the time, the speed and its ratio to the limit)."""


class DataNotFoundError(NameNotFoundError):
    """A data set name that no frame of the tree holds."""


class TargetNotReachedError(PinframesError, ValueError):
    """A target that ``solve_joints(..., strict=True)`` could not reach within the joint
    limits and tolerances (the message names the time and the residual errors)."""


class CollisionError(PinframesError, ValueError):
    """A planned motion that comes closer to something than its margin allows
    (``WeldProgram.plan(strict=True)``); the message names the move and the frames."""


class FileFormatError(PinframesError, ValueError):
    """A file whose content does not follow its format."""


class UnsupportedFeatureError(PinframesError, ValueError):
    """Valid input that pinframes deliberately does not handle (said in the message)."""


class GeometryError(PinframesError, ValueError):
    """Geometry a query needs and cannot have: a frame that is no URDF link, a link without
    shapes of the kind asked for, a malformed shape, a mesh file missing or unreadable."""


class WriteError(PinframesError, OSError):
    """A file that could not be written; any existing file at the path is left untouched."""


class ReadError(PinframesError, OSError):
    """A file that could not be read at all: missing, a folder, unreadable or not text."""


class ArgumentTypeError(PinframesError, TypeError):
    """An argument of the wrong type passed to a pinframes function or method."""


def near_misses(name: object, known: Iterable[str], kind: str = "frame") -> str:
    """``"; did you mean 'a/x' or 'x2'?"`` for names in ``known`` close to ``name``, or "".

    Names that end in ``/name`` (the name under a prefix) come first, then up to three
    names that :func:`difflib.get_close_matches` finds similar.
    """
    if not isinstance(name, str) or not name:
        return ""
    known = list(known)
    prefixed = [candidate for candidate in known if candidate.endswith("/" + name)]
    close = difflib.get_close_matches(name, known, n=3, cutoff=0.6)
    matches = list(dict.fromkeys([*prefixed, *close]))[:3]
    if not matches:
        return ""
    return f"; did you mean {kind} " + " or ".join(repr(match) for match in matches) + "?"


def joint_not_found(name: object, known: Iterable[str], *, frame: str | None = None,
                    field: str | None = None) -> JointNotFoundError:
    """The :class:`JointNotFoundError` for ``name``, which is not among the ``known`` joint
    names, with the close ones suggested (:func:`near_misses`)."""
    return JointNotFoundError(f"no joint named {name!r} in the tree"
                              + near_misses(name, known, "joint"), frame=frame, field=field)


def warn_at_caller(message: str, category: type[Warning] = UserWarning) -> None:
    """Warn about the line that called pinframes: the warning's file and line are those of
    the first frame outside the ``pinframes`` package (however deep inside pinframes the
    warning arises), so that Python shows the user's line and filters on it work."""
    frame: FrameType | None = sys._getframe(1)  # the function that warns: stacklevel 2
    level = 2
    while frame is not None and frame.f_globals.get("__name__", "").partition(".")[0] == (
            "pinframes"):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


class JointLimitWarning(UserWarning):
    """Joint values outside the limits written in the URDF."""


class FramesYamlWarning(UserWarning):
    """A ``frames.yaml`` oddity that pinframes reads anyway (unknown fields, undeclared frames)."""


class BagWarning(UserWarning):
    """A ROS bag read the way tf2 reads it, with something worth knowing: transforms tf2
    refuses, two transforms of a frame at one stamp, tf messages for links the robot
    description already has, joint states for joints it does not drive."""


class BrokenMimicWarning(UserWarning):
    """A URDF mimic joint that names a joint the file does not have: it is loaded as an
    independent joint (``strict=True`` refuses the file instead)."""


class SrdfWarning(UserWarning):
    """Parts of an SRDF that pinframes skips (one warning per file, naming them all): other
    tools' elements, group states nested in groups, names of links, joints or groups that
    the robot does not have."""


class GeometryWarning(UserWarning):
    """Something left out of a drawing: a link's mesh that is missing, unreadable, empty,
    compressed or too large, a point cloud, an ``<origin>`` inside a URDF ``<geometry>``; on
    the 3-D page also geometry or a frame that is not finite or too far away to draw."""


class JointWithoutSamplesWarning(UserWarning):
    """Robot joints evaluated without samples: they hold their rest value
    (:attr:`pinframes.Joint.rest_value`). Issued once until the tree changes."""


class ExtrapolationWarning(UserWarning):
    """Times outside the samples of a moving frame or joint, where it holds its first or
    last pose (the command line's ``--extrapolation clamp``)."""


class UnitWarning(UserWarning):
    """Numbers of a file that are implausible in pinframes' units (metres, radians): a
    position hundreds of metres away, an angle over a full turn. The message names the frame,
    the field and the likely unit (millimetres, degrees)."""


class ManifestWarning(UserWarning):
    """Lines of a batch's ``manifest.jsonl`` that are no run record (torn by an interrupted
    write, or edited by hand): they are skipped, and their runs computed again."""
