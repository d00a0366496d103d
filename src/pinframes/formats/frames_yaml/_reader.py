"""Reading a Duckietown ``frames.yaml`` map layer into a :class:`~pinframes.FrameTree`.

Frame names are the file's keys; a key's path makes the hierarchy (docs/frames-yaml.md). What is
needed to write the file back unchanged is kept in metadata under ``"frames_yaml"``:

``tree.metadata["frames_yaml"]``
    ``file`` (the path read) and ``top_level`` (the top-level fields in file order, such
    as ``version``, with ``frames`` mapped to None).
``tree.frame_metadata(name)["frames_yaml"]`` for a frame of the file
    ``key`` (its key), ``index`` (its position in the file), ``entry`` (its mapping as
    read: ``relative_to``, ``unit``, ``pose``, ``twist``, unknown fields), ``relative_to``
    (the frame its pose is given in, None for the key parent), ``pose_in_relative_to``
    (that pose in metres, a :class:`~pinframes.Pose`) and ``tile_size`` (``(x, y)`` metres
    for ``unit: tiles``, else None).
``tree.frame_metadata(name)["frames_yaml"]`` for a dummy frame
    ``key`` and ``dummy: True``: a missing ancestor or an undeclared ``relative_to``
    target, at the identity in its key parent.
"""

from __future__ import annotations

import os
from collections.abc import Callable

from ...errors import FileFormatError, PinframesError
from ...tree import FrameTree
from ...values.pose import Pose
from .._paths import is_regular_file
from .._registry import require_format
from ..limits import Limits, current_limits, exceeded, reader_with_limits
from ..reading import InputFile
from ._schema import (
    Entry,
    TileSize,
    key_ancestors,
    key_parent,
    load_tile_maps,
    locate_in,
    nearest_tile_size,
    parse_layer,
    tile_maps_beside,
    warn_layer,
)

__all__ = ["METADATA_KEY", "read_frames_yaml"]

METADATA_KEY = "frames_yaml"


@reader_with_limits
def read_frames_yaml(path: str | os.PathLike[str], root: str = "world", *,
                     limits: Limits | None = None) -> FrameTree:
    """Read a Duckietown ``frames.yaml`` map layer.

    Parameters
    ----------
    path : str or path-like
        The ``frames.yaml`` file. For ``unit: tiles`` frames, the ``tile_maps.yaml`` in the
        same folder gives the tile size.
    root : str
        Name of the root frame; top-level keys become its children.
    limits : Limits or None
        Bounds on what the file may cost to read (:class:`pinframes.Limits`; None: the
        defaults, or those of the reader this one is called from).

    Returns
    -------
    FrameTree
        One frame per key, named by its key, posed in its key parent (metres, radians).
        Missing ancestors and undeclared ``relative_to`` targets are dummy frames at the
        identity in their key parent. A ``relative_to`` pose is resolved into the key
        parent; the original is kept in ``tree.frame_metadata(name)["frames_yaml"]``.

    Raises
    ------
    FileFormatError
        Naming the file, key and field: YAML syntax errors, duplicate keys, wrong types,
        non-finite numbers, ``relative_to`` cycles, a missing ``tile_maps.yaml`` entry.

    Warns
    -----
    FramesYamlWarning
        For unknown fields (kept, not used) and undeclared ``relative_to`` targets.
    """
    source = InputFile.of(path)
    require_format(source, "frames.yaml")
    file = os.fspath(source)
    top_level, entries = parse_layer(source.yaml(locate_in("frames")), file)
    _check_key_depths(entries, file)
    declared = {entry.key: entry for entry in entries}
    tile_sizes = _tile_sizes(entries, file)
    offsets = {entry.key: _pose_in_relative_to(entry, tile_sizes.get(entry.key))
               for entry in entries}
    dummies = _dummies(entries, declared, file)
    for name in [*declared, *dummies]:
        if name == root:
            raise FileFormatError(
                f"the key is also the name of the root frame; pass another root= than {root!r}",
                file=file, frame=name)
    world = _world_poses(declared, dummies, offsets, root, file)

    tree = FrameTree(root=root)
    tree.metadata[METADATA_KEY] = {"file": file, "top_level": top_level}

    def add(name: str) -> None:
        chain = []  # name and its key ancestors not in the tree yet (no recursion: keys
        while name not in tree:  # may have many segments)
            chain.append(name)
            name = key_parent(name) or root
        for name in reversed(chain):
            add_one(name, key_parent(name) or root)

    def add_one(name: str, parent: str) -> None:
        entry = declared.get(name)
        if entry is None:
            tree.add(name, parent)
            tree.frame_metadata(name)[METADATA_KEY] = {"key": name, "dummy": True}
            return
        if entry.relative_to in (None, key_parent(name)):
            local = offsets[name]
        else:
            local = world[parent].inverse() @ world[name]
        tree.add(name, parent, local)
        tree.frame_metadata(name)[METADATA_KEY] = {
            "key": name, "index": entry.index, "entry": entry.raw,
            "relative_to": entry.relative_to, "pose_in_relative_to": offsets[name],
            "tile_size": tile_sizes.get(name)}

    try:
        for name in [*declared, *dummies]:
            add(name)
    except PinframesError as exc:
        raise exc.located(file=file) from exc
    return tree


