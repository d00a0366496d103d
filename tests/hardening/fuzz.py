"""Fuzzing the readers: mutated sample files must give a pinframes error or a result, nothing else.

Every input is made from a sample file by one mutation chosen by ``random.Random`` seeded
with ``(seed, reader, sample, index)``, so any input can be made again from those four
values. An exception that is not a :class:`pinframes.PinframesError`, or a reader that runs
longer than :data:`HANG_SECONDS`, is a failure.

Long runs (failing inputs are written to ``--out``, one file each, with a ``.json`` record)::

    PYTHONPATH=src python tests/hardening/fuzz.py --seconds 600 --seed 7 --out /tmp/fuzz

Once fixed, a failure is kept in ``fuzz_regressions/``: its record, and its input file too
unless that was made from a shared sample file (others' files stay out of the project; such
inputs are remade from the record, and skipped where the shared files are absent).

A new reader is one line in :func:`readers` (its samples and the syntax its structure
mutations parse: ``"yaml"``, ``"xml"``, ``"csv"``, ``"asdf"`` (the YAML part, tags kept) or
``None`` for bytes only).
"""

from __future__ import annotations

import argparse
import contextlib
import copy
import csv
import hashlib
import io
import json
import math
import random
import signal
import sys
import tempfile
import time
import traceback
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

import pinframes

MODELS = Path(__file__).resolve().parents[2] / "models"
REGRESSIONS = Path(__file__).resolve().parent / "fuzz_regressions"
HANG_SECONDS = 10.0
"""A reader that takes longer than this on one input (of a few kB) is taken to hang."""

_CSV_ROWS = 40
"""The joint-trajectory samples are cut to this many lines, to keep each input quick."""

_SMALL_URDF = """<?xml version="1.0"?>
<robot name="small">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="turn" type="revolute">
    <parent link="base"/><child link="a"/><origin xyz="0 0 0.1" rpy="0 0 0.3"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="a"/><child link="b"/><origin xyz="0.2 0 0" rpy="0.1 0.2 0.3"/>
    <axis xyz="1 1 0"/><limit lower="0" upper="0.5" effort="1" velocity="1"/>
  </joint>
  <joint name="spin" type="continuous">
    <parent link="b"/><child link="c"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="follow" type="revolute">
    <parent link="c"/><child link="d"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="turn" multiplier="-0.5" offset="0.1"/>
  </joint>
</robot>
"""

_SMALL_FRAMES_YAML = """version: 1.0
frames:
  map_0:
    relative_to: ~
    pose: {x: 0.0, y: 0.0, z: 0.0, roll: 0.0, pitch: 0.0, yaw: 0.0}
  map_0/tile_0_0:
    relative_to: map_0
    unit: tiles
    pose: {x: 0, y: 0, yaw: 1.5707963}
  map_0/sign_1:
    relative_to: map_0/tile_0_0
    pose: {x: 0.1, y: -0.2, z: 0.05, roll: 0.1, pitch: 0.2, yaw: 0.3}
"""

_SMALL_TILE_MAPS = """tile_maps:
  map_0:
    tile_size: {x: 0.585, y: 0.585}
"""

_SMALL_ISO_CSV = """time,j1,j2
2024-03-01T08:00:00,0.1,0.2
2024-03-01T08:00:00.5,0.2,0.3
2024-03-01T08:00:01,0.3,0.1
"""


@dataclass(frozen=True)
class Sample:
    """One file to mutate: its name, its bytes and the files it needs beside it.

    ``target`` is the input's path relative to the fuzz folder (the scene sits where its
    URDF and trajectory references resolve); ``beside`` maps paths in that folder to the
    bytes of files the reader also opens.
    """

    name: str
    content: bytes
    target: str
    beside: dict[str, bytes] = field(default_factory=dict)


@dataclass(frozen=True)
class Reader:
    """A reader under fuzz: the call, the syntax its structure mutations parse, its samples."""

    read: Callable[[Path], object]
    syntax: str | None
    samples: tuple[Sample, ...]


