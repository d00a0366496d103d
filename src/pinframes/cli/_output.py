"""The ``pose``, ``transform`` and ``demo`` outputs: :mod:`pinframes.formats.tables.pose_files`
to a file or standard output."""

from __future__ import annotations

import sys
from pathlib import Path

from ..errors import FileFormatError
from ..formats.atomic import atomic_write
from ..formats.tables import POSE_FILE_FORMATS, pose_file_format, poses_text, write_poses
from ..kinematics import Velocity
from ..values.pose import Pose

__all__ = ["OUTPUT_FORMATS", "output_format", "output_poses", "require_suffix", "write_text"]

OUTPUT_FORMATS = POSE_FILE_FORMATS


def output_format(requested: str | None, out: str | None) -> str:
    """The format asked for, else the one the output file name implies, else (standard
    output) CSV. A file name with another suffix is a :class:`FileFormatError`: nothing is
    written in a format the name does not say."""
    if requested is not None:
        return requested
    if out is None:
        return "csv"
    named = pose_file_format(out)
    if named is None:
        raise FileFormatError(
            f"cannot tell the output format from the name: name the file "
            f"{', '.join('.' + name for name in OUTPUT_FORMATS)}, or pass --format",
            file=out, field="-o")
    return named


def require_suffix(out: str | None, suffixes: tuple[str, ...], what: str) -> None:
    """Refuse an output file ``out`` whose suffix is none of ``suffixes`` (``.csv``): the
    command writes only ``what``, and a name such as ``out.xlsx`` would promise another
    format."""
    if out is not None and Path(out).suffix.lower() not in suffixes:
        raise FileFormatError(f"this command writes {what}: name the file "
                              f"{' or '.join(suffixes)}", file=out, field="-o")


def output_poses(pose: Pose, fmt: str, out: str | None, *, frame: str, relative_to: str,
                 velocity: Velocity | None = None) -> None:
    """``pose`` (of ``frame`` in ``relative_to``) to the file ``out`` (through
    :func:`~pinframes.write_poses`) or to standard output, with the columns of ``velocity``
    (at the same times) after the pose's when given."""
    if out is not None:
        write_poses(pose, out, fmt, frame=frame, relative_to=relative_to,
                        velocity=velocity)
        return
    if fmt == "npz":
        raise FileFormatError("NPZ output is binary: give a file with -o")
    write_text(poses_text(pose, fmt, frame=frame, relative_to=relative_to, velocity=velocity),
               None)


def write_text(text: str, out: str | None) -> None:
    """``text`` to the file ``out`` (atomically) or to standard output."""
    if out is None:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    with atomic_write(out, "w") as handle:
        handle.write(text)
