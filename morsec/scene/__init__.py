"""The scene IR: pydantic models, the per-catalogue schema, validation and resolution (names, defaults,
levels). It knows no file format: front ends hand it plain data and a SourceMap.

Its names are imported on first use: the runtime reads only `morsec.scene.manifest`, and running a build
folder does not build the scene's models."""

_EXPORTS = {"Scene": "morsec.scene.models", "SourceMap": "morsec.scene.sourcemap",
            "validate_scene": "morsec.scene.validate"}


def __getattr__(name: str):
    if name in _EXPORTS:
        import importlib
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["Scene", "SourceMap", "validate_scene"]
