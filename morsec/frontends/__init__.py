"""Front ends: scene files (YAML and TOML text, MORSE builder scripts) into the scene IR.

`load_scene(path)` picks the front end by suffix; nothing past this package opens a scene file."""

from morsec.frontends.load import SCENE_SUFFIXES, load_scene

__all__ = ["SCENE_SUFFIXES", "load_scene"]
