"""Opening weldx ASDF files as raw tagged data, and decoding their arrays and times.

Every weldx object is read as asdf's raw tagged data (``TaggedDict``, ``TaggedString``), never
through weldx's converters, so the result does not depend on whether weldx is installed.
Times come out as int64 nanoseconds (docs/asdf-format.md).
"""

from __future__ import annotations

import contextlib
import os
import re
import warnings
from collections.abc import Iterator
from typing import Any

import numpy as np
import yaml
from numpy.typing import NDArray

from ...errors import FileFormatError, PinframesError, ReadError
from ...values.timeconv import parse_timedelta, parse_timestamp
from .._paths import check_regular_file
from ..limits import current_limits, exceeded
from ._asdf_config import temporary_asdf_config
from ._bounds import check_asdf_yaml
from ._depth import MAX_GRAPH_DEPTH, deepest_frame_in_yaml, recursion_room, too_deep

__all__ = [
    "as_list",
    "float_array",
    "open_raw_tree",
    "raw_tag",
    "required",
    "time_index_ns",
    "timestamp",
    "weldx_tag",
]

_TAG_PREFIXES = ("asdf://weldx.bam.de/weldx/tags/", "tag:weldx.bam.de:weldx/")
_WELDX_EXTENSION_PREFIX = "asdf://weldx.bam.de/"
_WELDX_WARNINGS = (
    r"(asdf://weldx\.bam\.de/|tag:weldx\.bam\.de:)\S* is not recognized",
    r"(?s).*created with extension (URI 'asdf://weldx\.bam\.de/|class 'weldx\.)",
    # weldx up to 0.3 tagged units with the ASDF standard's unit tag, which asdf leaves to
    # asdf-astropy; pinframes reads the unit's text itself
    r"tag:stsci\.edu:asdf/unit/unit-\S* is not recognized",
)
_TAG = re.compile(r"^(?P<path>.+)-(?P<version>\d+\.\d+\.\d+)$")
# Frequency aliases of older pandas versions (docs/asdf-format.md), as units pinframes reads.
_PANDAS_FREQUENCY_ALIASES = {"H": "h", "T": "min", "S": "s", "L": "ms", "U": "us", "N": "ns",
                             "D": "d"}
_FREQUENCY = re.compile(r"^\s*(\d*)\s*([A-Za-zµ]+)\s*$")
# What numpy and asdf's lazy block reading raise for broken arrays; a block header claiming
# more bytes than any memory holds is a MemoryError.
DECODING_ERRORS = (ValueError, TypeError, KeyError, IndexError, OSError, AttributeError,
                    MemoryError, OverflowError)


@contextlib.contextmanager
def open_raw_tree(path: str | os.PathLike[str]) -> Iterator[dict[str, Any]]:
    """The tree of the ASDF file at ``path`` as raw tagged data, while the file is open.

    weldx's own asdf extensions are switched off for the read, and asdf's warnings about
    the weldx tags it then does not recognise are silenced (only those, and the ASDF
    standard's unit tag of old weldx files, whose text pinframes reads).

    Raises
    ------
    ReadError
        The file is missing or cannot be read.
    FileFormatError
        The file is not ASDF (or its YAML is broken).
    UnsupportedFeatureError
        Its YAML nests too deeply for asdf (a weldx graph deeper than MAX_GRAPH_DEPTH).
    """
    import asdf

    check_asdf_yaml(check_regular_file(path))
    with temporary_asdf_config() as config, warnings.catch_warnings():
        for extension in config.extensions:
            if (extension.extension_uri or "").startswith(_WELDX_EXTENSION_PREFIX):
                config.remove_extension(extension)
        for message in _WELDX_WARNINGS:
            warnings.filterwarnings("ignore", message=message)
        try:
            with recursion_room(MAX_GRAPH_DEPTH):
                opened = asdf.open(path, lazy_tree=False, memmap=False)
        except (RecursionError, yaml.YAMLError) as exc:
            raise _unparsed_yaml(path, exc) from None
        except OSError as exc:
            raise ReadError(f"cannot read the file: {exc}", file=path) from None
        except Exception as exc:  # asdf and yaml raise many kinds for a non-ASDF file
            raise FileFormatError(f"not a readable ASDF file: {first_line(exc)}",
                                  file=path) from None
        with opened as asdf_file:
            yield asdf_file.tree


def _unparsed_yaml(path: str | os.PathLike[str], exc: BaseException) -> PinframesError:
    """The error for YAML that asdf could not parse: a weldx graph nested deeper than
    MAX_GRAPH_DEPTH frames (libyaml stops at 1,000 levels since PyYAML 6.0.4, the pure-Python
    parser at Python's recursion limit), else a :class:`FileFormatError` with the parser's
    problem and line."""
    deepest, depth = deepest_frame_in_yaml(path)
    if depth > MAX_GRAPH_DEPTH:
        return too_deep(deepest, depth, path)
    if isinstance(exc, RecursionError):
        problem = "exceeded maximum nesting depth (Python's recursion limit)"
    elif isinstance(exc, yaml.MarkedYAMLError) and exc.problem:
        where = f" at line {exc.problem_mark.line + 1}" if exc.problem_mark else ""
        problem = f"{exc.problem}{where}"
    else:
        problem = first_line(exc)
    return FileFormatError(f"not a readable ASDF file: {problem}", file=path)


