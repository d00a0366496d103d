"""pinframes scene files: a welding cell (frames, layers, robots, tools) in one YAML file."""

from .._registry import FileFormat
from ._read_program import read_program
from ._reader import read_scene
from ._recognise import (
    SCENE_FORMAT_KEY,
    SCENE_FORMAT_VERSION,
    is_scene,
    scene_files_read,
    scene_without_key,
)
from ._writer import write_scene

__all__ = ["SCENE_FORMAT", "SCENE_FORMAT_KEY", "SCENE_FORMAT_VERSION", "read_program",
           "read_scene", "write_scene"]

SCENE_FORMAT = FileFormat(
    "scene", "scene", (".yaml", ".yml"), read_scene, write_scene, ("time",),
    document_test=is_scene, unrecognised=f"no '{SCENE_FORMAT_KEY}' key",
    files_read=scene_files_read, near_miss=scene_without_key)
"""The scene format: a ``.yaml`` file with the scene key (to be written: a ``.yaml`` name
that frames.yaml does not claim)."""
