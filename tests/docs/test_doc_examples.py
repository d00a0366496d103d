"""The Python examples of README.md and of every docs/*.md page run as written, each page
alone, and print what their comments say they print.

Each page runs as one script in a namespace of its own (its ``python`` blocks in order, so a
block may use what an earlier block of the SAME page made, never what another page made), in
a fresh temporary working folder that holds only links to the repository's ``models/`` and
``tests/data/`` (the paths the pages use). A page whose examples need an optional extra is
skipped when the extra is missing. Every ``print(...)`` with a comment on its lines (or on
comment lines right after it) must print values that the comment shows, in the same order
(the comment may add words: units, what the numbers mean). The last tests check numbers the
pages print against hand-derived values.
"""

from __future__ import annotations

import ast
import contextlib
import io
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
# modules of optional extras that a page's examples import, by page
NEEDS = {"view.md": ("meshcat", "trimesh"), "robots.md": ("xacro",),
         "ros-bags.md": ("rosbags",), "ros-bags-out.md": ("rosbags",),
         "batch.md": ("pandas", "dask.distributed"), "asdf-format.md": ("asdf",),
         "weldx.md": ("asdf",)}


def python_blocks(path: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), re.S)


PAGES_WITH_EXAMPLES = [path for path in PAGES if python_blocks(path)]


def _tokens(text: str) -> list[str]:
    """Words and numbers, without brackets, commas and quotes: ``[0.6 2.6 0. ]`` and
    ``[0.6, 2.6, 0.]`` give the same tokens."""
    return [word.rstrip(":;") for word in re.sub(r"[\[\](),'\"]", " ", text).split()]


def _shown(printed: str, comment: str) -> bool:
    """Whether every token of ``printed`` appears in ``comment``, in order."""
    rest = iter(_tokens(comment))
    return all(any(token == word for word in rest) for token in _tokens(printed))


def _commented_prints(block: str) -> list[tuple[int, str]]:
    """``(line, comment)`` of each print call with comments on its lines (and on comment
    lines right after it)."""
    lines = block.splitlines()
    found = []
    for node in ast.walk(ast.parse(block)):
        if (isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
                and isinstance(node.value.func, ast.Name) and node.value.func.id == "print"):
            end = node.end_lineno or node.lineno
            while end < len(lines) and lines[end].lstrip().startswith("#"):
                end += 1
            comments = [line.split("#", 1)[1] for line in lines[node.lineno - 1:end]
                        if "#" in line]
            if comments:
                found.append((node.lineno, " ".join(comments)))
    return found


def run_page(path: Path, folder: Path) -> tuple[dict, list[str]]:
    """Run the page's blocks in order in a fresh namespace with ``folder`` as the working
    folder; return the namespace and the prints that do not show what their comment says."""
    (folder / "models").symlink_to(ROOT / "models")
    (folder / "tests").mkdir()
    (folder / "tests" / "data").symlink_to(ROOT / "tests" / "data")
    namespace: dict = {"__name__": f"docs_page_{path.stem}"}  # not "__main__": batch.md
    wrong = []
    before = Path.cwd()
    os.chdir(folder)
    try:
        for number, block in enumerate(python_blocks(path), 1):
            printed: dict[int, str] = {}

            def record(*args, sep=" ", end="\n", file=None, flush=False, printed=printed):
                line = sys._getframe(1).f_lineno
                out = io.StringIO()
                print(*args, sep=sep, end=end, file=out)
                printed[line] = printed.get(line, "") + out.getvalue()

            namespace["print"] = record
            with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
                warnings.simplefilter("ignore")
                exec(compile(block, f"{path.name} (python block {number})", "exec"), namespace)
            for line, comment in _commented_prints(block):
                if line in printed and not _shown(printed[line], comment):
                    wrong.append(f"{path.name}: {block.splitlines()[line - 1].strip()}\n"
                                 f"  prints {printed[line].strip()!r}")
    finally:
        os.chdir(before)
    return namespace, wrong


_RUNS: dict[str, tuple[dict, list[str]]] = {}


