"""weldx coordinate system hierarchies in ASDF files (SPEC section 7)."""

from ._writer import write_asdf

__all__ = ["write_asdf"]
