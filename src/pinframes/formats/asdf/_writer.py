"""``write_asdf``: a :class:`FrameTree` as a weldx coordinate system hierarchy in ASDF.

Every frame but the root is written as its pose in its parent (never parent-in-child), the
root and then parents before children. Moving frames keep their keyframe times explicitly
(never as a regular ``freq`` grid) and their own reference times. Links driven by robot joints
become frames sampled at their joint's trajectory times (static links: static frames); ASDF
has no joints. Subsystems keep their names, roots, members, data names and nesting. Data
attached to frames goes into their graph nodes (schema 0.1.0 only).
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from ...errors import ArgumentTypeError, TreeStructureError, UnsupportedFeatureError, WriteError
from ...tree import FrameTree
from ...values.pose import Pose
from ...values.subsystem import Subsystem
from .._joint_steps import check_joint_steps
from .._writable import check_writable_tree, refuse_attached_data
from ..atomic import atomic_write
from ._asdf_config import temporary_asdf_config
from ._data import encode_data
from ._depth import MAX_GRAPH_DEPTH, deepest_frame, recursion_room, too_deep
from ._encode import CURRENT, LEGACY, SCHEMAS, Generation, encode_pose, encode_timestamp, tagged
from ._extension import bound_schemas

__all__ = ["DEFAULT_HIERARCHY_NAME", "HIERARCHY_KEY", "write_asdf"]

HIERARCHY_KEY = "coordinate_system_hierarchy"
DEFAULT_HIERARCHY_NAME = "pinframes"
_ARRAY_INLINE_THRESHOLD = 64


def write_asdf(tree: FrameTree, path: str | os.PathLike[str], schema: str = "0.1.0", *,
               key: str = HIERARCHY_KEY) -> None:
    """Write ``tree`` as a weldx coordinate system hierarchy (atomically).

    Parameters
    ----------
    tree : FrameTree
        The tree to write; a tree holding only its root is fine.
    path : path-like
        The ``.asdf`` file to write.
    schema : {"0.1.0", "1.0.0"}
        ``"0.1.0"`` (the default): the format weldx 0.6 to 0.8.2 writes and reads
        (``di_graph``, ``local_coordinate_system-0.1.1``, coordinates in millimeter, data
        attached to frames). ``"1.0.0"``: the legacy format (weldx up to 0.4; tags
        ``tag:weldx.bam.de:...``, coordinates in millimetres without unit, no data), which
        current weldx opens only as a raw dictionary.
    key : str
        Where the hierarchy goes in the file's tree.

    The hierarchy is named ``tree.name`` (``"pinframes"`` when it has none). The file is
    validated against pinframes' weldx schemas before it is written; the same tree always
    gives the same bytes (for one asdf version).

    Raises
    ------
    UnsupportedFeatureError
        An unknown ``schema``, a revolute joint turning by half a turn or more between
        two trajectory samples (resample it more densely), for ``"0.1.0"`` a frame more
        than 400 frames below the root (write ``"1.0.0"`` instead), for ``"1.0.0"`` data
        attached to frames (write ``"0.1.0"``).
    TreeStructureError
        Subsystems that name unknown nested subsystems or nest in a cycle.
    WriteError
        The file cannot be written; an existing file is left untouched.
    """
    if not isinstance(tree, FrameTree):
        raise ArgumentTypeError(f"expected a pinframes.FrameTree, got {type(tree).__name__}",
                                file=str(path), field="tree")
    check_writable_tree(tree, path)
    generation = SCHEMAS.get(schema)
    if generation is None:
        raise UnsupportedFeatureError(
            f"unknown schema {schema!r}: pinframes writes {' or '.join(map(repr, SCHEMAS))}",
            file=str(path), field="schema")
    depth = 0
    if generation is LEGACY:
        refuse_attached_data(tree, path, "schema '1.0.0'", field="schema")
        hierarchy = _legacy_hierarchy(tree)
    else:
        _check_data(tree, path)
        deepest, depth = deepest_frame((name, tree.parent(name) or "") for name in tree.frames[1:])
        if depth > MAX_GRAPH_DEPTH:
            raise too_deep(deepest, depth, path)
        hierarchy = _graph_hierarchy(tree)
    with recursion_room(depth):
        _write(hierarchy, generation, path, key)


def _write(hierarchy: Any, generation: Generation, path: str | os.PathLike[str], key: str
           ) -> None:
    import asdf

    with bound_schemas(), temporary_asdf_config() as config:
        config.array_inline_threshold = _ARRAY_INLINE_THRESHOLD
        document = asdf.AsdfFile({key: hierarchy}, version=generation.asdf_standard)
        try:
            document.validate()
        except asdf.ValidationError as exc:
            raise WriteError(f"the hierarchy does not validate against its weldx schema "
                             f"{generation.schema}: {exc.message}", file=str(path)) from exc
        with atomic_write(path) as handle:
            document.write_to(handle)


_LARGEST_METRES = 1e305
"""Translations beyond it become infinite once written in millimetres."""


def _frame_poses(tree: FrameTree) -> dict[str, Pose]:
    """Every frame but the root: its pose in its parent, joint-driven links sampled."""
    poses = {}
    for name in tree.frames[1:]:
        if tree.joint_of(name) is None:
            poses[name] = tree.local_pose(name)
        else:
            check_joint_steps(tree, name)
            poses[name] = tree.pose(name, relative_to=tree.parent(name))
        if np.max(np.abs(poses[name].translation)) > _LARGEST_METRES:
            raise UnsupportedFeatureError(
                "a translation over 1e305 m overflows in millimetres; read_asdf would refuse "
                "the file", frame=name, field="coordinates")
    return poses


_WRITABLE_KINDS = "biufcUS"
"""The dtype kinds of ASDF arrays: booleans, numbers and fixed-width strings."""


def _check_data(tree: FrameTree, path: str | os.PathLike[str]) -> None:
    """Refuse attached data that ASDF cannot hold or :func:`read_asdf` would refuse: points
    that overflow in millimetres, attributes of a dtype ASDF has no array type for."""
    for name in tree.data_names:
        data = tree.get_data(name)
        located = {"file": os.fspath(path), "frame": tree.data_frame(name)}
        field = f"attributes.data.{name}"
        if data.points.size and np.max(np.abs(data.points)) > _LARGEST_METRES:
            raise UnsupportedFeatureError(
                "a point over 1e305 m overflows in millimetres; read_asdf would refuse the "
                "file", field=f"{field}.points", **located)
        for attribute, values in data.attributes.items():
            if values.dtype.kind not in _WRITABLE_KINDS:
                raise UnsupportedFeatureError(
                    f"values of dtype {values.dtype} cannot be written to ASDF (booleans, "
                    "numbers and strings can)", field=f"{field}.attributes.{attribute}",
                    **located)


def _name(tree: FrameTree) -> str:
    return DEFAULT_HIERARCHY_NAME if tree.name is None else tree.name


# -- schema 1.0.0: a flat list of transformations ----------------------------------------
def _legacy_hierarchy(tree: FrameTree) -> Any:
    generation = LEGACY
    hierarchy: dict[str, Any] = {"name": _name(tree), "root_system_name": tree.root}
    if tree.reference_time is not None:
        hierarchy["reference_time"] = encode_timestamp(generation, tree.reference_time)
    hierarchy["subsystems"] = [_legacy_subsystem(subsystem) for subsystem in tree.subsystems]
    hierarchy["coordinate_systems"] = [
        tagged(generation, "core/transformations/coordinate_transformation", {
            "name": name, "reference_system": tree.parent(name),
            "transformation": encode_pose(generation, pose)})
        for name, pose in _frame_poses(tree).items()]
    hierarchy["subsystem_names"] = [s.name for s in _top_level_subsystems(tree)]
    return tagged(generation, "core/transformations/coordinate_system_hierarchy", hierarchy)


def _legacy_subsystem(subsystem: Subsystem) -> Any:
    node: dict[str, Any] = {"name": subsystem.name}
    if subsystem.parent is not None:
        node["parent_system"] = subsystem.parent
    if subsystem.reference_time is not None:
        node["reference_time"] = encode_timestamp(LEGACY, subsystem.reference_time)
    node.update(root_cs=subsystem.root, members=list(subsystem.members),
                subsystem_names=list(subsystem.subsystems))
    return tagged(LEGACY, "core/transformations/coordinate_system_hierarchy_subsystem", node)


# -- schema 0.1.0: a directed graph from the root ------------------------------------------
def _graph_hierarchy(tree: FrameTree) -> Any:
    generation = CURRENT
    hierarchy: dict[str, Any] = {"name": _name(tree)}
    if tree.reference_time is not None:
        hierarchy["reference_time"] = encode_timestamp(generation, tree.reference_time)
    hierarchy["graph"] = tagged(generation, "core/graph/di_graph",
                                {"root_node": _root_node(tree, generation)})
    hierarchy["subsystems"] = _nested_subsystems(tree, generation)
    return tagged(generation, "core/transformations/coordinate_system_hierarchy", hierarchy)


def _root_node(tree: FrameTree, generation: Generation) -> Any:
    """The root's ``di_node``; each child hangs on a ``bwd`` edge (child in parent).

    Built leaves first, so deep trees need no recursion here.
    """
    poses = _frame_poses(tree)
    data: dict[str, dict[str, Any]] = {}
    for data_name in tree.data_names:
        data.setdefault(tree.data_frame(data_name), {})[data_name] = encode_data(
            generation, tree.get_data(data_name))
    nodes: dict[str, Any] = {}
    for name in reversed(tree.frames):
        node: dict[str, Any] = {"name": name, "attributes": {"data": data.get(name, {})}}
        edges = [tagged(generation, "core/graph/di_edge", {
            "direction": "bwd",
            "attributes": {"defined": True,
                           "transformation": encode_pose(generation, poses[child])},
            "target_node": nodes.pop(child)}) for child in tree.children(name)]
        if edges:
            node["edges"] = edges
        nodes[name] = tagged(generation, "core/graph/di_node", node)
    return nodes[tree.root]


def _nested_subsystems(tree: FrameTree, generation: Generation) -> list[dict[str, Any]]:
    by_name = {subsystem.name: subsystem for subsystem in tree.subsystems}

    def entry(subsystem: Subsystem) -> dict[str, Any]:
        node: dict[str, Any] = {"name": subsystem.name, "root_node": subsystem.root,
                                "common_node": subsystem.root}
        if subsystem.reference_time is not None:
            node["reference_time"] = encode_timestamp(generation, subsystem.reference_time)
        node.update(members=list(subsystem.members), data=list(subsystem.data),
                    subsystems=[entry(by_name[name]) for name in subsystem.subsystems])
        return node

    return [entry(subsystem) for subsystem in _top_level_subsystems(tree)]


def _top_level_subsystems(tree: FrameTree) -> list[Subsystem]:
    """The subsystems not nested in another one, after checking the nesting is a forest."""
    known = {subsystem.name for subsystem in tree.subsystems}
    nested: dict[str, str] = {}
    for subsystem in tree.subsystems:
        for name in subsystem.subsystems:
            if name not in known:
                raise TreeStructureError(f"subsystem {subsystem.name!r} nests {name!r}, which "
                                         "is not one of the tree's subsystems",
                                         field="subsystems")
            if name in nested:
                raise TreeStructureError(f"subsystem {name!r} is nested in both "
                                         f"{nested[name]!r} and {subsystem.name!r}",
                                         field="subsystems")
            nested[name] = subsystem.name
    top = [subsystem for subsystem in tree.subsystems if subsystem.name not in nested]
    reachable, pending = set(), [s.name for s in top]
    while pending:
        name = pending.pop()
        reachable.add(name)
        pending.extend(n for n, parent in nested.items() if parent == name)
    if reachable != known:
        raise TreeStructureError("subsystems nest in a cycle: "
                                 f"{', '.join(sorted(known - reachable))}", field="subsystems")
    return top
