"""The project names nothing outside itself: no outside spec file, no folder beside the
checkout in its docs and docstrings, and every docs/ page it names exists."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _texts() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
            *sorted((ROOT / "src" / "pinframes").rglob("*.py"))]


def test_no_doc_or_docstring_cites_an_outside_spec():
    outside = re.compile(r"\bSPEC\b|\.\./shared|shared/SPEC")
    cited = [f"{path.relative_to(ROOT)}:{number}"
             for path in _texts()
             for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if outside.search(line)]
    assert not cited, f"put the definitions into docs/ and cite them there: {cited}"


def test_every_docs_page_named_exists():
    named = {name for path in _texts()
             for name in re.findall(r"docs/([\w-]+\.md)", path.read_text(encoding="utf-8"))}
    missing = sorted(name for name in named if not (ROOT / "docs" / name).is_file())
    assert named and not missing, missing
