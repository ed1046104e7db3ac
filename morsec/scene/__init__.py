"""The scene IR: pydantic models, the per-catalogue schema, validation and resolution (names, defaults,
levels). It knows no file format: front ends hand it plain data and a SourceMap."""

from morsec.scene.models import Scene
from morsec.scene.sourcemap import SourceMap
from morsec.scene.validate import validate_scene

__all__ = ["Scene", "SourceMap", "validate_scene"]