def _check_key_depths(entries: list[Entry], file: str) -> None:
    """Refuse keys (and ``relative_to`` targets) of more than ``max_depth`` path segments."""
    limit = current_limits().max_depth
    for entry in entries:
        for name, field in ((entry.key, None), (entry.relative_to, "relative_to")):
            if name is not None and name.count("/") >= limit:
                raise exceeded("max_depth", f"{name.count('/') + 1:,} path segments",
                               frame=entry.key, field=field).located(file=file)


def _tile_sizes(entries: list[Entry], file: str) -> dict[str, TileSize]:
    """Tile sizes of the ``unit: tiles`` frames, from ``tile_maps.yaml`` beside ``file``."""
    tiled = [entry for entry in entries if entry.unit == "tiles"]
    if not tiled:
        return {}
    tile_maps = tile_maps_beside(file)
    if not is_regular_file(tile_maps):
        raise FileFormatError(
            f"unit 'tiles' needs the tile size from {tile_maps.name} beside this file, but "
            f"{tile_maps} does not exist", file=file, frame=tiled[0].key, field="unit")
    sizes = load_tile_maps(tile_maps)
    found = {}
    for entry in tiled:
        size = nearest_tile_size(entry.key, sizes)
        if size is None:
            raise FileFormatError(
                f"unit 'tiles' needs a tile size, but none of its ancestors "
                f"({', '.join(key_ancestors(entry.key)) or 'none'}) is listed in {tile_maps}",
                file=file, frame=entry.key, field="unit")
        found[entry.key] = size
    return found


def _pose_in_relative_to(entry: Entry, tile_size: TileSize | None) -> Pose:
    """The entry's pose in its ``relative_to`` frame, metres; tiles count from tile centres."""
    values = dict(entry.values)
    if tile_size is not None:
        values["x"] = (values["x"] + 0.5) * tile_size[0]
        values["y"] = (values["y"] + 0.5) * tile_size[1]
    return Pose.from_xyz_rpy(**values)


def _dummies(entries: list[Entry], declared: dict[str, Entry], file: str) -> dict[str, None]:
    """Undeclared frames the file implies, in order of first need: ancestors, targets."""
    dummies: dict[str, None] = {}
    warned: set[str] = set()
    for entry in entries:
        needed = key_ancestors(entry.key)
        target = entry.relative_to
        if target is not None and target not in declared:
            if target not in warned:
                warned.add(target)
                warn_layer(file, entry.key,
                      f"relative_to names {target!r}, which the file does not declare: "
                      "it is created at the identity in its key parent")
            needed += [target, *key_ancestors(target)]
        for name in needed:
            if name not in declared:
                dummies[name] = None
    return dummies


def _world_poses(declared: dict[str, Entry], dummies: dict[str, None],
                 offsets: dict[str, Pose], root: str, file: str) -> dict[str, Pose]:
    """The pose of every frame in the root, following ``relative_to`` and key parents."""

    def basis(name: str) -> str:
        entry = declared.get(name)
        if entry is not None and entry.relative_to is not None:
            return entry.relative_to
        return key_parent(name) or root

    world = {root: Pose.identity()}
    for start in [*declared, *dummies]:
        chain: list[str] = []
        name = start
        while name not in world:
            if name in chain:
                _raise_cycle(chain[chain.index(name):], basis, declared, file)
            chain.append(name)
            name = basis(name)
        for name in reversed(chain):
            offset = offsets.get(name, Pose.identity())
            world[name] = world[basis(name)] @ offset
    return world


def _raise_cycle(cycle: list[str], basis: Callable[[str], str], declared: dict[str, Entry],
                 file: str) -> None:
    """Report a cycle of frames whose poses each depend on the next."""
    links = []
    for name in cycle:
        relation = "is relative to" if declared.get(name) and (
            declared[name].relative_to is not None) else "is inside"
        links.append(f"{name!r} {relation} {basis(name)!r}")
    culprit = next(name for name in cycle
                   if declared.get(name) and declared[name].relative_to is not None)
    raise FileFormatError(f"relative_to cycle: {', '.join(links)}: no pose can be resolved",
                          file=file, frame=culprit, field="relative_to")
