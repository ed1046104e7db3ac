"""One entry to every front end: a scene file's suffix picks the front end, the IR comes out."""

from __future__ import annotations

from pathlib import Path

from pydantic import BaseModel

from morsec.component.catalogue import Catalogue, load_catalogue
from morsec.frontends.text import TOML_SUFFIXES, YAML_SUFFIXES, read_scene_file
from morsec.scene.validate import validate_scene

BUILDER_SUFFIXES = (".py",)
SCENE_SUFFIXES = (*YAML_SUFFIXES, *TOML_SUFFIXES, *BUILDER_SUFFIXES)


def load_scene(path: Path, catalogue: Catalogue | None = None, strict: bool = False) -> BaseModel:
    """The validated, resolved IR of a scene file (YAML, TOML or a MORSE builder script). `strict`: a
    builder script's warnings are errors (YAML and TOML scenes have none: what they cannot say is an error)."""
    path = Path(path)
    cat = catalogue or load_catalogue(path.parent)
    if path.suffix in BUILDER_SUFFIXES:
        from morsec.frontends.builder.script import run_builder_script
        return run_builder_script(path, cat, strict)
    data, smap = read_scene_file(path)
    return validate_scene(data, smap, cat)
