"""The package's layers: no module imports a higher layer, no imports go round in a circle,
and no module reaches into another folder's ``_`` modules.

Every import is read from the source (module level, inside functions and under
``TYPE_CHECKING`` alike), so an import hidden in a function counts as much as one at the top.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import pinframes

PACKAGE = Path(pinframes.__file__).parent
BUNDLED_DATA = PACKAGE / "models"
"""The bundled models (their generator scripts too): data, not modules of the package. In a
checkout it is a symbolic link that rglob does not enter; an installed copy is a folder."""

LAYERS = [
    ("errors",),
    ("values",),
    ("kinematics",),
    ("tree",),
    ("program",),
    ("formats",),
    ("",),  # the package's own __init__: the public names
    ("cli", "plotting", "view", "batch"),
]
"""Lowest first; a module may import its own layer and the layers below."""


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _imports(path: Path) -> set[str]:
    """Modules of pinframes that ``path`` imports, resolved to module names."""
    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    modules = _all_modules()
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                stem = ".".join(base + ([node.module] if node.module else []))
            else:
                stem = node.module or ""
            # `from X import Y` imports module X.Y when there is one, else a name of X
            targets = [f"{stem}.{alias.name}" if f"{stem}.{alias.name}" in modules else stem
                       for alias in node.names]
        else:
            continue
        found.update(t for t in targets if t == "pinframes" or t.startswith("pinframes."))
    found.discard(name)
    return found


def _sources() -> list[Path]:
    return sorted(path for path in PACKAGE.rglob("*.py")
                  if not path.is_relative_to(BUNDLED_DATA))


def _all_modules() -> set[str]:
    return {_module_name(path) for path in _sources()}


def _layer(module: str) -> int:
    first = module.split(".")[1] if "." in module else ""
    for index, names in enumerate(LAYERS):
        if first in names:
            return index
    raise AssertionError(f"{module} is in no layer; add its folder to LAYERS")


def _graph() -> dict[str, set[str]]:
    return {_module_name(path): _imports(path) for path in _sources()}


def test_the_reader_resolves_relative_imports_and_imports_inside_functions(tmp_path):
    """The graph reader itself: an import inside a function, relative and absolute forms."""
    graph = _graph()
    assert "pinframes.errors" in graph["pinframes.tree.frame_tree"]
    # `from .formats import asdf` inside __getattr__, seen as the module pinframes.formats.asdf
    assert "pinframes.formats.asdf" in graph["pinframes"]
    assert "pinframes.kinematics._model" in graph["pinframes.kinematics._plan"]


def test_every_module_belongs_to_a_layer():
    for module in _graph():
        _layer(module)


def test_no_module_imports_a_higher_layer():
    upward = []
    for module, imports in _graph().items():
        for target in imports:
            if _layer(target) > _layer(module):
                upward.append(f"{module} -> {target}")
    assert upward == []


def test_no_import_cycles():
    """No module reaches itself through imports (a package's own __init__ included)."""
    graph = _graph()
    cycles = []
    state: dict[str, int] = {}

    def visit(module: str, stack: list[str]) -> None:
        state[module] = 1
        stack.append(module)
        for target in sorted(graph.get(module, ())):
            if state.get(target) == 1:
                cycles.append(" -> ".join([*stack[stack.index(target):], target]))
            elif target not in state:
                visit(target, stack)
        stack.pop()
        state[module] = 2

    for module in sorted(graph):
        if module not in state:
            visit(module, [])
    assert cycles == []


def _private_owner(module: str) -> str | None:
    """The folder (package) whose own business ``module`` is, when a part of its name starts
    with ``_`` (``pinframes.values._readonly`` -> ``pinframes.values``); None for a public
    module."""
    parts = module.split(".")
    for depth, part in enumerate(parts):
        if part.startswith("_") and not part.startswith("__"):
            return ".".join(parts[:depth])
    return None


def _folder(module: str) -> str:
    """The package a module lives in (a package's ``__init__`` lives in the package)."""
    path = PACKAGE.parent.joinpath(*module.split("."))
    return module if path.is_dir() else module.rpartition(".")[0]


def _crossings(graph: dict[str, set[str]]) -> list[str]:
    """Imports of a ``_`` module from outside its folder (and the folders inside it)."""
    crossings = []
    for module, imports in graph.items():
        folder = _folder(module)
        for target in sorted(imports):
            owner = _private_owner(target)
            if owner is not None and folder != owner and not folder.startswith(owner + "."):
                crossings.append(f"{module} -> {target}")
    return crossings


def test_private_modules_stay_in_their_folder():
    """A ``_`` module is used by its own folder (and the folders inside it) only; what other
    folders use has a public name."""
    assert _crossings(_graph()) == []


def test_the_crossing_check_tells_a_crossing_from_a_folder_of_its_own():
    """A sibling folder's ``_`` module crosses; the own folder's and a parent folder's do not,
    nor does a public module."""
    graph = {
        "pinframes.kinematics.pose": {"pinframes.values._readonly", "pinframes.kinematics._path",
                                      "pinframes.values.se3"},
        "pinframes.formats.urdf._parse": {"pinframes.formats._paths"},
        "pinframes.cli._output": {"pinframes.formats._paths"},
        "pinframes.kinematics": {"pinframes.kinematics._description"},
    }
    assert _crossings(graph) == ["pinframes.kinematics.pose -> pinframes.values._readonly",
                                 "pinframes.cli._output -> pinframes.formats._paths"]


@pytest.mark.parametrize("layer", ["values", "kinematics", "tree"])
def test_the_core_never_imports_formats_or_the_edge(layer):
    """Named once more for the layers issue 13 pulled apart (tree -> urdf was a cycle)."""
    for module, imports in _graph().items():
        if module.startswith(f"pinframes.{layer}"):
            assert not [t for t in imports if _layer(t) > _layer(module)], module
