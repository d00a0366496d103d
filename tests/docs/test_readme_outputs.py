"""What README.md's Python examples say they print is what they print: every ``print(...)``
with a comment on its lines, run as written, prints values that the comment shows in the
same order (the comment may add words: units, what the numbers mean)."""

from __future__ import annotations

import ast
import contextlib
import io
import re
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _tokens(text: str) -> list[str]:
    """Words and numbers, without brackets, commas and quotes: ``[0.6 2.6 0. ]`` and
    ``[0.6, 2.6, 0.]`` give the same tokens."""
    return [word.rstrip(":;") for word in re.sub(r"[\[\](),'\"]", " ", text).split()]


def _shown(printed: str, comment: str) -> bool:
    """Whether every token of ``printed`` appears in ``comment``, in order."""
    rest = iter(_tokens(comment))
    return all(any(token == word for word in rest) for token in _tokens(printed))


def _commented_prints(block: str) -> list[tuple[int, int, str]]:
    """``(first line, last line, comment)`` of each print call with comments on its lines
    (and on comment lines right after it)."""
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
                found.append((node.lineno, end, " ".join(comments)))
    return found


def test_every_printed_comment_shows_what_is_printed(monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    namespace: dict = {}
    wrong = []
    for block in blocks:
        if 'if __name__ == "__main__":' in block:  # starts a cluster: tests/batch runs it
            continue
        printed: dict[int, str] = {}

        def record(*args, sep=" ", end="\n", file=None, flush=False, printed=printed):
            import sys
            line = sys._getframe(1).f_lineno
            out = io.StringIO()
            print(*args, sep=sep, end=end, file=out)
            printed[line] = printed.get(line, "") + out.getvalue()

        namespace["print"] = record
        with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("ignore")
            exec(compile(block, "README.md", "exec"), namespace)
        for first, _last, comment in _commented_prints(block):
            if first in printed and not _shown(printed[first], comment):
                wrong.append(f"{block.splitlines()[first - 1].strip()}\n  prints "
                             f"{printed[first].strip()!r}")
    assert not wrong, "\n".join(wrong)
