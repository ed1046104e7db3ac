"""Scene IR -> build folder: scene.xml (MJCF), robots/*.urdf, middleware.json, manifest.json.
A `Scene` comes in, files go out; the compiler never opens a scene file."""

from morsec.compiler.build import compile_scene, write_build

__all__ = ["compile_scene", "write_build"]
