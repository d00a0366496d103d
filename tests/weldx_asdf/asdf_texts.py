"""Small weldx ASDF files written as text in tests (no weldx, no pinframes code).

Tags: ``!weldx!`` is the current ``asdf://weldx.bam.de/weldx/tags/`` prefix, ``!legacy!`` the
1.0.0 ``tag:weldx.bam.de:weldx/`` prefix, ``!`` asdf's core. Helpers make flow-style YAML
snippets for one line of a hierarchy.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import numpy as np

HEADER = """\
#ASDF 1.0.0
#ASDF_STANDARD 1.5.0
%YAML 1.1
%TAG ! tag:stsci.edu:asdf/
%TAG !weldx! asdf://weldx.bam.de/weldx/tags/
%TAG !legacy! tag:weldx.bam.de:weldx/
--- !core/asdf-1.1.0
"""


def asdf_text(body: str) -> str:
    """The text of an ASDF file whose YAML tree is ``body`` (dedented)."""
    return HEADER + textwrap.dedent(body).strip("\n") + "\n...\n"


def write_asdf_text(path: Path, body: str) -> Path:
    """Write an ASDF file whose YAML tree is ``body`` (dedented); return its path."""
    path.write_text(asdf_text(body))
    return path


def ndarray(values) -> str:
    """An inline ``core/ndarray`` of float64 (int64 for integer input)."""
    array = np.asarray(values)
    datatype = "int64" if array.dtype.kind in "iu" else "float64"
    return (f"!core/ndarray-1.0.0 {{data: {json.dumps(array.tolist())}, datatype: {datatype}, "
            f"shape: {list(array.shape)}}}")


def variable(name: str, values, *, units: str | None = None, legacy: bool = False) -> str:
    """A ``core/variable`` holding ``values``; a leading time axis when they are stacked."""
    array = np.asarray(values, dtype=float)
    dims = {"orientations": ["c", "v"], "coordinates": ["c"]}[name]
    if array.ndim > len(dims):
        dims = ["time", *dims]
    tag = "!legacy!core/variable-1.0.0" if legacy else "!weldx!core/variable-0.1.1"
    unit = "" if units is None else (f", unit: {units}" if legacy else
                                     f", units: !weldx!units/units-0.1.0 {units}")
    return (f"{tag} {{name: {name}, dimensions: [{', '.join(dims)}], dtype: <f8{unit}, "
            f"data: {ndarray(array)}}}")


def duration(text: str, *, legacy: bool = False) -> str:
    """A ``time/timedelta`` such as ``P0DT0H0M4S``."""
    return f"!legacy!time/timedelta-1.0.0 {{value: {text}}}" if legacy \
        else f"!weldx!time/timedelta-0.1.0 {text}"


def stamp(text: str, *, legacy: bool = False) -> str:
    """A ``time/timestamp`` such as ``2024-03-01T08:00:00``."""
    return f"!legacy!time/timestamp-1.0.0 {{value: '{text}'}}" if legacy \
        else f"!weldx!time/timestamp-0.1.0 '{text}'"


def time_values(nanoseconds, *, legacy: bool = False) -> str:
    """A ``time/timedeltaindex`` with explicit int64 nanosecond values."""
    tag = "!legacy!time/timedeltaindex-1.0.0" if legacy else "!weldx!time/timedeltaindex-0.1.0"
    return f"{tag} {{values: {ndarray(np.asarray(nanoseconds, dtype=np.int64))}}}"


def time_grid(start: str, end: str, freq: str, *, legacy: bool = False) -> str:
    """A regular ``time/timedeltaindex`` grid without values."""
    tag = "!legacy!time/timedeltaindex-1.0.0" if legacy else "!weldx!time/timedeltaindex-0.1.0"
    return (f"{tag} {{start: {duration(start, legacy=legacy)}, "
            f"end: {duration(end, legacy=legacy)}, freq: {freq}}}")


def lcs(*, orientations=None, coordinates=None, units: str | None = "millimeter",
        time: str | None = None, reference_time: str | None = None,
        version: str = "0.1.1") -> str:
    """A ``local_coordinate_system`` of ``version`` ("1.0.0", "0.1.0" or "0.1.1")."""
    legacy = version == "1.0.0"
    unit = units if version == "0.1.1" else None
    parts = []
    if time is not None:
        parts.append(f"time: {time}")
    if reference_time is not None:
        parts.append(f"reference_time: {stamp(reference_time, legacy=legacy)}")
    if orientations is not None:
        parts.append(f"orientations: {variable('orientations', orientations, legacy=legacy)}")
    if coordinates is not None:
        parts.append(f"coordinates: "
                     f"{variable('coordinates', coordinates, units=unit, legacy=legacy)}")
    prefix = "!legacy!" if legacy else "!weldx!"
    return f"{prefix}core/transformations/local_coordinate_system-{version} {{{', '.join(parts)}}}"


def legacy_hierarchy(name: str, root: str, entries, *, reference_time: str | None = None,
                     extra: str = "") -> str:
    """A 1.0.0 hierarchy under key ``csm``; ``entries`` are ``(name, reference_system, lcs)``."""
    lines = ["csm: !legacy!core/transformations/coordinate_system_hierarchy-1.0.0",
             f"  name: {name}", f"  root_system_name: {root}"]
    if reference_time is not None:
        lines.append(f"  reference_time: {stamp(reference_time, legacy=True)}")
    lines.append("  coordinate_systems:" + ("" if entries else " []"))
    for child, reference, transformation in entries:
        lines.append("  - !legacy!core/transformations/coordinate_transformation-1.0.0 "
                     f"{{name: {child}, reference_system: {reference}, "
                     f"transformation: {transformation}}}")
    return "\n".join(lines) + ("\n" + textwrap.indent(textwrap.dedent(extra), "  ")
                               if extra else "")


def digraph_node(name: str, edges=()) -> str:
    """A ``di_node`` (flow style); ``edges`` are ``(direction, lcs, target_node)``."""
    rendered = ", ".join(
        f"!weldx!core/graph/di_edge-0.1.0 {{direction: {direction}, attributes: "
        f"{{defined: true, transformation: {transformation}}}, target_node: {target}}}"
        for direction, transformation, target in edges)
    edge_part = f", edges: [{rendered}]" if edges else ""
    return (f"!weldx!core/graph/di_node-0.1.0 {{name: {name}, attributes: {{data: {{}}}}"
            f"{edge_part}}}")


def digraph_hierarchy(name: str, root_node: str, *, reference_time: str | None = None,
                      subsystems: str | None = None, key: str = "csm") -> str:
    """A 0.1.0 hierarchy (weldx 0.5 to 0.8) under ``key``."""
    lines = [f"{key}: !weldx!core/transformations/coordinate_system_hierarchy-0.1.0",
             f"  name: {name}"]
    if reference_time is not None:
        lines.append(f"  reference_time: {stamp(reference_time)}")
    lines.append(f"  graph: !weldx!core/graph/di_graph-0.1.0 {{root_node: {root_node}}}")
    if subsystems is not None:
        lines.append(f"  subsystems: {subsystems}")
    return "\n".join(lines)
