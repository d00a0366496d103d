"""weldx ASDF files: coordinate system hierarchies of all three generations (SPEC 7)."""

from ._reader import read_asdf
from ._writer import write_asdf

__all__ = ["read_asdf", "write_asdf"]