def readers(shared_data: Path | None = None) -> dict[str, Reader]:
    """The readers under fuzz with their samples (``shared_data``: the shared sample files)."""
    return {
        "read_frames_yaml": Reader(pinframes.read_frames_yaml, "yaml",
                                   _frames_yaml_samples(shared_data)),
        "read_urdf": Reader(pinframes.read_urdf, "xml", _urdf_samples()),
        "read_scene": Reader(pinframes.read_scene, "yaml", _scene_samples()),
        "read_joint_trajectory": Reader(pinframes.read_joint_trajectory, "csv",
                                        _trajectory_samples()),
        "read_joint_trajectory_npz": Reader(pinframes.read_joint_trajectory, None,
                                            _npz_samples()),
        "read_asdf": Reader(pinframes.read_asdf, "asdf", _asdf_samples(shared_data)),
        "read_rosbag": Reader(pinframes.read_rosbag, None, (Sample(
            "cell_run.mcap", (MODELS / "welding_cell" / "cell_run.mcap").read_bytes(),
            "run.mcap"), *_ros1_bag_samples())),
    }


def _frames_yaml_samples(shared_data: Path | None) -> tuple[Sample, ...]:
    samples = [Sample("small_frames.yaml", _SMALL_FRAMES_YAML.encode(), "frames.yaml",
                      {"tile_maps.yaml": _SMALL_TILE_MAPS.encode()})]
    maps = shared_data / "duckietown-maps" if shared_data is not None else None
    if maps is not None and maps.is_dir():
        for path in sorted(maps.glob("**/frames.yaml")):
            tile_maps = path.with_name("tile_maps.yaml")
            beside = {"tile_maps.yaml": tile_maps.read_bytes()} if tile_maps.is_file() else {}
            samples.append(Sample(f"{path.parent.name}/frames.yaml", path.read_bytes(),
                                  "frames.yaml", beside))
    return tuple(samples)


def _urdf_samples() -> tuple[Sample, ...]:
    robot = MODELS / "welding_robot" / "welding_robot.urdf"
    return (Sample("small.urdf", _SMALL_URDF.encode(), "robot.urdf"),
            Sample("welding_robot.urdf", robot.read_bytes(), "robot.urdf"))


def _scene_samples() -> tuple[Sample, ...]:
    cell = MODELS / "welding_cell"
    beside = {"welding_robot/welding_robot.urdf":
              (MODELS / "welding_robot" / "welding_robot.urdf").read_bytes(),
              "welding_cell/robot_motion.csv": _head(cell / "robot_motion.csv")}
    return (Sample("welding_cell/scene.yaml", (cell / "scene.yaml").read_bytes(),
                   "welding_cell/scene.yaml", beside),)


def _trajectory_samples() -> tuple[Sample, ...]:
    return (Sample("robot_motion.csv", _head(MODELS / "welding_cell" / "robot_motion.csv"),
                   "motion.csv"),
            Sample("iso_times.csv", _SMALL_ISO_CSV.encode(), "motion.csv"))


def _npz_samples() -> tuple[Sample, ...]:
    """Three joints over five samples, stored plainly and compressed (bytes mutations only)."""
    arrays = {"times": np.linspace(0.0, 2.0, 5), "positions": np.arange(15.0).reshape(5, 3),
              "joint_names": np.array(["j1", "j2", "j3"])}
    samples = []
    for name, save in (("motion.npz", np.savez), ("compressed.npz", np.savez_compressed)):
        buffer = io.BytesIO()
        save(buffer, **arrays)
        samples.append(Sample(name, buffer.getvalue(), "motion.npz"))
    return tuple(samples)


