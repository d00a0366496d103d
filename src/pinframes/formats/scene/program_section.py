"""A scene's ``program:`` section: the moves a welding cell runs, by frame name.

Read: checked field by field into plain data (kept in the tree's metadata under
:data:`PROGRAM_METADATA_KEY`, so that writing the scene keeps it) and made into a
:class:`~pinframes.program.WeldProgram` by :func:`scene_program`. Frames, joints and group
states are looked up when the program is planned; a name that does not exist is an error
naming the move.
"""

from __future__ import annotations

import os
from typing import Any

from ...errors import FileFormatError, PinframesError
from ...program import WeldProgram
from ...program.weld_program import MOVE_KINDS
from ...tree import FrameTree
from ...values.weave import Weave
from ..joint_limits import read_joint_limits
from ._fields import SceneFields

__all__ = ["PROGRAM_METADATA_KEY", "read_program_section", "scene_program"]

PROGRAM_METADATA_KEY = "program"
"""Where a scene's program section is kept in the tree's metadata."""

_SECTION_KEYS = {"tool", "joints", "limits", "start", "step", "check", "moves"}
_OPTIONS = {
    "move_joints": set(),
    "move_linear": {"speed"},
    "weld": {"torch", "speed", "approach", "retract", "approach_speed", "tilt", "free_axis",
             "weave"},
    "wait": set(),
}
_NUMBERS = {"speed", "approach", "retract", "approach_speed"}
_WEAVE_KEYS = {"amplitude", "frequency", "pattern", "dwell"}


def read_program_section(section: Any, fields: SceneFields) -> dict[str, Any]:
    """The ``program:`` section checked, as plain data (a :class:`FileFormatError` naming
    the field otherwise)."""
    fields.check_keys(section, _SECTION_KEYS, None, "program")
    checked: dict[str, Any] = {"tool": fields.name(section.get("tool"), None, "program.tool")}
    joints = section.get("joints")
    if joints is not None:
        checked["joints"] = (fields.name(joints, None, "program.joints")
                             if isinstance(joints, str) else
                             [fields.name(name, None, f"program.joints[{index}]")
                              for index, name in enumerate(_list(joints, fields,
                                                                 "program.joints"))])
    if "limits" in section:
        checked["limits"] = _limits(section["limits"], fields)
    if "start" in section:
        checked["start"] = _joint_values(section["start"], fields, "program.start")
    if "step" in section:
        checked["step"] = fields.positive(section["step"], None, "program.step")
    if "check" in section:
        checked["check"] = _check(section["check"], fields)
    moves = _list(section.get("moves"), fields, "program.moves")
    checked["moves"] = [_move(item, fields, f"program.moves[{index}]")
                        for index, item in enumerate(moves)]
    return checked


def scene_program(tree: FrameTree, file: str | os.PathLike[str] | None = None
                  ) -> WeldProgram:
    """The :class:`WeldProgram` of ``tree``'s scene program (``tree.metadata["program"]``),
    with its moves added; errors name ``file``, the field and the move."""
    section = tree.metadata.get(PROGRAM_METADATA_KEY)
    if not isinstance(section, dict):
        raise FileFormatError("the scene has no program section", file=file, field="program")
    try:
        program = WeldProgram(tree, section["tool"], joints=section.get("joints"),
                              limits=section.get("limits"), start=section.get("start"),
                              step=section.get("step", 0.004), check=section.get("check"))
    except PinframesError as exc:
        raise exc.located(file=file, field="program") from None
    for index, move in enumerate(section["moves"]):
        options = dict(move)
        kind = next(key for key in MOVE_KINDS if key in options)
        target = options.pop(kind)
        if "weave" in options:
            options["weave"] = Weave(**options["weave"])
        if "tilt" in options:
            options["tilt"] = tuple(options["tilt"])
        try:
            getattr(program, kind)(target, **options)
        except PinframesError as exc:
            name = move.get("name", f"{kind} {index + 1}")
            raise type(exc)(f"move {name!r}: {exc.message}", file=file, frame=exc.frame,
                            joint=exc.joint, field=f"program.moves[{index}]") from None
    return program


