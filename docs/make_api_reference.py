"""Write docs/api.md, the API reference, from the docstrings of ``pinframes``' public names.

Run ``python docs/make_api_reference.py`` after changing a public docstring or signature;
``tests/docs/test_api_reference.py`` fails while docs/api.md differs from what this writes.
Every name of ``pinframes.__all__`` gets a section: its signature and its whole docstring,
and for a class its public methods and properties, each with its signature and the first
paragraph of its docstring.
"""

from __future__ import annotations

import inspect
import sys
from pathlib import Path

import pinframes

OUTPUT = Path(__file__).resolve().parent / "api.md"

_KINDS = (("Trees", lambda obj: obj is pinframes.FrameTree),
          ("Exceptions and warnings",
           lambda obj: isinstance(obj, type) and issubclass(obj, (Exception, Warning))),
          ("Values and results", lambda obj: isinstance(obj, type)),
          ("Functions", callable))


def _signature(obj: object) -> str:
    try:
        return str(inspect.signature(obj))  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return "(...)"


def _first_paragraph(doc: str | None) -> str:
    return inspect.cleandoc(doc or "").split("\n\n")[0].replace("\n", " ")


def _members(cls: type) -> list[str]:
    """One line per public method and property that the class defines or inherits from
    pinframes (not from ``object``, ``Exception`` or numpy)."""
    lines = []
    for name, member in inspect.getmembers(cls):
        if name.startswith("_"):
            continue
        owner = next((base for base in cls.__mro__ if name in vars(base)), None)
        if owner is None or not owner.__module__.startswith("pinframes"):
            continue
        if isinstance(inspect.getattr_static(cls, name), property):
            lines.append(f"- `{name}` (property): {_first_paragraph(member.__doc__)}")
        elif callable(member):
            lines.append(f"- `{name}{_signature(member)}`: {_first_paragraph(member.__doc__)}")
    return lines


def _section(name: str, obj: object) -> list[str]:
    heading = f"### `{name}`" if isinstance(obj, type) else f"### `{name}{_signature(obj)}`"
    lines = [heading, ""]
    if isinstance(obj, type) and not issubclass(obj, (Exception, Warning)):
        lines += [f"`{name}{_signature(obj)}`", ""]
    doc = inspect.cleandoc(obj.__doc__ or "")
    if doc:
        lines += [doc, ""]
    if isinstance(obj, type) and not issubclass(obj, (Exception, Warning)):
        members = _members(obj)
        if members:
            lines += [*members, ""]
    return lines


def reference() -> str:
    """The whole API reference as Markdown."""
    public = {name: getattr(pinframes, name) for name in sorted(pinframes.__all__)
              if name != "__version__"}
    lines = ["# API reference", "",
             "Every public name of `pinframes`, written from the docstrings by "
             "`docs/make_api_reference.py`. Lengths are in metres, angles in radians, "
             "quaternions `(x, y, z, w)`.", ""]
    placed: set[str] = set()
    for title, belongs in _KINDS:
        names = [name for name, obj in public.items() if name not in placed and belongs(obj)]
        placed.update(names)
        lines += [f"## {title}", ""]
        for name in names:
            lines += _section(name, public[name])
    return "\n".join(lines).rstrip() + "\n"


if __name__ == "__main__":
    OUTPUT.write_text(reference(), encoding="utf-8")
    sys.stdout.write(f"wrote {OUTPUT}\n")
