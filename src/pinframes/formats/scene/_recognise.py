"""What a scene file is: its key and version, the format's content test, the near miss of a
scene without its key line, and the files reading a scene opens."""

from __future__ import annotations

from pathlib import Path

from .._registry import files_read
from ..reading import InputFile

__all__ = ["LAYER_FORMATS", "SCENE_FORMAT_KEY", "SCENE_FORMAT_VERSION", "TOP_KEYS", "is_scene",
           "scene_files_read", "scene_without_key"]

SCENE_FORMAT_KEY = "pinframes_scene"
"""The top-level key that marks a scene file; its value is the format version."""

SCENE_FORMAT_VERSION = 1
"""The scene format version pinframes reads and writes."""

LAYER_FORMATS = ("frames.yaml", "asdf")
"""Formats a scene layer may be in."""
TOP_KEYS = {SCENE_FORMAT_KEY, "name", "root", "reference_time", "layers", "frames", "robots",
            "tools", "program"}
"""The keys a scene file may have at its top level."""
_FILE_KEYS = {"layers": ("file",), "robots": ("urdf", "trajectory", "srdf")}
"""The keys of entries that name files (relative to the scene's folder)."""


def is_scene(source: InputFile) -> bool:
    """Whether ``source`` holds a scene: a YAML mapping with the :data:`SCENE_FORMAT_KEY`
    key (the content test of the scene format)."""
    content = source.yaml()
    return isinstance(content, dict) and SCENE_FORMAT_KEY in content


def scene_without_key(source: InputFile) -> str | None:
    """What ``source`` is when it is a scene but for its :data:`SCENE_FORMAT_KEY` line: a
    YAML mapping of scene keys only, with robots, tools, layers or a list of frames."""
    content = source.yaml()
    if not isinstance(content, dict) or SCENE_FORMAT_KEY in content or not content or (
            not set(content) <= TOP_KEYS):
        return None
    if not (isinstance(content.get("frames"), list)
            or any(key in content for key in ("robots", "tools", "layers"))):
        return None
    return (f"a pinframes scene without its first line '{SCENE_FORMAT_KEY}: "
            f"{SCENE_FORMAT_VERSION}' (add that line and it reads as a scene)")


def scene_files_read(source: InputFile) -> list[Path]:
    """The files reading the scene ``source`` opens: the files its entries name (those that
    exist or not, in the scene's order), with what a layer file reads in turn. Names that
    are not strings are left for the reader to refuse."""
    content = source.yaml()
    named = []
    for section, keys in _FILE_KEYS.items():
        entries = content.get(section) if isinstance(content, dict) else None
        for entry in entries if isinstance(entries, list) else []:
            for key in keys:
                value = entry.get(key) if isinstance(entry, dict) else None
                if isinstance(value, str):
                    path = source.path.parent / value
                    named += files_read(path, among=LAYER_FORMATS) if section == "layers" \
                        else [path]
    program = content.get("program") if isinstance(content, dict) else None
    if isinstance(program, dict) and isinstance(program.get("limits"), str):
        named.append(source.path.parent / program["limits"])  # a MoveIt joint_limits.yaml
    return named
