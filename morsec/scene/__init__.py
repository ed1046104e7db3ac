"""The scene: its pydantic IR, the YAML/TOML loaders that produce it, and the naming rules."""

from morsec.scene.loader import load_scene, read_scene_file
from morsec.scene.models import Scene

__all__ = ["Scene", "load_scene", "read_scene_file"]
