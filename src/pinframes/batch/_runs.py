"""Which runs a batch computes: files, glob patterns, or a runs list (CSV).

A run is one input file of any format pinframes reads (a scene with its trajectories, an
ASDF file, a ROS bag, ...) or a ROS 2 bag folder, and a run id that names it in the output;
one input is one run. Which paths are runs is decided in :func:`_is_run_input` (the place
for another kind of input).

Run ids: a runs list (``.csv``) gives them itself: a header ``run,file`` and one line per
run, files relative to the list's folder. A glob pattern names its matches relative to the
folder where the pattern starts, without the suffix, and without the file name when the
pattern ends in one (``campaign/*/scene.yaml`` gives ``r001``; ``runs/*.asdf`` gives
``weld_1``): the id of a run does not depend on which other runs match, so a growing
campaign keeps its ids. Runs named one by one (as a shell expands a pattern) are named
relative to the folder they share, by their folders when their files all have the same
name. An output folder keeps the ids it gave: :func:`keep_known_ids`.
"""

from __future__ import annotations

import csv
import glob
import io
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import FileFormatError, ReadError
from ..formats.reading import is_regular_file, read_text, regular_file_problem

__all__ = ["RUNS_LIST_SUFFIX", "Run", "find_runs", "keep_known_ids"]

RUNS_LIST_SUFFIX = ".csv"
"""A RUNS argument ending so is a runs list; pinframes reads no tree from a CSV file."""

_GLOB_CHARACTERS = frozenset("*?[")


@dataclass(frozen=True)
class Run:
    """One run: its id in the output and the file its tree is read from; ``listed``: the
    id was given by a runs list (else derived from the path)."""

    run_id: str
    path: Path
    listed: bool = False

    @property
    def input(self) -> str:
        """The run's file as an absolute path, symbolic links resolved: what tells two runs
        apart across batches (the manifest's ``input``)."""
        return os.fspath(self.path.resolve())


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
    matched: list[Run] = []
    named: list[Path] = []
    for spec in specs:
        text = os.fspath(spec)
        if _GLOB_CHARACTERS & set(text):
            matched.extend(_matched(text))
        elif text.lower().endswith(RUNS_LIST_SUFFIX):
            listed.extend(_read_runs_list(Path(text)))
        else:
            named.extend(_run_files(text))
    runs = listed + matched + _named_by_path(named)
    _require_unique(runs)
    return runs


def _is_run_input(path: Path) -> bool:
    """Whether ``path`` is a run's input: a regular file, or a ROS 2 bag folder (read as
    one input, like a file)."""
    return is_regular_file(path) or _is_bag_folder(path)


def _is_bag_folder(path: Path) -> bool:
    return path.is_dir() and (path / "metadata.yaml").is_file()


def _run_files(text: str) -> list[Path]:
    """The run named by the argument ``text`` (see :func:`_is_run_input`)."""
    path = Path(text)
    if _is_run_input(path):
        return [path]
    raise ReadError(regular_file_problem(text) or "not a run's input", file=text)


def _matched(pattern: str) -> list[Run]:
    """The runs a glob pattern matches, named relative to its first folder with a glob
    character (see the module docstring)."""
    parts = Path(pattern).parts
    fixed = next(index for index, part in enumerate(parts) if _GLOB_CHARACTERS & set(part))
    base = Path(*parts[:fixed]) if fixed else Path(".")
    drop_name = not _GLOB_CHARACTERS & set(parts[-1])
    runs = []
    for match in sorted(glob.glob(pattern, recursive=True)):
        path = Path(match)
        if not _is_run_input(path):
            continue
        relative = path.relative_to(base)
        named = relative.parent if drop_name and relative.parent.parts else (
            relative.with_suffix(""))
        runs.append(Run(named.as_posix(), path))
    if not runs:
        raise ReadError("this pattern matches no file", file=pattern)
    return runs


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
        runs.append(Run(row[0].strip(), path.parent / row[1].strip(), listed=True))
    return runs


def _require_unique(runs: list[Run]) -> None:
    """One id per run and one run per file: a file under two ids would be computed twice
    into one dataset."""
    ids: dict[str, Path] = {}
    files: dict[str, Run] = {}
    for run in runs:
        if run.run_id in ids:
            raise FileFormatError(f"two runs have the id {run.run_id!r}: {ids[run.run_id]} "
                                  f"and {run.path}", file=run.path, field="run")
        ids[run.run_id] = run.path
        if (twin := files.get(run.input)) is not None:
            raise FileFormatError(f"the runs {twin.run_id!r} and {run.run_id!r} are one "
                                  "file: give each file once", file=run.path, field="file")
        files[run.input] = run


def keep_known_ids(runs: list[Run], records: dict[str, dict[str, Any]]
                   ) -> tuple[list[Run], list[str]]:
    """The runs with the ids an output folder gave their files before, and the ids of
    earlier records that now name no run's file any more (their file moved to another id).

    ``records`` are the manifest's, by id, each with its file's ``input``. A run whose id
    is derived from its path keeps the id its file had, unless another run of this batch
    has that id now; a run whose id a runs list gives keeps that id, and the file's old id
    is returned, to be removed: one file, one id, one set of poses in the dataset.
    """
    earlier = {record["input"]: run_id for run_id, record in records.items()
               if isinstance(record.get("input"), str)}
    taken = {run.run_id for run in runs}
    kept, moved = [], []
    for run in runs:
        old_id = earlier.get(run.input)
        if old_id is None or old_id == run.run_id:
            kept.append(run)
        elif not run.listed and old_id not in taken:
            taken.discard(run.run_id)
            taken.add(old_id)
            kept.append(Run(old_id, run.path))
        else:
            kept.append(run)
            if old_id not in taken:
                moved.append(old_id)
    return kept, moved
