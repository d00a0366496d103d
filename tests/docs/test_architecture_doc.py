"""docs/architecture.md names every module of src/pinframes, and no module that is gone.

A module is named by a backticked path, with or without ``.py``, that ends its path below
``src/pinframes`` and that no other module's path ends with (`_registry.py`, but
`asdf/_reader.py`: four folders hold a `_reader.py`). Packages' ``__init__.py`` files hand
names on and need no line. A new module needs its line in the table (or the text) when it
lands; a module planned but not written yet is named after the word "planned" in its row or
paragraph.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "pinframes"
DOC = ROOT / "docs" / "architecture.md"


def _modules() -> list[tuple[str, ...]]:
    return sorted(path.relative_to(SRC).parts for path in SRC.rglob("*.py"))


def _spans(planned: bool = True) -> set[str]:
    """Every backticked span of the document, without a leading ``src/pinframes/``; with
    ``planned=False`` not those after the word "planned" in a row or paragraph."""
    text = DOC.read_text(encoding="utf-8")
    if not planned:
        text = "\n\n".join(block.split("planned")[0] for block in re.split(r"\n\s*\n|\n\|", text))
    return {span.removeprefix("src/pinframes/").removeprefix("pinframes/")
            for span in re.findall(r"`([^`\n]+)`", text)}


def _suffixes(parts: tuple[str, ...]) -> list[str]:
    """The paths that end ``parts``, each with and without its ``.py``."""
    tails = ["/".join(parts[start:]) for start in range(len(parts))]
    return tails + [tail.removesuffix(".py") for tail in tails]


def test_every_module_is_named_in_the_architecture_document():
    modules = _modules()
    owners: dict[str, int] = {}
    for parts in modules:
        for suffix in _suffixes(parts):
            owners[suffix] = owners.get(suffix, 0) + 1
    spans = _spans()
    unnamed = ["/".join(parts) for parts in modules if parts[-1] != "__init__.py"
               and not any(owners[suffix] == 1 and suffix in spans
                           for suffix in _suffixes(parts))]
    assert not unnamed, f"add these modules to {DOC.relative_to(ROOT)}: {', '.join(unnamed)}"


def test_the_architecture_document_names_no_module_that_is_gone():
    files = [path.relative_to(ROOT).parts for folder in ("src", "tests", "benchmarks", "models")
             for path in (ROOT / folder).rglob("*.py")]
    known = {suffix for parts in files for suffix in _suffixes(parts)}
    gone = sorted(span for span in _spans(planned=False)
                  if span.endswith(".py") and span not in known)
    assert not gone, f"{DOC.relative_to(ROOT)} names files that do not exist: {', '.join(gone)}"