@pytest.fixture
def page_run(tmp_path_factory):
    """The namespace and wrong prints of one page's run, run once per test process."""
    def run(name: str) -> tuple[dict, list[str]]:
        path = ROOT / name
        for module in NEEDS.get(path.name, ()):
            pytest.importorskip(module)
        if name not in _RUNS:
            _RUNS[name] = run_page(path, tmp_path_factory.mktemp(path.stem))
        return _RUNS[name]
    return run


@pytest.mark.parametrize("path", PAGES_WITH_EXAMPLES, ids=lambda path: path.name)
def test_a_page_s_examples_run_alone_and_print_what_they_say(path, page_run):
    _namespace, wrong = page_run(str(path.relative_to(ROOT)))
    assert not wrong, "\n".join(wrong)


def test_the_pages_with_examples_are_found():
    names = {path.name for path in PAGES_WITH_EXAMPLES}
    assert {"README.md", "queries.md", "inverse-kinematics.md", "clearance.md"} <= names


def test_the_first_tree_turns_the_seam_on_a_circle(page_run):
    """README: the seam start turns with the table about the positioner's z axis, 0.2 m
    from it."""
    namespace, _ = page_run("README.md")
    seam = namespace["pose_seam_in_world"].translation
    np.testing.assert_allclose(np.hypot(seam[:, 0] - 1.5, seam[:, 1]), 0.2, atol=1e-12)
    np.testing.assert_allclose(seam[:, 2], 0.85, atol=1e-15)


def test_the_queries_page_prints_hand_derived_numbers(page_run):
    """docs/queries.md: points, velocities and the Jacobian of the turning table and arm."""
    namespace, _ = page_run("docs/queries.md")
    # the table turns 90 degrees in 10 s about z at (1.5, 0, 0.8)
    angles = np.array([0.0, np.pi / 4, np.pi / 2])
    for index, radius in enumerate([0.2, 0.25]):
        expected = np.stack([1.5 + radius * np.cos(angles), radius * np.sin(angles),
                             np.full(3, 0.85)], axis=1)
        np.testing.assert_allclose(namespace["profile_in_world"][:, index], expected,
                                   atol=1e-15)
    np.testing.assert_allclose(namespace["track_in_world"], [[1.7, 0, 0.8], [1.5, 0.2, 0.8]],
                               atol=1e-15)
    rate = np.pi / 20
    np.testing.assert_allclose(namespace["velocity_seam"].angular, [[0, 0, rate]], atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(namespace["velocity_seam"].linear), 0.2 * rate,
                               atol=1e-15)
    # joint_1 turns about the z axis of robot_base, 0.2 m up: its column is z x (p - axis)
    jacobian = namespace["jacobian_tcp"]
    tcp = namespace["tree"].pose("torch_tcp", "robot_base", times=[5.0]).translation[0]
    np.testing.assert_allclose(jacobian.matrix[0, :, 0], [-tcp[1], tcp[0], 0, 0, 0, 1],
                               atol=1e-14)
    velocity = namespace["velocity_tcp"]
    np.testing.assert_allclose(velocity.angular, [[0, 0, 0.05]], atol=1e-15)
    np.testing.assert_allclose(velocity.linear, [[-0.05 * tcp[1], 0.05 * tcp[0], 0]],
                               atol=1e-15)


def test_the_view_page_loads_the_bundled_geometry(page_run):
    """docs/view.md: 17 pieces, the torch's mesh file with its 352 triangles."""
    namespace, _ = page_run("docs/view.md")
    torch = namespace["torch"]
    assert (len(namespace["pieces"]), torch.source, torch.faces.shape) == (
        17, "meshes/torch.stl", (352, 3))
    assert namespace["page"].read_bytes().startswith(b"<!DOCTYPE html>")


def test_the_shapes_example_measures_the_probe_above_the_table(page_run):
    """docs/clearance.md: the probe's ball 0.3 m above the table top (the cylinder is
    hypot(0.3, 0.2) - 0.03 m aside), less its radius."""
    namespace, _ = page_run("docs/clearance.md")
    assert namespace["jig"].clearance("table", "probe").distance[0] == \
        pytest.approx(0.3 - 0.02, abs=1e-12)
