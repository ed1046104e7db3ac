"""Scene IR -> build folder: scene.xml (MJCF), robots/*.urdf, middleware.json, manifest.json."""

from morsec.compiler.build import build_scene

__all__ = ["build_scene"]