def weldx_tag(node: Any) -> tuple[str, str] | None:
    """``(path, version)`` of a weldx tag, e.g. ``("time/timedelta", "0.1.0")``, else None."""
    tag = raw_tag(node)
    if tag is None:
        return None
    for prefix in _TAG_PREFIXES:
        if tag.startswith(prefix):
            match = _TAG.match(tag[len(prefix):])
            if match:
                return match.group("path"), match.group("version")
    return None


def raw_tag(node: Any) -> str | None:
    """The YAML tag of a tagged mapping, list or string as asdf reads it, else None.

    Arrays are never asked (their attributes would load their binary blocks).
    """
    from asdf.tagged import Tagged

    tag = node._tag if isinstance(node, Tagged) else None
    return tag if isinstance(tag, str) else None


def required(node: Any, key: str, field: str) -> Any:
    """``node[key]``, or a :class:`FileFormatError` at ``field`` when it is missing."""
    if not isinstance(node, dict):
        raise FileFormatError(f"expected a mapping, got {type(node).__name__}", field=field)
    if key not in node:
        raise FileFormatError(f"the required field {key!r} is missing", field=field)
    return node[key]


def as_list(value: Any, field: str) -> list[Any]:
    """``value`` if it is a list, else a :class:`FileFormatError` at ``field``."""
    if not isinstance(value, list):
        raise FileFormatError(f"expected a list, got {type(value).__name__}", field=field)
    return value


def float_array(value: Any, field: str) -> NDArray[np.float64]:
    """An ndarray (inline, in a binary block, or a plain number/list) as a float array
    (its size and source checked before, by ``_arrays.check_arrays``)."""
    try:
        return np.array(value, dtype=float)
    except DECODING_ERRORS as exc:
        raise FileFormatError(f"cannot read the numbers: {first_line(exc)}",
                              field=field) from None


def timestamp(value: Any, field: str) -> np.datetime64:
    """A weldx timestamp (``{value: ...}`` in 1.0.0, a plain string in 0.1.0)."""
    return parse_timestamp(_scalar_value(value, field), field=field)


def timedelta_ns(value: Any, field: str) -> int:
    """A weldx duration (``P0DT0H0M4.4S``, negative as ``P-1DT23H59M59S``) in nanoseconds."""
    return int(parse_timedelta(_scalar_value(value, field), field=field).astype(np.int64))


def time_index_ns(node: Any, field: str) -> NDArray[np.int64]:
    """A weldx ``timedeltaindex`` as int64 nanoseconds.

    Either explicit ``values`` (nanoseconds) or a regular grid ``{start, end, freq}``: every
    ``start + k * freq`` up to ``end``, as pandas' ``timedelta_range`` makes it.
    """
    if isinstance(node, dict) and "values" in node:
        try:
            values = np.array(node["values"])
        except DECODING_ERRORS as exc:
            raise FileFormatError(f"cannot read the times: {first_line(exc)}",
                                  field=f"{field}.values") from None
        if values.ndim != 1 or values.dtype.kind not in "iu":
            raise FileFormatError(
                f"expected a 1-D array of integer nanoseconds, got {values.dtype} of shape "
                f"{values.shape}", field=f"{field}.values")
        if values.dtype.kind == "u" and values.size and values.max() > np.iinfo(np.int64).max:
            raise FileFormatError("unsigned nanoseconds beyond int64 (over 292 years); "
                                  "numpy would wrap them around to negative times",
                                  field=f"{field}.values")
        _check_sample_count(values.shape[0], field)
        return values.astype(np.int64)
    start = timedelta_ns(required(node, "start", field), f"{field}.start")
    end = timedelta_ns(required(node, "end", field), f"{field}.end")
    step = _frequency_ns(required(node, "freq", field), f"{field}.freq")
    if end < start:
        raise FileFormatError(f"the grid ends ({end} ns) before it starts ({start} ns)",
                              field=field)
    _check_sample_count((end - start) // step + 1, field)  # before allocating the grid
    return start + step * np.arange((end - start) // step + 1, dtype=np.int64)


def _check_sample_count(count: int, field: str) -> None:
    if count > current_limits().max_samples:
        raise exceeded("max_samples", f"the time axis has {count:,} samples", field=field)


def _frequency_ns(value: Any, field: str) -> int:
    """A pandas frequency such as ``500ms``, ``10s`` or the older ``500L``, ``S``, in ns."""
    match = _FREQUENCY.match(str(value))
    if not match:
        raise FileFormatError(f"cannot read the frequency {value!r}", field=field)
    count, unit = match.groups()
    unit = _PANDAS_FREQUENCY_ALIASES.get(unit, unit)
    step = int(parse_timedelta(f"{count or 1}{unit}", field=field).astype(np.int64))
    if step <= 0:
        raise FileFormatError(f"the frequency {value!r} is not positive", field=field)
    return step


def _scalar_value(value: Any, field: str) -> Any:
    """The ``value`` of a 1.0.0 ``{value: ...}`` object, or the value itself."""
    if isinstance(value, dict):
        return required(value, "value", field)
    return value


def first_line(exc: BaseException) -> str:
    if isinstance(exc, PinframesError):
        return exc.message
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__
