"""Which tree format a file holds, told by its content: ASDF, URDF, scene or frames.yaml.

The first bytes tell ASDF (``#ASDF``) and XML (a URDF when its root element is
``<robot>``); YAML is told by its keys: ``pinframes_scene`` for a scene, ``frames`` for a
Duckietown ``frames.yaml`` (also a YAML file whose name starts with ``frames``). Any other
file is a :class:`~pinframes.errors.FileFormatError` that says what the file looks like and,
where pinframes has a use for it, where it goes.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from ._reading import read_bytes
from ._yaml_loader import load_yaml
from .errors import FileFormatError
from .scene import SCENE_FORMAT_KEY as SCENE_KEY

__all__ = ["TREE_FORMATS", "tree_format_of"]

TREE_FORMATS = ("scene", "frames.yaml", "asdf", "urdf")

_HEAD_BYTES = 4096
_XML_ROOT = re.compile(rb"<([A-Za-z_][\w:.-]*)")
_XML_SKIPPED = re.compile(rb"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>", re.DOTALL)
_READ_BY = ("every command that takes a tree reads scene, frames.yaml, ASDF and URDF "
            "files")
_OTHER_KINDS = (
    (b"\x89PNG", "a PNG image (pinframes plot and demo write those)"),
    (b"\xff\xd8\xff", "a JPEG image (pinframes plot writes those)"),
    (b"%PDF", "a PDF document (pinframes plot writes those)"),
    (b"PK\x03\x04", "a ZIP archive such as an NPZ file (a joint trajectory .npz goes in a "
     "scene's robots[].trajectory; poses .npz are what pinframes pose writes)"),
)


def tree_format_of(path: str | os.PathLike[str]) -> str:
    """One of :data:`TREE_FORMATS` for the file at ``path``, told by its content.

    Raises
    ------
    FileFormatError
        The file holds no tree pinframes reads; the message says what it looks like.
    ReadError
        The file is missing, a folder or unreadable.
    """
    head = read_bytes(path)[:_HEAD_BYTES]
    body = head.removeprefix(b"\xef\xbb\xbf").lstrip()
    if body.startswith(b"#ASDF"):
        return "asdf"
    if body.startswith(b"<"):
        match = _XML_ROOT.search(_XML_SKIPPED.sub(b"", body))
        root = match.group(1).decode("ascii", "replace") if match else "?"
        if root == "robot":
            return "urdf"
        raise _other(path, f"an XML file whose root element is <{root}>, not a URDF "
                     "(<robot>)")
    for magic, kind in _OTHER_KINDS:
        if body.startswith(magic):
            raise _other(path, kind)
    try:
        head.decode("utf-8")
    except UnicodeDecodeError as exc:
        if exc.start < len(head) - 4:  # not just a character cut at the end of the head
            raise _other(path, "binary data") from None
    if body.startswith((b"{", b"[")) and Path(path).suffix.lower() == ".json":
        raise _other(path, "a JSON file (pinframes pose -f json writes poses as JSON)")
    first_line = body.split(b"\n", 1)[0]
    if b"," in first_line and b":" not in first_line:
        raise _other(path, "a CSV table (a joint trajectory .csv goes in a scene's "
                     "robots[].trajectory; pinframes pose writes poses as CSV)")
    return _yaml_format(path)


def _yaml_format(path: str | os.PathLike[str]) -> str:
    content = load_yaml(path)
    if isinstance(content, dict) and SCENE_KEY in content:
        return "scene"
    if isinstance(content, dict) and "frames" in content:
        return "frames.yaml"
    if Path(path).name.lower().startswith("frames"):
        return "frames.yaml"
    if isinstance(content, dict):
        keys = ", ".join(map(str, list(content)[:5])) or "none"
        raise _other(path, f"a YAML mapping with keys {keys}, but neither a scene (no "
                     f"'{SCENE_KEY}' key) nor a frames.yaml (no 'frames' key)")
    raise _other(path, f"YAML (or plain text) holding a {type(content).__name__}, not a "
                 "scene or frames.yaml mapping")


def _other(path: str | os.PathLike[str], kind: str) -> FileFormatError:
    return FileFormatError(f"this looks like {kind}; {_READ_BY}", file=path)