def _ros1_bag_samples() -> tuple[Sample, ...]:
    """A tool moving in ``world``, 40 TFMessages in ROS 1 bags written by rosbags, their
    chunks stored plainly and compressed with bz2 and lz4 (bytes mutations only)."""
    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    kind = "tf2_msgs/msg/TFMessage"
    store = get_typestore(Stores.ROS1_NOETIC)
    store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", kind))
    types = store.types
    samples = []
    with tempfile.TemporaryDirectory() as folder:
        for compression in (None, "BZ2", "LZ4"):
            path = Path(folder) / f"tool-{compression or 'plain'}.bag"
            writer = Writer(path)
            if compression:
                writer.set_compression(Writer.CompressionFormat[compression])
            with writer:
                connection = writer.add_connection("/tf", kind, typestore=store)
                for index in range(40):
                    stamp = 1_700_000_000 * 10**9 + index * 10**8
                    header = types["std_msgs/msg/Header"](seq=index, stamp=types[
                        "builtin_interfaces/msg/Time"](sec=stamp // 10**9, nanosec=stamp % 10**9),
                        frame_id="world")
                    transform = types["geometry_msgs/msg/Transform"](
                        translation=types["geometry_msgs/msg/Vector3"](0.01 * index, 0.0, 0.5),
                        rotation=types["geometry_msgs/msg/Quaternion"](0.0, 0.0, 0.0, 1.0))
                    message = types[kind](transforms=[types["geometry_msgs/msg/TransformStamped"](
                        header=header, child_frame_id="tool", transform=transform)])
                    writer.write(connection, stamp, store.serialize_ros1(message, kind))
            samples.append(Sample(path.name, path.read_bytes(), "run.bag"))
    return tuple(samples)


def _asdf_samples(shared_data: Path | None) -> tuple[Sample, ...]:
    """The small tree in both schemas, and the shared weldx files (read where they are)."""
    samples = [Sample(f"small-{schema}.asdf", small_asdf_file(schema), "tree.asdf")
               for schema in ("1.0.0", "0.1.0")]
    weldx_files = shared_data / "weldx-files" if shared_data is not None else None
    if weldx_files is not None and weldx_files.is_dir():
        samples.extend(Sample(path.name, path.read_bytes(), "tree.asdf")
                       for path in sorted(weldx_files.glob("*.asdf")))
    return tuple(samples)


def small_asdf_file(schema: str) -> bytes:
    """The bytes of :func:`_small_asdf_tree` written by ``write_asdf`` in ``schema``."""
    with tempfile.TemporaryDirectory() as scratch:
        path = Path(scratch) / "small.asdf"
        pinframes.write_asdf(_small_asdf_tree(), path, schema)
        return path.read_bytes()


def _small_asdf_tree() -> pinframes.FrameTree:
    """Static frames (inline arrays), a moving frame of 30 samples (binary blocks) and a
    subsystem."""
    seconds = np.linspace(0.0, 2.9, 30)
    tree = pinframes.FrameTree("base", "small", "2024-03-01T08:00:00")
    tree.add("table", "base", pinframes.Pose([0.5, 0.2, 0.0], [0.0, 0.0, 0.38268343, 0.92387953]))
    tree.add("part", "table", pinframes.Pose([0.1, 0.0, 0.02]))
    tree.add("torch", "base", pinframes.Pose(
        np.stack([0.01 * seconds, np.sin(seconds), 0.3 + 0 * seconds], axis=1),
        np.stack([np.zeros(30), np.zeros(30), np.sin(seconds / 4), np.cos(seconds / 4)],
                 axis=1),
        times=seconds, reference_time="2024-03-01T08:00:01"))
    tree.subsystems = [pinframes.Subsystem("fixture", "table", ("table", "part"), "small")]
    return tree


def _head(path: Path) -> bytes:
    return b"".join(path.read_bytes().splitlines(keepends=True)[:_CSV_ROWS])


# -- mutations ---------------------------------------------------------------------------------

_TOKENS = [b"\x00", b"\xff\xfe", b"\n", b"  ", b"- ", b": ", b"{", b"[", b"]", b"}", b"'",
           b'"', b"&a ", b"*a", b"!!python/object:os.system ", b"!include ", b"<", b"/>",
           b"<!--", b"]]>", b"<!DOCTYPE x [<!ENTITY e \"e\">]>", b"&e;", b",", b"#",
           b".nan", b"-.inf", b"1e400", b"-0", b"9" * 40, b"9" * 400, b"~", b"null", b"\t",
           b"\xc3(", b"[" * 5000 + b"]" * 5000, b"{a: " * 3000 + b"1" + b"}" * 3000,
           b"<x>" * 5000 + b"</x>" * 5000, b"a,b\n" * 2000]

_ODD_VALUES = [None, "", "x", "not a number", True, False, 0, -1, 10**400, 1e308, -1e308,
               math.nan, math.inf, -math.inf, 1e-320, [], {}, [1, 2], {"a": 1}, "2s",
               "2024-13-45T99:99:99", "1e400", "nan", "-inf", "../../../etc/passwd", "..",
               "robot/", "world", "/", "a/b", 3.5, [math.nan, 0, 0], [0, 0, 0, 0]]


def mutate(content: bytes, syntax: str | None, rng: random.Random) -> bytes:
    """One mutation of ``content``: a byte mutation, or a structure mutation of its syntax."""
    if syntax is not None and rng.random() < 0.5:
        try:
            mutated = _STRUCTURE[syntax](content, rng)
        except RecursionError:  # a deeply nested input from an earlier mutation
            mutated = None
        if mutated is not None:
            return mutated
    return _byte_mutation(content, rng)


def _byte_mutation(data: bytes, rng: random.Random) -> bytes:
    buffer = bytearray(data)
    for _ in range(rng.choice((1, 1, 1, 2, 4, 16))):
        kind = rng.choice(("flip", "insert", "delete", "truncate", "duplicate", "token"))
        position = rng.randrange(len(buffer) + 1)
        if kind == "flip" and buffer:
            index = min(position, len(buffer) - 1)
            buffer[index] ^= 1 << rng.randrange(8)
        elif kind == "insert":
            buffer[position:position] = bytes(rng.randrange(256)
                                              for _ in range(rng.randint(1, 8)))
        elif kind == "delete":
            del buffer[position:position + rng.randint(1, 64)]
        elif kind == "truncate":
            del buffer[position:]
        elif kind == "duplicate":
            chunk = buffer[position:position + rng.randint(1, 200)]
            buffer[position:position] = chunk * rng.randint(1, 50)
        else:
            buffer[position:position] = rng.choice(_TOKENS)
    return bytes(buffer)


def _yaml_mutation(content: bytes, rng: random.Random) -> bytes | None:
    try:
        document = yaml.safe_load(content)
    except yaml.YAMLError:
        return None
    holders = list(_containers(document))
    if not holders:
        return None
    for _ in range(rng.choice((1, 1, 2, 3))):
        _mutate_container(rng.choice(holders), holders, rng)
    if rng.random() < 0.1:
        deep: object = rng.choice(_ODD_VALUES)
        for _ in range(rng.choice((50, 1000, 20000))):
            deep = [deep] if rng.random() < 0.5 else {"k": deep}
        _set_random(rng.choice(holders), deep, rng)
    if rng.random() < 0.1:
        _set_random(rng.choice(holders), _alias_structure(rng), rng)
    return yaml.safe_dump(document, sort_keys=False, width=rng.choice((80, 10**6))).encode()


def _alias_structure(rng: random.Random) -> list:
    """A list that dumps as YAML aliases: each level repeats the one below (an alias bomb of
    up to 10^9 nodes in a few hundred bytes), or a list that contains itself."""
    if rng.random() < 0.3:
        loop: list = []
        loop.append(loop)
        return loop
    structure: list = [rng.choice(_ODD_VALUES)]
    for _ in range(rng.choice((2, 5, 9))):
        structure = [structure] * rng.choice((2, 10))
    return structure


def _containers(node: object) -> Iterator[dict | list]:
    stack = [node]
    while stack:
        current = stack.pop()
        if isinstance(current, dict | list):
            yield current
            stack.extend(current.values() if isinstance(current, dict) else current)


def _mutate_container(holder: dict | list, holders: list, rng: random.Random) -> None:
    keys = list(holder) if isinstance(holder, dict) else list(range(len(holder)))
    kind = rng.choice(("drop", "duplicate", "retype", "swap", "rekey", "transplant"))
    if not keys:
        _set_random(holder, rng.choice(_ODD_VALUES), rng)
        return
    key = rng.choice(keys)
    if kind == "drop":
        del holder[key]
    elif kind == "duplicate":
        if isinstance(holder, dict):
            holder[f"{key}_copy"] = copy.deepcopy(holder[key])
        else:
            holder.insert(key, copy.deepcopy(holder[key]))
    elif kind == "retype":
        holder[key] = copy.deepcopy(rng.choice(_ODD_VALUES))
    elif kind == "swap":
        other = rng.choice(keys)
        holder[key], holder[other] = holder[other], holder[key]
    elif kind == "rekey" and isinstance(holder, dict):
        value = holder.pop(key)
        new_key = rng.choice([k for k in _ODD_VALUES if isinstance(k, str | int | float)])
        holder[new_key] = value
    else:
        donor = rng.choice(holders)
        donor_keys = list(donor) if isinstance(donor, dict) else list(range(len(donor)))
        if donor_keys and donor is not holder:
            holder[key] = copy.deepcopy(donor[rng.choice(donor_keys)])


def _set_random(holder: dict | list, value: object, rng: random.Random) -> None:
    if isinstance(holder, dict):
        keys = list(holder)
        holder[rng.choice(keys) if keys else "k"] = value
    elif holder:
        holder[rng.randrange(len(holder))] = value
    else:
        holder.append(value)


def _xml_mutation(content: bytes, rng: random.Random) -> bytes | None:
    try:
        root = ET.fromstring(content)
    except ET.ParseError:
        return None
    elements = list(root.iter())
    for _ in range(rng.choice((1, 1, 2, 3))):
        element = rng.choice(elements)
        kind = rng.choice(("attribute", "drop_attribute", "drop", "duplicate", "retag",
                           "nest"))
        parent = next((e for e in elements if element in list(e)), None)
        if kind == "attribute":
            names = [*element.attrib, "name", "type", "xyz", "rpy", "link", "joint",
                     "lower", "upper", "multiplier", "offset"]
            element.set(rng.choice(names), str(rng.choice(_ODD_VALUES)))
        elif kind == "drop_attribute" and element.attrib:
            del element.attrib[rng.choice(list(element.attrib))]
        elif kind == "drop" and parent is not None:
            parent.remove(element)
        elif kind == "duplicate" and parent is not None:
            parent.append(copy.deepcopy(element))
        elif kind == "retag":
            element.tag = rng.choice(("link", "joint", "origin", "axis", "limit", "mimic",
                                      "parent", "child", "robot", "visual", "x"))
        elif kind == "nest":
            inner = element
            for _ in range(rng.choice((10, 1000, 20000))):
                outer = ET.Element("visual")
                outer.append(inner)
                inner = outer
            if parent is not None:
                parent.remove(element)
                parent.append(inner)
        elements = list(root.iter())
    return ET.tostring(root, encoding="unicode").encode()


def _csv_mutation(content: bytes, rng: random.Random) -> bytes | None:
    try:
        rows = list(csv.reader(io.StringIO(content.decode("utf-8"))))
    except (UnicodeDecodeError, csv.Error):
        return None
    if not rows:
        return None
    for _ in range(rng.choice((1, 1, 2, 3))):
        row = rng.choice(rows)
        kind = rng.choice(("cell", "drop_cell", "add_cell", "drop_row", "duplicate_row",
                           "swap_rows"))
        column = rng.randrange(len(row)) if row else 0
        if kind == "cell" and row:
            row[column] = str(rng.choice(_ODD_VALUES))
        elif kind == "drop_cell" and row:
            del row[column]
        elif kind == "add_cell":
            row.insert(column, str(rng.choice(_ODD_VALUES)))
        elif kind == "drop_row":
            rows.remove(row)
        elif kind == "duplicate_row":
            rows.insert(rows.index(row), list(row))
        else:
            a, b = rng.randrange(len(rows)), rng.randrange(len(rows))
            rows[a], rows[b] = rows[b], rows[a]
        if not rows:
            return b""
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows(rows)
    return out.getvalue().encode()


_ASDF_TAG_HANDLES = {"!": "tag:stsci.edu:asdf/", "!weldx!": "asdf://weldx.bam.de/weldx/tags/",
                     "!legacy!": "tag:weldx.bam.de:weldx/"}
_ODD_TAGS = ["tag:weldx.bam.de:weldx/core/transformations/mystery-1.0.0",
             "asdf://weldx.bam.de/weldx/tags/core/time_series-0.1.0",
             "tag:stsci.edu:asdf/core/ndarray-1.0.0", "tag:yaml.org,2002:str",
             "tag:stsci.edu:asdf/core/complex-1.0.0", "tag:yaml.org,2002:binary"]


def _asdf_mutation(content: bytes, rng: random.Random) -> bytes | None:
    """Mutate the YAML tree of an ASDF file as nodes (tags kept); its blocks stay after it."""
    yaml_part, end, blocks = content.partition(b"\n...\n")
    if not end:
        return None
    try:
        document = yaml.compose(yaml_part + end, Loader=yaml.SafeLoader)
    except yaml.YAMLError:
        return None
    holders = [node for node in _nodes(document)
               if isinstance(node, yaml.MappingNode | yaml.SequenceNode)]
    if not holders:
        return None
    tags = sorted({node.tag for node in _nodes(document)} | set(_ODD_TAGS))
    for _ in range(rng.choice((1, 1, 2, 3))):
        _mutate_node(rng.choice(holders), holders, tags, rng)
    if rng.random() < 0.15:
        _extreme_grid(document, rng)
    if rng.random() < 0.1:
        _alias_node(rng.choice(holders), rng)
    headers = b"".join(line for line in yaml_part.splitlines(keepends=True)
                       if line.startswith(b"#"))
    text = yaml.serialize(document, version=(1, 1), tags=_ASDF_TAG_HANDLES,
                          explicit_start=True, explicit_end=True,
                          width=rng.choice((80, 10**6)))
    return headers + text.encode() + blocks


def _nodes(root: yaml.Node) -> Iterator[yaml.Node]:
    stack, seen = [root], set()
    while stack:
        node = stack.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        yield node
        if isinstance(node, yaml.MappingNode):
            stack.extend(part for pair in node.value for part in pair)
        elif isinstance(node, yaml.SequenceNode):
            stack.extend(node.value)


def _odd_node(rng: random.Random) -> yaml.Node:
    return yaml.compose(yaml.safe_dump(rng.choice(_ODD_VALUES)), Loader=yaml.SafeLoader)


def _mutate_node(holder: yaml.Node, holders: list[yaml.Node], tags: list[str],
                 rng: random.Random) -> None:
    """One change of a mapping or sequence node: an entry dropped, doubled, replaced by an
    odd value, swapped, moved from elsewhere, or a tag changed."""
    items = holder.value
    kind = rng.choice(("drop", "duplicate", "retype", "swap", "transplant", "retag"))
    if kind == "retag":
        rng.choice(holders).tag = rng.choice(tags)
        return
    if not items:
        items.append((_odd_node(rng), _odd_node(rng)) if isinstance(holder, yaml.MappingNode)
                     else _odd_node(rng))
        return
    index = rng.randrange(len(items))
    mapping = isinstance(holder, yaml.MappingNode)
    if kind == "drop":
        del items[index]
    elif kind == "duplicate":
        items.insert(index, copy.deepcopy(items[index]))
    elif kind == "retype":
        items[index] = (items[index][0], _odd_node(rng)) if mapping else _odd_node(rng)
    elif kind == "swap":
        other = rng.randrange(len(items))
        if mapping:
            items[index], items[other] = ((items[index][0], items[other][1]),
                                          (items[other][0], items[index][1]))
        else:
            items[index], items[other] = items[other], items[index]
    else:
        donor = rng.choice(holders)
        if donor.value and donor is not holder:
            taken = rng.choice(donor.value)
            taken = taken[1] if isinstance(donor, yaml.MappingNode) else taken
            items[index] = (items[index][0], copy.deepcopy(taken)) if mapping \
                else copy.deepcopy(taken)


_GRID_ENDS = ("P0DT0H0M0.5S", "P1DT0H0M0S", "P36500DT0H0M0S", "P-1DT0H0M0S", "P0DT0H0M0S")
_GRID_FREQUENCIES = ("1N", "1U", "1L", "3N", "0N", "-1N", "N", "99999999999999999999N", "1S")


def _extreme_grid(document: yaml.Node, rng: random.Random) -> None:
    """Turn one weldx time index into a regular grid ``{start, end, freq}`` with an extreme
    step or span (a 1 ns step over 0.5 s asks for 500 million samples)."""
    indexes = [node for node in _nodes(document)
               if isinstance(node, yaml.MappingNode) and "timedeltaindex" in (node.tag or "")]
    if not indexes:
        return
    index = rng.choice(indexes)
    duration_tag = index.tag.replace("timedeltaindex", "timedelta")
    legacy = index.tag.endswith("-1.0.0")

    def duration(text: str) -> yaml.Node:
        if legacy:
            return yaml.MappingNode(duration_tag, [(_plain("value"), _plain(text))])
        return yaml.ScalarNode(duration_tag, text)

    index.value = [(_plain("start"), duration("P0DT0H0M0S")),
                   (_plain("end"), duration(rng.choice(_GRID_ENDS))),
                   (_plain("freq"), _plain(rng.choice(_GRID_FREQUENCIES)))]


def _plain(text: str) -> yaml.ScalarNode:
    return yaml.ScalarNode("tag:yaml.org,2002:str", text)


def _alias_node(holder: yaml.Node, rng: random.Random) -> None:
    """Put an alias structure (see :func:`_alias_structure`) into ``holder`` as nodes: the
    serializer writes a node met twice as an anchor and aliases."""
    sequence = "tag:yaml.org,2002:seq"
    if rng.random() < 0.3:
        structure = yaml.SequenceNode(sequence, [])
        structure.value.append(structure)
    else:
        structure = _odd_node(rng)
        for _ in range(rng.choice((2, 5, 9))):
            structure = yaml.SequenceNode(sequence, [structure] * rng.choice((2, 10)))
    if isinstance(holder, yaml.MappingNode):
        holder.value.append((_plain(f"alias{rng.randrange(1000)}"), structure))
    else:
        holder.value.append(structure)


_STRUCTURE: dict[str, Callable[[bytes, random.Random], bytes | None]] = {
    "yaml": _yaml_mutation, "xml": _xml_mutation, "csv": _csv_mutation,
    "asdf": _asdf_mutation}


# -- running -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class Failure:
    """An input on which a reader raised something other than a pinframes error, or hung."""

    reader: str
    sample: str
    seed: int
    index: int
    error: str
    content: bytes


class _Hang(BaseException):
    """Raised by the alarm when one read takes longer than :data:`HANG_SECONDS`."""


@contextlib.contextmanager
def _time_limit(seconds: float) -> Iterator[None]:
    def alarm(signum, frame):
        raise _Hang(f"no answer within {seconds} s")

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def prepare(folder: Path, sample: Sample) -> Path:
    """Write ``sample``'s companion files into ``folder``; return where its input goes."""
    for relative, data in sample.beside.items():
        (folder / relative).parent.mkdir(parents=True, exist_ok=True)
        (folder / relative).write_bytes(data)
    target = folder / sample.target
    target.parent.mkdir(parents=True, exist_ok=True)
    return target


def read_once(reader: Reader, target: Path, content: bytes) -> str | None:
    """Feed ``content`` to ``reader``; the failure description, or None when it behaved."""
    target.write_bytes(content)
    try:
        with warnings.catch_warnings(), _time_limit(HANG_SECONDS):
            warnings.simplefilter("ignore")
            reader.read(target)
    except pinframes.PinframesError:
        return None
    except (Exception, _Hang) as exc:
        frames = traceback.extract_tb(exc.__traceback__)
        where = frames[-1] if frames else None
        place = f" at {Path(where.filename).name}:{where.lineno}" if where else ""
        return f"{type(exc).__name__}{place}: {str(exc)[:300]}"
    return None


def make_input(reader: Reader, sample: Sample, name: str, seed: int, index: int) -> bytes:
    """The input number ``index`` for ``sample`` of reader ``name`` under ``seed``."""
    rng = random.Random(f"{seed}/{name}/{sample.name}/{index}")
    return mutate(sample.content, reader.syntax, rng)


def fuzz(reader_table: dict[str, Reader], folder: Path, seed: int,
         count: int | None = None, seconds: float | None = None
         ) -> tuple[dict[str, int], list[Failure]]:
    """Try ``count`` inputs per reader, or as many as fit in ``seconds``, round robin.

    Returns the number of inputs tried per reader and the failures.
    """
    tried = dict.fromkeys(reader_table, 0)
    failures: list[Failure] = []
    targets = {}
    for name, reader in reader_table.items():
        for sample in reader.samples:
            place = folder / f"{name}-{len(targets)}"
            targets[name, sample.name] = prepare(place, sample)
    deadline = None if seconds is None else time.monotonic() + seconds
    index = 0
    while (count is None or index < count) and (deadline is None
                                                 or time.monotonic() < deadline):
        for name, reader in reader_table.items():
            sample = reader.samples[index % len(reader.samples)]
            content = make_input(reader, sample, name, seed, index)
            error = read_once(reader, targets[name, sample.name], content)
            tried[name] += 1
            if error is not None:
                failures.append(Failure(name, sample.name, seed, index, error, content))
        index += 1
    return tried, failures


def regression_inputs() -> list[Path]:
    """The records (``.json``) of kept inputs that once failed."""
    return sorted(REGRESSIONS.glob("*.json"))


class SampleMissing(LookupError):
    """A kept input is remade from a shared sample file that is not on this machine."""


def replay(reader_table: dict[str, Reader], record_path: Path, folder: Path) -> str | None:
    """Read a kept input again: the file beside its record, else remade from seed and index.

    Remade inputs depend on the mutation code. Inputs made from the shared sample files
    (others' files, never copied into the project) and large inputs are kept that way.

    Raises
    ------
    SampleMissing
        The input is to be remade from a shared sample that is absent.
    """
    record = json.loads(record_path.read_text())
    reader = reader_table[record["reader"]]
    sample = next((s for s in reader.samples if s.name == record["sample"]), None)
    if sample is None:
        raise SampleMissing(record["sample"])
    content_path = record_path.with_suffix("")
    if content_path.is_file():
        content = content_path.read_bytes()
    else:
        content = make_input(reader, sample, record["reader"], record["seed"], record["index"])
    return read_once(reader, prepare(folder, sample), content)


def _save(failure: Failure, out: Path) -> Path:
    digest = hashlib.sha1(failure.content).hexdigest()[:10]
    suffix = Path(failure.sample).suffix
    path = out / f"{failure.reader}__{digest}{suffix}"
    path.write_bytes(failure.content)
    record = {"reader": failure.reader, "sample": failure.sample, "seed": failure.seed,
              "index": failure.index, "error": failure.error}
    path.with_suffix(suffix + ".json").write_text(json.dumps(record, indent=1) + "\n")
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=Path("fuzz-failures"))
    parser.add_argument("--reader", action="append", help="fuzz only these readers")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from conftest import SHARED_DATA

    table = readers(SHARED_DATA)
    if args.reader:
        table = {name: table[name] for name in args.reader}
    with tempfile.TemporaryDirectory() as scratch:
        tried, failures = fuzz(table, Path(scratch), args.seed, seconds=args.seconds)
    args.out.mkdir(parents=True, exist_ok=True)
    kinds: dict[str, set[str]] = {}
    for failure in failures:
        _save(failure, args.out)
        kinds.setdefault(failure.reader, set()).add(failure.error.split(":")[0])
    for name, number in tried.items():
        found = [f for f in failures if f.reader == name]
        print(f"{name}: {number} inputs, {len(found)} failures"
              + (f" ({'; '.join(sorted(kinds[name]))})" if found else ""))
    print(f"seed {args.seed}, {args.seconds:.0f} s: {sum(tried.values())} inputs, "
          f"{len(failures)} failures" + (f", written to {args.out}" if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
