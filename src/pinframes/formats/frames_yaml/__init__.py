"""Duckietown ``frames.yaml`` map layers: read into a FrameTree and written back (SPEC 8)."""

from ._reader import read_frames_yaml
from ._schema import FramesYamlWarning
from ._writer import write_frames_yaml

__all__ = ["FramesYamlWarning", "read_frames_yaml", "write_frames_yaml"]
