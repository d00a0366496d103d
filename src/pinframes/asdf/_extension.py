"""pinframes' schemas for weldx hierarchies, bound into asdf only while pinframes uses a file.

weldx registers its own converters and schemas for the ``asdf://weldx.bam.de`` tags through
asdf's entry points. pinframes must live beside it in one environment, so it never registers
anything globally: :func:`bound_schemas` adds the schemas in ``schemas/`` and an extension
built from ``schemas/manifests/`` to a temporary asdf configuration, where they take
precedence over weldx's for the tags they name; asdf then validates against them, on write
and on read (asdf 6 no longer validates on read by default, so the block turns it on).
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Iterator
from pathlib import Path

import yaml

__all__ = ["EXTENSION_URI", "SCHEMA_URI_PREFIX", "bound_schemas"]

SCHEMA_FOLDER = Path(__file__).with_name("schemas")
SCHEMA_URI_PREFIX = "asdf://pinframes/schemas/weldx/"
MANIFEST = SCHEMA_FOLDER / "manifests" / "weldx_hierarchies-1.0.0.yaml"
EXTENSION_URI = "asdf://pinframes/extensions/weldx_hierarchies-1.0.0"


@contextlib.contextmanager
def bound_schemas() -> Iterator[None]:
    """Within this block asdf knows pinframes' weldx schemas and validates against them."""
    import asdf

    with asdf.config_context() as config:
        config.validate_on_read = True
        config.add_resource_mapping(_schema_mapping())
        config.add_extension(_extension())
        yield


@functools.lru_cache(maxsize=1)
def _schema_mapping():  # -> asdf.resource.DirectoryResourceMapping
    from asdf.resource import DirectoryResourceMapping

    return DirectoryResourceMapping(SCHEMA_FOLDER / "weldx", SCHEMA_URI_PREFIX, recursive=True)


@functools.lru_cache(maxsize=1)
def _extension():  # -> asdf.extension.ManifestExtension
    from asdf.extension import ManifestExtension

    manifest = yaml.safe_load(MANIFEST.read_text(encoding="utf-8"))
    return ManifestExtension(manifest)
