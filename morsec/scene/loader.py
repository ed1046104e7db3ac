"""Scene files (YAML, TOML) -> validated, fully-resolved IR, or one SceneError naming file:line:column."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from morsec.catalogue import Catalogue, load_catalogue
from morsec.errors import SceneError, did_you_mean
from morsec.scene.positions import SourceMap, parse_toml, parse_yaml
from morsec.scene.resolve import resolve
from morsec.scene.schema import scene_model

YAML_SUFFIXES = (".yaml", ".yml")
TOML_SUFFIXES = (".toml",)


def read_scene_file(path: Path) -> tuple[Any, SourceMap]:
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"{path}: no such scene file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(f"{path}: cannot read: {err}") from None
    suffix = path.suffix.lower()
    if suffix in YAML_SUFFIXES:
        data, smap = parse_yaml(text, str(path))
    elif suffix in TOML_SUFFIXES:
        data, smap = parse_toml(text, str(path))
    else:
        raise SceneError(f"{path}: unknown scene format {suffix!r}; use .yaml, .yml, .toml or a builder script .py")
    if not isinstance(data, dict):
        raise SceneError("a scene must be a mapping with environment, robots, objects and zones", str(path), 1, 1)
    return data, smap


def load_scene(path: Path, catalogue: Catalogue | None = None) -> BaseModel:
    path = Path(path)
    if path.suffix == ".py":
        from morsec.builder.script import run_builder_script
        return run_builder_script(path, catalogue)
    data, smap = read_scene_file(path)
    cat = catalogue or load_catalogue(path.parent)
    return validate_scene(data, smap, cat)


def validate_scene(data: dict, smap: SourceMap, cat: Catalogue) -> BaseModel:
    model = scene_model(cat)
    try:
        scene = model.model_validate(data)
    except ValidationError as err:
        raise scene_error(err, data, smap, cat) from None
    resolve(scene, cat, smap)
    scene._source = smap
    return scene


# ---------------------------------------------------------------- pydantic errors -> one clear line

def scene_error(err: ValidationError, data: Any, smap: SourceMap, cat: Catalogue) -> SceneError:
    errors = err.errors(include_url=False)
    first = min(errors, key=lambda e: _rank(e))
    path = _data_path(first["loc"], data)
    kind = first["type"]
    ctx = first.get("ctx") or {}
    key_position = False
    if kind == "unknown_key":
        path = path + (ctx["key"],)
        key_position = True
        message = first["msg"]
    elif kind == "union_tag_invalid":
        tag = ctx.get("tag")
        kind_name = "robots" if path and path[0] == "robots" and len(path) == 2 else "sensors"
        choices = cat.names("robots") if kind_name == "robots" else (cat.names("sensors") + cat.names("actuators"))
        label = "robot" if kind_name == "robots" else "component"
        message = f"unknown {label} type {tag!r}{did_you_mean(str(tag), choices)}"
        path = path + ("type",)
    elif kind == "union_tag_not_found":
        message = "missing key 'type'"
    elif kind == "literal_error":
        got = _value_at(data, path)
        expected = ctx.get("expected", "")
        choices = [c.strip().strip("'") for c in expected.replace(" or ", ",").split(",") if c.strip()]
        message = f"{got!r} is not one of {expected}{did_you_mean(str(got), choices)}"
    elif kind in ("too_short", "too_long"):
        got = _value_at(data, path)
        n = len(got) if isinstance(got, (list, tuple)) else "?"
        want = ctx.get("min_length") if kind == "too_short" else ctx.get("max_length")
        if path and path[-1] in ("translate", "rotate", "location", "rotation", "size"):
            message = f"must be a list of 3 numbers [x, y, z], got {n}"
        else:
            message = f"must have {'at least' if kind == 'too_short' else 'at most'} {want} items, got {n}"
    elif kind == "finite_number":
        message = f"must be a finite number, got {_value_at(data, path)!r}"
    elif kind == "missing":
        message = f"missing required key {path[-1]!r}"
        path = path[:-1]
        key_position = True
    else:
        message = first["msg"][0].lower() + first["msg"][1:]
        got = _value_at(data, path)
        if got is not _MISSING and not isinstance(got, (dict, list)):
            message += f", got {got!r}"
    where = _dotted(path)
    if where:
        message = f"{where}: {message}"
    line_col = smap.find(path, key=key_position)
    line, col = line_col if line_col else (None, None)
    extra = len(errors) - 1
    if extra:
        message += f" (and {extra} more problem{'s' if extra > 1 else ''})"
    return SceneError(message, smap.file, line, col)


_MISSING = object()


def _rank(error: dict) -> tuple:
    # report the earliest-located, most specific problem first
    return (len(error["loc"]) == 0, [str(p) for p in error["loc"]])


def _data_path(loc: tuple, data: Any) -> tuple:
    """Drop pydantic's union tags and function names from `loc`, keeping the keys and indices of the file."""
    path: list = []
    node = data
    for part in loc:
        if isinstance(node, dict):
            if part in node:
                path.append(part)
                node = node[part]
            elif node.get("type") == part or (isinstance(part, str) and ("[" in part or "(" in part)):
                continue
            else:
                path.append(part)
                node = _MISSING
        elif isinstance(node, list) and isinstance(part, int) and 0 <= part < len(node):
            path.append(part)
            node = node[part]
        elif isinstance(part, str) and ("[" in part or "(" in part):
            continue
        else:
            path.append(part)
            node = _MISSING
    return tuple(path)


def _value_at(data: Any, path: tuple) -> Any:
    node = data
    for part in path:
        try:
            node = node[part]
        except (KeyError, IndexError, TypeError):
            return _MISSING
    return node


def _dotted(path: tuple) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out
