"""Telling a tree file's format by its content, for :func:`~pinframes.formats.detect_format`.

The first bytes tell ASDF (``#ASDF``), ROS bags (a ROS 1 bag, MCAP or SQLite file: their magic
bytes) and XML (a URDF when its root element is ``<robot>``).
Other text is YAML, and the YAML formats' own tests tell it apart (a scene has the
``pinframes_scene`` key, a frames.yaml the ``frames`` key or a name starting with
``frames``). A file of any other kind is a :class:`~pinframes.errors.FileFormatError` that
says what it looks like and, where pinframes has a use for it, where it goes.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ..errors import FileFormatError
from .reading import read_bytes
from .rosbag import bag_kind_of_head

__all__ = ["format_by_content"]

_HEAD_BYTES = 4096
_XML_ROOT = re.compile(rb"<([A-Za-z_][\w:.-]*)")
_XML_SKIPPED = re.compile(rb"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>", re.DOTALL)
_MAGIC = (
    (b"\x89PNG", "a PNG image (pinframes plot and demo write those)"),
    (b"\xff\xd8\xff", "a JPEG image (pinframes plot writes those)"),
    (b"%PDF", "a PDF document (pinframes plot writes those)"),
    (b"PK\x03\x04", "a ZIP archive such as an NPZ file (a joint trajectory .npz goes in a "
     "scene's robots[].trajectory; pinframes pose writes poses as .npz)"),
)


def format_by_content(path: Path, candidates: Sequence[Any],
                      yaml_test: Callable[[Any], str | None]) -> str:
    """The name of the format among ``candidates`` (registered tree formats) that the file
    at ``path`` holds; ``yaml_test(candidates)`` names the YAML format or None."""
    head = read_bytes(path, _HEAD_BYTES)
    bag = bag_kind_of_head(head)
    if bag is not None:
        return _pick("rosbag", f"a {bag} file", path, candidates)
    body = head.removeprefix(b"\xef\xbb\xbf").lstrip()
    if body.startswith(b"#ASDF"):
        return _pick("asdf", "an ASDF file", path, candidates)
    if body.startswith(b"<"):
        match = _XML_ROOT.search(_XML_SKIPPED.sub(b"", body))
        root = match.group(1).decode("ascii", "replace") if match else "?"
        if root == "robot":
            return _pick("urdf", "a URDF file", path, candidates)
        raise _other(path, f"an XML file whose root element is <{root}>, not a URDF "
                     "(<robot>)", candidates)
    for magic, kind in _MAGIC:
        if body.startswith(magic):
            raise _other(path, kind, candidates)
    try:
        head.decode("utf-8")
    except UnicodeDecodeError as exc:
        if exc.start < len(head) - 4:  # not just a character cut at the end of the head
            raise _other(path, "binary data", candidates) from None
    if body.startswith((b"{", b"[")) and path.suffix.lower() == ".json":
        raise _other(path, "a JSON file (pinframes pose -f json writes poses as JSON)",
                     candidates)
    first_line = body.split(b"\n", 1)[0]
    if b"," in first_line and b":" not in first_line:
        raise _other(path, "a CSV table (a joint trajectory .csv goes in a scene's "
                     "robots[].trajectory; pinframes pose writes poses as CSV)", candidates)
    yaml_format = yaml_test([e for e in candidates if e.name not in ("asdf", "urdf", "rosbag")])
    if yaml_format is not None:
        return yaml_format
    reasons = " nor ".join(f"a {e.title} ({e.unrecognised})" for e in candidates
                           if e.unrecognised)
    raise _other(path, f"YAML or text, but neither {reasons}" if reasons else "text",
                 candidates)


def _pick(name: str, kind: str, path: Path, candidates: Sequence[Any]) -> str:
    if any(entry.name == name for entry in candidates):
        return name
    raise _other(path, kind, candidates)


def _other(path: Path, kind: str, candidates: Sequence[Any]) -> FileFormatError:
    titles = [entry.title for entry in candidates]
    known = ", ".join(titles[:-1]) + " and " + titles[-1] if len(titles) > 1 else titles[0]
    return FileFormatError(f"this looks like {kind}; pinframes reads trees from {known} "
                           "files", file=path)
