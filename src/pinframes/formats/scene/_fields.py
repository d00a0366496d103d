"""Typed values of a scene's fields: each error names the scene file, the frame and the field.

Lengths in metres, angles in radians, times in seconds.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import numpy as np

from ...errors import FileFormatError, PinframesError
from ...values.timeconv import parse_timestamp
from .._paths import regular_file_problem

_NUMBER_AS_TEXT = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)[eE][-+]?\d+")
"""A number with an exponent, which YAML 1.1 reads as text unless it has a dot and the
exponent a sign (``1e3`` and ``1.0e3`` are text, ``1.0e+3`` a number)."""


def _got(value: Any) -> str:
    """``value`` as an error message shows it, with why YAML read it as text when it looks
    like a number with an exponent."""
    if isinstance(value, str) and _NUMBER_AS_TEXT.fullmatch(value.strip()):
        return (f"the text {value!r} (YAML reads a number with an exponent as text unless "
                "it has a dot and a signed exponent: write 1.0e+3, not 1e3 or 1.0e3)")
    return repr(value)


class SceneFields:
    """Reads the values of one scene file's fields; ``path`` is that scene file."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def check_keys(self, item: Any, allowed: set[str], frame: str | None, field: str) -> None:
        """Refuse ``item`` unless it is a mapping with keys among ``allowed``."""
        if not isinstance(item, dict):
            raise FileFormatError(f"expected a mapping, got {type(item).__name__}",
                                  file=self.path, frame=frame, field=field or None)
        unknown = sorted(str(key) for key in item if key not in allowed)
        if unknown:
            raise FileFormatError(
                f"unknown key(s) {', '.join(unknown)}; expected {', '.join(sorted(allowed))}",
                file=self.path, frame=frame, field=field or None)

    def name(self, value: Any, frame: str | None, field: str) -> str:
        """A non-empty string."""
        if not isinstance(value, str) or not value:
            raise FileFormatError(f"expected a non-empty string, got {value!r}",
                                  file=self.path, frame=frame, field=field)
        return value

    def prefix(self, item: dict, frame: str | None, field: str) -> str:
        """The entry's ``prefix`` for the names it adds (empty when not given)."""
        prefix = item.get("prefix", "")
        if not isinstance(prefix, str):
            raise FileFormatError(f"expected a string, got {prefix!r}", file=self.path,
                                  frame=frame, field=f"{field}.prefix")
        return prefix

    def file(self, item: dict, key: str, frame: str | None, field: str) -> Path:
        """The regular file ``item[key]`` names, relative to the scene's folder."""
        if key not in item:
            raise FileFormatError("missing", file=self.path, frame=frame, field=f"{field}.{key}")
        value = self.name(item[key], frame, f"{field}.{key}")
        path = self.path.parent / value
        if (problem := regular_file_problem(path)) is not None:
            raise FileFormatError(f"{problem}: {path}", file=self.path, frame=frame,
                                  field=f"{field}.{key}")
        return path

    def folders(self, item: dict, frame: str | None, field: str) -> list[str]:
        """A robot's ``package_dirs``: folders relative to the scene's."""
        value = item.get("package_dirs", [])
        if not isinstance(value, list):
            raise FileFormatError(f"expected a list of folders, got {type(value).__name__}",
                                  file=self.path, frame=frame, field=f"{field}.package_dirs")
        folders = []
        for index, entry in enumerate(value):
            name = self.name(entry, frame, f"{field}.package_dirs[{index}]")
            folder = self.path.parent / name
            if not folder.is_dir():
                raise FileFormatError(f"no such folder: {folder}", file=self.path, frame=frame,
                                      field=f"{field}.package_dirs[{index}]")
            folders.append(str(folder))
        return folders

    def flag(self, item: dict, key: str, frame: str | None, field: str) -> bool:
        """A ``true``/``false`` entry (False when absent)."""
        value = item.get(key, False)
        if not isinstance(value, bool):
            raise FileFormatError(f"expected true or false, got {value!r}", file=self.path,
                                  frame=frame, field=f"{field}.{key}")
        return value

    def xacro_args(self, item: dict, frame: str | None, field: str) -> dict[str, str] | None:
        """A robot's ``xacro_args``: names to text, numbers or booleans."""
        value = item.get("xacro_args")
        if value is None:
            return None
        if not isinstance(value, dict) or not all(
                isinstance(key, str) and isinstance(text, (str, int, float, bool))
                for key, text in value.items()):
            raise FileFormatError("expected a mapping of argument names to text, numbers or "
                                  "booleans", file=self.path, frame=frame,
                                  field=f"{field}.xacro_args")
        return {key: ("true" if text else "false") if isinstance(text, bool) else str(text)
                for key, text in value.items()}

    def numbers(self, value: Any, count: int, frame: str | None, field: str) -> np.ndarray:
        """A list of ``count`` finite numbers as a (count,) array."""
        values = value.tolist() if isinstance(value, np.ndarray) else value
        if (not isinstance(values, (list, tuple)) or len(values) != count
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                           for v in values)):
            shown = next((_got(v) for v in values if isinstance(v, str)), repr(value)) if (
                isinstance(values, (list, tuple))) else _got(value)
            raise FileFormatError(f"expected a list of {count} numbers, got {shown}",
                                  file=self.path, frame=frame, field=field)
        try:
            array = np.array(values, dtype=float)
        except OverflowError:  # an integer too large for a float
            array = np.full(count, np.inf)
        if not np.all(np.isfinite(array)):
            raise FileFormatError("values must be finite", file=self.path, frame=frame,
                                  field=field)
        return array

    def vectors(self, value: Any, frame: str | None, field: str) -> np.ndarray:
        """A list of [x, y, z] lists as an (N, 3) array."""
        if not isinstance(value, list) or not value:
            raise FileFormatError("expected a non-empty list of [x, y, z] lists",
                                  file=self.path, frame=frame, field=field)
        return np.array([self.numbers(row, 3, frame, f"{field}[{index}]")
                         for index, row in enumerate(value)])

    def number(self, value: Any, frame: str | None, field: str) -> float:
        """One finite number."""
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise FileFormatError(f"expected a number, got {_got(value)}", file=self.path,
                                  frame=frame, field=field)
        try:
            number = float(value)
        except OverflowError:  # an integer too large for a float
            number = np.inf
        if not np.isfinite(number):
            raise FileFormatError("the value must be finite", file=self.path, frame=frame,
                                  field=field)
        return number

    def positive(self, value: Any, frame: str | None, field: str) -> float:
        """One finite number above zero."""
        number = self.number(value, frame, field)
        if number <= 0.0:
            raise FileFormatError(f"expected a positive number, got {value!r}",
                                  file=self.path, frame=frame, field=field)
        return number

    def timestamp(self, value: Any, frame: str | None, field: str) -> np.datetime64:
        """An absolute time (a reference time)."""
        try:
            return parse_timestamp(value, field=field)
        except PinframesError as exc:
            raise FileFormatError(exc.message, file=self.path, frame=frame,
                                  field=field) from None
