"""weldx ASDF files: coordinate system hierarchies of all three generations.

The generations and their tags: docs/asdf-format.md. ``ASDF_FORMAT`` (the registry's entry)
is here at once; :func:`read_asdf` and :func:`write_asdf` load the asdf package, so they are
imported on first use.
"""

from __future__ import annotations

from ._format import ASDF_FORMAT

__all__ = ["ASDF_FORMAT", "read_asdf", "write_asdf"]


def __getattr__(name: str) -> object:
    if name == "read_asdf":
        from ._reader import read_asdf

        return read_asdf
    if name == "write_asdf":
        from ._writer import write_asdf

        return write_asdf
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
