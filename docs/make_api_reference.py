"""Write docs/api.md, the API reference, from the docstrings of pinframes' public names.

Run ``python docs/make_api_reference.py`` after adding a public name or changing a public
docstring or signature; ``tests/docs/test_api_reference.py`` fails while docs/api.md differs
from what this writes. The public names are those of ``__all__`` in each module of
``PUBLIC_MODULES``: ``pinframes`` itself and the modules at its edge that users import
(``pinframes.view``, ``pinframes.plotting``, ``pinframes.batch``), and the single names of
``PUBLIC_NAMES`` that live deeper. Every public name gets a section with its signature and
its whole docstring; a class also gets every public method and property that it defines or
inherits from pinframes, each with its signature and whole docstring. Importing
``pinframes.batch`` needs the ``batch`` extra, ``pinframes.view`` is plain Python.
"""

from __future__ import annotations

import importlib
import inspect
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pinframes

OUTPUT = Path(__file__).resolve().parent / "api.md"

PUBLIC_MODULES = ("pinframes", "pinframes.view", "pinframes.plotting", "pinframes.batch")
# public functions that live in a deeper module and are named in the documentation
PUBLIC_NAMES = (("pinframes.formats.urdf", "expand_xacro"),)

_KINDS: tuple[tuple[str, Callable[[object], bool]], ...] = (
    ("Trees", lambda obj: obj is pinframes.FrameTree),
    ("Exceptions and warnings",
     lambda obj: isinstance(obj, type) and issubclass(obj, (Exception, Warning))),
    ("Values and results", lambda obj: isinstance(obj, type)),
    ("Functions", callable),
    ("Constants", lambda obj: True),
)


def _signature(obj: object, drop_self: bool = False) -> str:
    try:
        signature = inspect.signature(obj)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return "(...)"
    parameters = list(signature.parameters.values())
    if drop_self and parameters and parameters[0].name == "self":
        signature = signature.replace(parameters=parameters[1:])
    return str(signature)


def _docstring(obj: object) -> list[str]:
    """The whole docstring, verbatim in a fenced block (numpydoc's underlined section titles
    would be Markdown headings, and its indented descriptions would run together)."""
    doc = inspect.cleandoc(inspect.getdoc(obj) or "") if _own_doc(obj) else ""
    fence = "~~~" if "```" in doc else "```"
    return [f"{fence}text", doc, fence, ""] if doc else []


def _own_doc(obj: object) -> bool:
    """False for objects whose docstring is only their type's (a constant's ``int`` doc)."""
    return isinstance(obj, (type, property)) or callable(obj) or isinstance(obj, ModuleType)


def public_members(cls: type) -> list[tuple[str, object]]:
    """The public methods and properties that ``cls`` defines or inherits from pinframes
    (not from ``object``, ``Exception``, numpy or dataclasses), by name."""
    members = []
    for name, member in inspect.getmembers(cls):
        if name.startswith("_"):
            continue
        owner = next((base for base in cls.__mro__ if name in vars(base)), None)
        if owner is None or not owner.__module__.startswith("pinframes"):
            continue
        static = inspect.getattr_static(cls, name)
        if isinstance(static, property) or callable(member):
            members.append((name, static if isinstance(static, property) else member))
    return members


def _member_section(cls_name: str, name: str, member: object, level: str) -> list[str]:
    if isinstance(member, property):
        heading = f"{level} `{cls_name}.{name}` (property)"
    else:
        heading = f"{level} `{cls_name}.{name}{_signature(member, drop_self=True)}`"
    return [heading, "", *_docstring(member)]


def _section(module: str, name: str, obj: object, level: str) -> list[str]:
    """The section of one public name, its heading at ``level`` (``"###"``), its members'
    one level below."""
    if module != "pinframes" and name in pinframes.__all__ and getattr(pinframes, name) is obj:
        return [f"{level} `{name}`", "", f"The same object as `pinframes.{name}` (above).", ""]
    if isinstance(obj, type):
        lines = [f"{level} `{name}`", ""]
        if not issubclass(obj, (Exception, Warning)):
            lines += [f"`{name}{_signature(obj)}`", ""]
        lines += _docstring(obj)
        for member_name, member in public_members(obj):
            lines += _member_section(name, member_name, member, level + "#")
        return lines
    if callable(obj):
        return [f"{level} `{name}{_signature(obj)}`", "", *_docstring(obj)]
    return [f"{level} `{name}`", "", f"`{name} = {obj!r}`", ""]


def public_names(module_name: str) -> dict[str, object]:
    """The public names of one module of ``PUBLIC_MODULES``, by name."""
    module = importlib.import_module(module_name)
    return {name: getattr(module, name) for name in sorted(module.__all__)
            if name != "__version__"}


def _module_part(module_name: str) -> list[str]:
    module = importlib.import_module(module_name)
    lines = [f"## `{module_name}`", "", *_docstring(module)]
    public = public_names(module_name)
    placed: set[str] = set()
    for title, belongs in _KINDS:
        names = [name for name, obj in public.items() if name not in placed and belongs(obj)]
        placed.update(names)
        if names and module_name == "pinframes":  # many names: grouped by kind
            lines += [f"### {title}", ""]
        for name in names:
            level = "####" if module_name == "pinframes" else "###"
            lines += _section(module_name, name, public[name], level)
    return lines


def reference() -> str:
    """The whole API reference as Markdown."""
    lines = ["# API reference", "",
             "Every public name of pinframes with its signature and its whole docstring, "
             "written by `docs/make_api_reference.py` (run it after a public name or "
             "docstring changes). Lengths are in metres, angles in radians, times in "
             "seconds, quaternions `(x, y, z, w)`. The topics are explained, with examples, "
             "on the other pages of docs/ (see the README).", "",
             "Modules: " + ", ".join(f"`{name}`" for name in PUBLIC_MODULES)
             + "; and " + ", ".join(f"`{module}.{name}`" for module, name in PUBLIC_NAMES)
             + ".", ""]
    for module_name in PUBLIC_MODULES:
        lines += _module_part(module_name)
    lines += ["## Deeper public functions", ""]
    for module_name, name in PUBLIC_NAMES:
        obj = getattr(importlib.import_module(module_name), name)
        lines += [f"### `{module_name}.{name}{_signature(obj)}`", "", *_docstring(obj)]
    return "\n".join(lines).rstrip() + "\n"


if __name__ == "__main__":
    OUTPUT.write_text(reference(), encoding="utf-8")
    sys.stdout.write(f"wrote {OUTPUT}\n")
