"""pinframes' schemas for weldx hierarchies, bound into asdf only while pinframes uses a file.

weldx registers its own converters and schemas for the ``asdf://weldx.bam.de`` tags through
asdf's entry points. pinframes must live beside it in one environment, so it never registers
anything globally: :func:`bound_schemas` adds the schemas in ``schemas/`` and an extension
built from ``schemas/manifests/`` to a temporary asdf configuration, where they take
precedence over weldx's for the tags they name; asdf then validates against them.
:func:`validate_hierarchy` checks one hierarchy read from a file against them.
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import yaml

from ...errors import FileFormatError
from ._asdf_config import temporary_asdf_config
from ._decode import DECODING_ERRORS, first_line, weldx_tag

__all__ = [
    "EXTENSION_URI",
    "SCHEMA_URI_PREFIX",
    "bound_schemas",
    "frame_on_path",
    "validate_hierarchy",
]

SCHEMA_FOLDER = Path(__file__).with_name("schemas")
SCHEMA_URI_PREFIX = "asdf://pinframes/schemas/weldx/"
MANIFEST = SCHEMA_FOLDER / "manifests" / "weldx_hierarchies-1.0.0.yaml"
EXTENSION_URI = "asdf://pinframes/extensions/weldx_hierarchies-1.0.0"
_FRAME_TAGS = ("core/transformations/coordinate_transformation", "core/graph/di_node",
               "core/graph/di_edge")


@contextlib.contextmanager
def bound_schemas() -> Iterator[None]:
    """Within this block asdf knows pinframes' weldx schemas and validates against them."""
    with temporary_asdf_config() as config:
        config.add_resource_mapping(_schema_mapping())
        config.add_extension(_extension())
        yield


def validate_hierarchy(hierarchy: Any) -> None:
    """Check a hierarchy (raw tagged data, as read) against pinframes' weldx schemas.

    Only the hierarchy is checked, not the rest of the file it came from.

    Raises
    ------
    FileFormatError
        Naming the field (a path inside the hierarchy) and the frame it belongs to.
    """
    import asdf
    from asdf import schema, yamlutil

    with bound_schemas():
        document = asdf.AsdfFile()
        try:
            tagged = yamlutil.custom_tree_to_tagged_tree(hierarchy, document)
        except DECODING_ERRORS as exc:  # arrays whose blocks decoded to what asdf cannot tag
            raise FileFormatError(f"holds an array asdf cannot check: {first_line(exc)}") from None
        try:
            schema.validate(tagged, document)
        except asdf.ValidationError as exc:
            path = list(exc.absolute_path)
            raise FileFormatError(f"breaks its weldx schema: {exc.message}",
                                  frame=frame_on_path(hierarchy, path),
                                  field="/".join(map(str, path)) or None) from None


def frame_on_path(node: Any, path: list[Any]) -> str | None:
    """The last frame met going down ``path``: that of a transformation, node or edge."""
    frame = None
    for step in path:
        try:
            node = node[step]
        except (KeyError, IndexError, TypeError):
            break
        kind = (weldx_tag(node) or ("", ""))[0]
        is_edge = kind == "core/graph/di_edge" and isinstance(node, dict)
        named = node.get("target_node") if is_edge else node
        if kind in _FRAME_TAGS and isinstance(named, dict) and isinstance(named.get("name"), str):
            frame = named["name"]
    return frame


@functools.lru_cache(maxsize=1)
def _schema_mapping():  # -> asdf.resource.DirectoryResourceMapping
    from asdf.resource import DirectoryResourceMapping

    return DirectoryResourceMapping(SCHEMA_FOLDER / "weldx", SCHEMA_URI_PREFIX, recursive=True)


@functools.lru_cache(maxsize=1)
def _extension():  # -> asdf.extension.ManifestExtension
    from asdf.extension import ManifestExtension

    manifest = yaml.safe_load(MANIFEST.read_text(encoding="utf-8"))
    return ManifestExtension(manifest)