def _move(item: Any, fields: SceneFields, field: str) -> dict[str, Any]:
    kinds = [key for key in MOVE_KINDS if isinstance(item, dict) and key in item]
    if len(kinds) != 1:
        raise FileFormatError(f"a move has exactly one of {', '.join(MOVE_KINDS)}",
                              file=fields.path, field=field)
    kind = kinds[0]
    fields.check_keys(item, {kind, "name"} | _OPTIONS[kind], None, field)
    checked: dict[str, Any] = {}  # the kind first, as written
    value = item[kind]
    if kind == "wait":
        checked[kind] = fields.number(value, None, f"{field}.wait")
    elif kind == "move_joints":
        checked[kind] = _joint_values(value, fields, f"{field}.move_joints")
    else:
        checked[kind] = fields.name(value, None, f"{field}.{kind}")
    if "name" in item:
        checked["name"] = fields.name(item["name"], None, f"{field}.name")
    if kind == "move_linear" and "speed" not in item:
        raise FileFormatError("missing (m/s)", file=fields.path, field=f"{field}.speed")
    for key in _OPTIONS[kind] & set(item):
        where = f"{field}.{key}"
        if key in _NUMBERS:
            checked[key] = fields.number(item[key], None, where)
        elif key == "torch":
            checked[key] = fields.name(item[key], None, where)
        elif key == "free_axis":
            if item[key] not in ("x", "y", "z", None):
                raise FileFormatError(f"expected x, y, z or null, got {item[key]!r}",
                                      file=fields.path, field=where)
            checked[key] = item[key]
        elif key == "tilt":
            checked[key] = [float(number) for number in fields.numbers(item[key], 2, None,
                                                                       where)]
        else:
            fields.check_keys(item[key], _WEAVE_KEYS, None, where)
            checked[key] = {name: (item[key][name] if name == "pattern" else
                                   fields.number(item[key][name], None, f"{where}.{name}"))
                            for name in _WEAVE_KEYS & set(item[key])}
    return checked


def _joint_values(value: Any, fields: SceneFields, field: str) -> Any:
    """Joint values by name, one per joint, or a name (a frame or a group state)."""
    if isinstance(value, str):
        return fields.name(value, None, field)
    if isinstance(value, dict):
        return {fields.name(name, None, field): fields.number(number, None, f"{field}.{name}")
                for name, number in value.items()}
    return [fields.number(number, None, f"{field}[{index}]")
            for index, number in enumerate(_list(value, fields, field))]


def _limits(value: Any, fields: SceneFields) -> dict[str, dict[str, float]]:
    """Inline limits, or those of a MoveIt ``joint_limits.yaml`` the section names (relative
    to the scene), kept inline."""
    if isinstance(value, str):
        file = fields.file({"limits": value}, "limits", None, "program")
        return {name: {kind: number for kind in ("velocity", "acceleration", "jerk")
                       if (number := getattr(record, kind)) is not None}
                for name, record in read_joint_limits(file).items()}
    if not isinstance(value, dict):
        raise FileFormatError("expected a mapping of joint names to velocity, acceleration "
                              "and jerk", file=fields.path, field="program.limits")
    checked = {}
    for joint, record in value.items():
        where = f"program.limits.{joint}"
        fields.check_keys(record, {"velocity", "acceleration", "jerk"}, None, where)
        checked[fields.name(joint, None, "program.limits")] = {
            key: fields.positive(number, None, f"{where}.{key}")
            for key, number in record.items()}
    return checked


def _check(value: Any, fields: SceneFields) -> dict[str, Any]:
    fields.check_keys(value, {"a", "b", "exclude", "margin"}, None, "program.check")
    checked: dict[str, Any] = {}
    for side in ("a", "b"):
        names = value.get(side)
        checked[side] = (fields.name(names, None, f"program.check.{side}")
                         if isinstance(names, str) else
                         [fields.name(name, None, f"program.check.{side}")
                          for name in _list(names, fields, f"program.check.{side}")])
    if "exclude" in value:
        checked["exclude"] = [
            [fields.name(name, None, f"program.check.exclude[{index}]")
             for name in _list(pair, fields, f"program.check.exclude[{index}]")]
            for index, pair in enumerate(_list(value["exclude"], fields,
                                               "program.check.exclude"))]
    if "margin" in value:
        checked["margin"] = fields.number(value["margin"], None, "program.check.margin")
    return checked


def _list(value: Any, fields: SceneFields, field: str) -> list[Any]:
    if not isinstance(value, list) or not value:
        raise FileFormatError(f"expected a non-empty list, got {value!r}", file=fields.path,
                              field=field)
    return value
