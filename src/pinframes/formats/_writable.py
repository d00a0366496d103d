"""What every writer checks before it writes: names its own reader reads back unchanged.

A writer writes a file its own reader accepts with the same meaning, or refuses before
writing, naming the frame and the field. Names are where the formats differ least from each
other and most from Python strings: XML 1.0 cannot hold most control characters, YAML reads
``\\x85`` (NEL) and other line breaks inside a plain scalar as a space, and none of the files
can encode a lone surrogate (``\\ud800``). So names with control characters (Unicode
category ``Cc``) or surrogates are refused by every writer; the tree itself accepts any
non-empty string. A CSV header is read back with its cells stripped, and a spreadsheet runs a
cell that starts with ``=``, ``+``, ``-`` or ``@`` as a formula: joint names written as a
CSV header may neither start nor end with a space nor start with one of those.
"""

from __future__ import annotations

import unicodedata
from collections.abc import Sequence

from ..errors import (
    ArgumentTypeError,
    InvalidDataError,
    PinframesError,
    TreeStructureError,
    UnsupportedFeatureError,
)
from ..tree import FrameTree
from ._paths import path_argument

__all__ = ["check_joint_names", "check_writable_tree", "refuse_attached_data"]

FORMULA_STARTS = ("=", "+", "-", "@")
"""First characters that make a spreadsheet read a CSV cell as a formula."""


def check_writable_tree(tree: FrameTree, path: object) -> None:
    """Check a writer's arguments before it does any work.

    Raises an :class:`ArgumentTypeError` for a ``tree`` that is no FrameTree or a ``path``
    that is no text path, an :class:`UnsupportedFeatureError` for a name no file could
    hold unchanged, and a :class:`TreeStructureError` for a subsystem naming frames the
    tree lacks; the last two name the file ``path``.
    """
    file = path_argument(path)
    if not isinstance(tree, FrameTree):
        raise ArgumentTypeError(f"expected a pinframes.FrameTree, got {type(tree).__name__}",
                                file=file, field="tree")
    try:
        _check_tree(tree)
    except PinframesError as exc:
        raise exc.located(file=file) from None


def refuse_attached_data(tree: FrameTree, path: object, what: str, field: str = "data"
                         ) -> None:
    """Refuse to write ``tree`` to a ``what`` file, which cannot hold data, when data is
    attached to its frames: an :class:`UnsupportedFeatureError` naming the data, their
    frames and the one format that holds them (a writer never drops data silently)."""
    names = tree.data_names
    if not names:
        return
    attached = ", ".join(f"{name!r} on frame {tree.data_frame(name)!r}" for name in names)
    raise UnsupportedFeatureError(
        f"data is attached to frames ({attached}) and {what} cannot hold data: pinframes "
        "writes data in ASDF schema '0.1.0' only (or detach it first: "
        "tree.delete_data(name))", file=path_argument(path), frame=tree.data_frame(names[0]),
        field=field)


def check_joint_names(names: Sequence[str], *, csv_header: bool) -> None:
    """Refuse joint names a joint trajectory file would not read back unchanged: none at
    all (an :class:`InvalidDataError`), a control character or a lone surrogate (every
    file), and in a CSV header a space at either end or a formula's first character (an
    :class:`UnsupportedFeatureError` naming the joint)."""
    if not names:
        raise InvalidDataError("no joints: a joint trajectory holds at least one",
                               field="joint_names")
    for name in names:
        _check_name(name, None, "joint_names", joint=_printable(name))
        if csv_header and name != name.strip():
            problem = "starts or ends with a space, which a CSV reader strips"
        elif csv_header and name.startswith(FORMULA_STARTS):
            problem = (f"starts with {name[0]!r}, which spreadsheets run as a formula when "
                       "they open a CSV file")
        else:
            continue
        raise UnsupportedFeatureError(f"the joint name {problem}: rename it, or write .npz "
                                      "or a ROS bag", joint=_printable(name),
                                      field="joint_names")


def _check_tree(tree: FrameTree) -> None:
    if tree.name is not None:
        _check_name(tree.name, None, "name")
    for frame in tree.frames:
        _check_name(frame, frame, "name")
        joint = tree.joint_of(frame)
        if joint is not None:
            _check_name(joint.name, frame, "joint")
    for subsystem in tree.subsystems:
        _check_name(subsystem.name, subsystem.root, "subsystems.name")
        missing = [name for name in (subsystem.root, *subsystem.members) if name not in tree]
        if missing:
            raise TreeStructureError(
                f"subsystem {subsystem.name!r} names frames the tree does not hold: "
                f"{', '.join(map(repr, missing))}", frame=missing[0], field="subsystems")


def _check_name(name: str, frame: str | None, field: str, joint: str | None = None) -> None:
    for character in name:
        kind = unicodedata.category(character)
        if kind in ("Cc", "Cs"):
            what = "a control character" if kind == "Cc" else "a lone surrogate"
            raise UnsupportedFeatureError(
                f"the name holds {what} ({character!r}), which files cannot hold unchanged: "
                "rename it", frame=_printable(frame), field=field, joint=joint)


def _printable(name: str | None) -> str | None:
    """``name`` with surrogates escaped, so that the error message itself can be printed."""
    if name is None:
        return None
    return name.encode("utf-8", "backslashreplace").decode("utf-8")
