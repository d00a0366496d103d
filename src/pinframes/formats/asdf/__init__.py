"""weldx ASDF files: coordinate system hierarchies of all three generations.

The generations and their tags: docs/asdf-format.md.
"""

from ._reader import read_asdf
from ._writer import write_asdf

__all__ = ["read_asdf", "write_asdf"]
