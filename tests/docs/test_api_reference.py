"""docs/api.md is what docs/make_api_reference.py writes from today's docstrings."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pinframes

DOCS = Path(__file__).resolve().parents[2] / "docs"


def _generator():
    spec = importlib.util.spec_from_file_location("make_api_reference",
                                                  DOCS / "make_api_reference.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_api_reference_is_up_to_date():
    written = (DOCS / "api.md").read_text(encoding="utf-8")
    assert written == _generator().reference(), (
        "docs/api.md is stale: run `python docs/make_api_reference.py`")


def test_the_api_reference_names_every_public_name_with_its_docstring():
    text = _generator().reference()
    for name in pinframes.__all__:
        if name == "__version__":
            continue
        assert f"### `{name}" in text, name
        summary = (getattr(pinframes, name).__doc__ or "").strip().splitlines()[0]
        assert summary in text, name
