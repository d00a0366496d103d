"""Which runs a batch computes: files, glob patterns, or a runs list (CSV).

A run is one input file of any format pinframes reads (a scene with its trajectories, an
ASDF file, a ROS bag, ...), or a ROS 2 bag folder, and a run id that names it in the output.
Run ids come from the paths: the path relative to the folder all runs share, without the
suffix; when every run file has the same name (``campaign/r001/scene.yaml``,
``campaign/r002/scene.yaml``) the folder alone (``r001``). A runs list (``.csv``) gives the
ids itself: a header ``run,file`` and one line per run, files relative to the list's folder.
"""

from __future__ import annotations

import csv
import glob
import io
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from ..errors import FileFormatError, ReadError
from ..formats.reading import read_text

__all__ = ["RUNS_LIST_SUFFIX", "Run", "find_runs"]

RUNS_LIST_SUFFIX = ".csv"
"""A RUNS argument ending so is a runs list; pinframes reads no tree from a CSV file."""

_GLOB_CHARACTERS = frozenset("*?[")


@dataclass(frozen=True)
class Run:
    """One run: its id in the output and the file its tree is read from."""

    run_id: str
    path: Path


def find_runs(specs: Iterable[str | os.PathLike[str]]) -> list[Run]:
    """The runs named by ``specs`` (files, glob patterns, runs lists), in the given order.

    Raises
    ------
    ReadError
        A file is missing or a pattern matches nothing.
    FileFormatError
        A runs list is malformed, or two runs get the same id.
    """
    listed: list[Run] = []
    found: list[Path] = []
    for spec in specs:
        text = os.fspath(spec)
        if _GLOB_CHARACTERS & set(text):
            matches = sorted(glob.glob(text, recursive=True))
            if not matches:
                raise ReadError("this pattern matches no file", file=text)
            found.extend(Path(match) for match in matches
                         if Path(match).is_file() or _is_bag_folder(Path(match)))
        elif text.lower().endswith(RUNS_LIST_SUFFIX):
            listed.extend(_read_runs_list(Path(text)))
        elif Path(text).is_file() or _is_bag_folder(Path(text)):
            found.append(Path(text))
        else:
            raise ReadError("is a folder, not a file" if Path(text).is_dir() else
                            "no such file", file=text)
    runs = listed + _named_by_path(found)
    _require_unique(runs)
    return runs


def _is_bag_folder(path: Path) -> bool:
    """A ROS 2 bag folder: read as one input, like a file."""
    return path.is_dir() and (path / "metadata.yaml").is_file()


def _named_by_path(paths: list[Path]) -> list[Run]:
    """Runs for ``paths``, named by their paths relative to the folder they share."""
    if not paths:
        return []
    absolute = [path.resolve() for path in paths]
    common = Path(os.path.commonpath([path.parent for path in absolute]))
    same_name = len({path.name for path in absolute}) == 1 and len(absolute) > 1
    runs = []
    for path, full in zip(paths, absolute, strict=True):
        relative = full.parent.relative_to(common) if same_name else (
            full.relative_to(common).with_suffix(""))
        runs.append(Run(relative.as_posix() if relative.parts else full.stem, path))
    return runs


def _read_runs_list(path: Path) -> list[Run]:
    """The runs of a runs list: header ``run,file``, files relative to the list."""
    lines = [(number, row) for number, row in
             enumerate(csv.reader(io.StringIO(read_text(path))), start=1) if row]
    if not lines or [cell.strip() for cell in lines[0][1]] != ["run", "file"]:
        raise FileFormatError("a runs list starts with the header line 'run,file'",
                              file=path, field="header")
    runs = []
    for number, row in lines[1:]:
        if len(row) != 2 or not row[0].strip() or not row[1].strip():
            raise FileFormatError(f"expected a run id and a file, got {','.join(row)!r}",
                                  file=path, field=f"line {number}")
        runs.append(Run(row[0].strip(), path.parent / row[1].strip()))
    return runs


def _require_unique(runs: list[Run]) -> None:
    seen: dict[str, Path] = {}
    for run in runs:
        if run.run_id in seen:
            raise FileFormatError(f"two runs have the id {run.run_id!r}: {seen[run.run_id]} "
                                  f"and {run.path}", file=run.path, field="run")
        seen[run.run_id] = run.path
