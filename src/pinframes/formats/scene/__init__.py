"""pinframes scene files: a welding cell (frames, layers, robots, tools) in one YAML file."""

from ._reader import SCENE_FORMAT_KEY, SCENE_FORMAT_VERSION, read_scene
from ._writer import write_scene

__all__ = ["SCENE_FORMAT_KEY", "SCENE_FORMAT_VERSION", "read_scene", "write_scene"]
