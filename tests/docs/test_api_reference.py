"""docs/api.md is what docs/make_api_reference.py writes from today's docstrings, and it shows
every public name, and every public method and property of a public class, with its whole
docstring."""

from __future__ import annotations

import importlib
import importlib.util
import inspect
from pathlib import Path

import pytest

import pinframes

DOCS = Path(__file__).resolve().parents[2] / "docs"

pytest.importorskip("pyarrow")  # pinframes.batch, one of the public modules, needs it


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


def test_the_public_modules_include_the_edge_that_users_import():
    generator = _generator()
    assert {"pinframes", "pinframes.view", "pinframes.plotting", "pinframes.batch"} <= set(
        generator.PUBLIC_MODULES)


def _whole(obj: object) -> str:
    return inspect.cleandoc(inspect.getdoc(obj) or "")


def test_every_public_name_and_member_is_shown_with_its_whole_docstring():
    generator = _generator()
    text = generator.reference()
    missing = []
    for module_name in generator.PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        assert module.__all__, module_name
        for name in module.__all__:
            if name == "__version__":
                continue
            obj = getattr(module, name)
            if f" `{name}" not in text:
                missing.append(f"{module_name}.{name}")
            if not (callable(obj) or isinstance(obj, type)):
                continue
            if module_name != "pinframes" and getattr(pinframes, name, None) is obj:
                continue  # shown once, under pinframes
            documented = [(name, obj)]
            if isinstance(obj, type):
                documented += [(f"{name}.{member_name}", member) for member_name, member
                               in generator.public_members(obj)]
            for label, item in documented:
                doc = _whole(item)
                if not doc or doc not in text:
                    missing.append(f"{module_name}.{label}: docstring")
    assert not missing, missing


def test_frame_tree_methods_are_not_cut_to_their_first_line():
    text = _generator().reference()
    doc = _whole(pinframes.FrameTree.solve_joints)
    assert len(doc.splitlines()) > 5 and doc in text
    assert "`FrameTree.solve_joints(" in text and "`FrameTree.frames` (property)" in text
