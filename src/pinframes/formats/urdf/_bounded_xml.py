"""URDF text to an XML element tree, refused as soon as it exceeds the reader limits
(:mod:`pinframes.formats.limits`).

ElementTree parses with expat, which expands entities declared in a document's DTD: a
400-byte file of nested entity definitions (the "billion laughs") describes gigabytes of
text or millions of elements. Expat 2.4.1 and newer stop such a document once it has
produced about 8 MiB and a hundred times its own size (``ParseError: limit on input
amplification factor``); within those 8 MiB a tiny file still yields two million elements
(a second and 160 MB here). So the parse here goes further:

- a ``<!DOCTYPE ...>`` declaration is refused: URDF has no DTD, and Pinocchio's parser
  (urdfdom on TinyXML2) skips one without expanding its entities, so a file that needs
  them means something else there;
- elements are counted (``max_xml_elements``) and their nesting measured (``max_depth``)
  as the parser produces them, and the parse stops at the first one over a limit, before
  the rest of the document is built.

XML forbids ``--`` inside a comment; ROS tools (urdfdom and MoveIt on TinyXML2) end a comment
at the first ``-->`` whatever it holds, and published files rely on it (a comment closed by
``--!>`` in Kawasaki's duAro SRDF). A document that expat refuses and that holds such a
comment is read again with its comments cut where TinyXML2 cuts them, with one warning.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

from ...errors import FileFormatError, warn_at_caller
from ..limits import current_limits, exceeded

_COMMENT = re.compile(r"<!--(.*?)-->", re.DOTALL)
"""A comment as TinyXML2 delimits it: from ``<!--`` to the first ``-->``."""

__all__ = ["parse_bounded_xml"]


def parse_bounded_xml(text: str, source: str) -> ET.Element:
    """The root element of ``text``; a :class:`FileFormatError` naming ``source`` for
    malformed XML, a DOCTYPE declaration, or more elements or nesting than the limits allow.
    """
    try:
        return _parse(text, source)
    except ET.ParseError as exc:
        refused = exc
    dashed = [match for match in _COMMENT.finditer(text) if "--" in match.group(1)]
    if dashed:
        try:
            root = _parse(_COMMENT.sub("", text), source)
        except ET.ParseError:
            pass
        else:
            line = text.count("\n", 0, dashed[0].start()) + 1
            warn_at_caller(f"{source}: {len(dashed)} comment(s) holding '--' (the first on "
                           f"line {line}), which XML forbids, read as ROS tools read them "
                           "(each comment ends at the first '-->')")
            return root
    raise FileFormatError(f"malformed XML: {refused}", file=source) from None


def _parse(text: str, source: str) -> ET.Element:
    parser = ET.XMLParser(target=_BoundedBuilder(source))
    parser.feed(text)
    return parser.close()


class _BoundedBuilder(ET.TreeBuilder):
    """The standard tree builder, counting elements and levels as they start."""

    def __init__(self, source: str) -> None:
        super().__init__()
        self._source = source
        self._limits = current_limits()
        self._elements = 0
        self._depth = 0

    def doctype(self, name: str, pubid: str | None, system: str | None) -> None:
        raise FileFormatError(
            "a <!DOCTYPE> declaration is refused: URDF has no DTD, and entities defined "
            "in one can expand a small file to gigabytes (Pinocchio and ROS do not expand "
            "them)", file=self._source, field="DOCTYPE")

    def start(self, tag: str, attrs: dict[str, str]) -> ET.Element:
        self._elements += 1
        self._depth += 1
        if self._elements > self._limits.max_xml_elements:
            raise exceeded("max_xml_elements", f"more than "
                           f"{self._limits.max_xml_elements:,} XML elements",
                           field=tag).located(file=self._source)
        if self._depth > self._limits.max_depth:
            raise exceeded("max_depth", f"XML elements nested more than "
                           f"{self._limits.max_depth:,} levels deep",
                           field=tag).located(file=self._source)
        return super().start(tag, attrs)

    def end(self, tag: str) -> ET.Element:
        self._depth -= 1
        return super().end(tag)
