"""Duckietown ``frames.yaml`` map layers: read into a FrameTree and written back.

The format and how it is read: docs/frames-yaml.md.
"""

from pathlib import Path

from .._registry import FileFormat
from ..reading import InputFile
from ._reader import read_frames_yaml
from ._schema import FramesYamlWarning, is_frames_yaml, is_frames_yaml_name, tile_maps_beside
from ._writer import write_frames_yaml

__all__ = ["FRAMES_YAML_FORMAT", "FramesYamlWarning", "read_frames_yaml", "write_frames_yaml"]


def _files_read(source: InputFile) -> list[Path]:
    """The ``tile_maps.yaml`` beside the file (read for ``unit: tiles`` frames)."""
    return [tile_maps_beside(source.path)]


FRAMES_YAML_FORMAT = FileFormat(
    "frames.yaml", "frames.yaml", (".yaml", ".yml"), read_frames_yaml, write_frames_yaml,
    ("time", "slash_replacement"), document_test=is_frames_yaml,
    unrecognised="no 'frames' key", write_name_test=is_frames_yaml_name,
    files_read=_files_read)
"""The frames.yaml format: a ``.yaml`` file named ``frames...`` or with a ``frames`` key."""
