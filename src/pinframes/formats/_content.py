"""What a file that no format claims looks like, for the message that refuses it.

The formats tell their own files by their content (``FileFormat.head_test`` and
``document_test`` in :mod:`._registry`). A file none of them claims gets a message that says
what it looks like: :func:`other_content` recognises the kinds of files people pass by
mistake (images the ``plot`` command writes, other XML, JSON, CSV, binary data) from the
first bytes, :func:`other_document` the YAML that names its own kind. :func:`xml_root` is
the root element of an XML file, for the URDF test too.
"""

from __future__ import annotations

import re

from .reading import InputFile

__all__ = ["is_text", "other_content", "other_document", "xml_root"]

_XML_ROOT = re.compile(rb"<([A-Za-z_][\w:.-]*)")
_XML_SKIPPED = re.compile(rb"<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^>]*>", re.DOTALL)
_MAGIC = (
    (b"\x89PNG", "a PNG image (pinframes plot and demo write those)"),
    (b"\xff\xd8\xff", "a JPEG image (pinframes plot writes those)"),
    (b"%PDF", "a PDF document (pinframes plot writes those)"),
    (b"PK\x03\x04", "a ZIP archive"),
)


def xml_root(source: InputFile) -> str | None:
    """The name of the root element if the file starts as XML (``<``), else None; ``"?"``
    when the first bytes name none."""
    start = source.start()
    if not start.startswith(b"<"):
        return None
    match = _XML_ROOT.search(_XML_SKIPPED.sub(b"", start))
    return match.group(1).decode("ascii", "replace") if match else "?"


def is_text(source: InputFile) -> bool:
    """Whether the first bytes are UTF-8 (a character cut at their end aside)."""
    head = source.head()
    try:
        head.decode("utf-8")
    except UnicodeDecodeError as exc:
        return exc.start >= len(head) - 4
    return True


def other_content(source: InputFile) -> str | None:
    """What the file looks like (``"a PNG image (...)"``), if it is a kind of file no tree
    format reads; None for text that may be YAML."""
    start = source.start()
    root = xml_root(source)
    if root is not None:
        return f"an XML file whose root element is <{root}>, not a URDF (<robot>)"
    for magic, kind in _MAGIC:
        if start.startswith(magic):
            return kind
    if not is_text(source):
        return "binary data"
    if start.startswith((b"{", b"[")) and source.path.suffix.lower() == ".json":
        return "a JSON file"
    lines = [line for line in start.split(b"\n") if line.strip()
             and not line.lstrip().startswith(b"#")]
    if lines and b"," in lines[0] and b":" not in lines[0]:
        return "a CSV table"
    return None


def other_document(source: InputFile) -> str | None:
    """What a YAML file that no format claims is, when it says so itself: a mapping with a
    ``format`` (or ``type``) key naming its kind."""
    document = source.yaml()
    if not isinstance(document, dict):
        return None
    for key in ("format", "type"):
        if isinstance(document.get(key), str):
            return (f"YAML of another kind ({key}: {document[key]!r}), which no pinframes "
                    "reader takes")
    return None
