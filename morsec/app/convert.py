"""`morsec convert SRC -o DST`: a scene in one form written in another.

    builder script .py  ->  .yaml / .yml / .toml
    .yaml / .yml       <->  .toml

What is written is the scene as its source states it (validated but not resolved: no defaults added),
so a converted builder script reads like a hand-written YAML scene. Before anything is written the
output is read back and validated: it must give exactly the IR of the source, hence the same build.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path
from typing import Any

import yaml

from morsec.component.catalogue import Catalogue, load_catalogue
from morsec.errors import MorsecError, SceneError
from morsec.frontends.builder.script import record_script
from morsec.frontends.text import TOML_SUFFIXES, YAML_SUFFIXES, parse_toml, parse_yaml, read_scene_file
from morsec.scene.sourcemap import SourceMap
from morsec.scene.validate import validate_scene

SOURCES = (".py", *YAML_SUFFIXES, *TOML_SUFFIXES)
TARGETS = (*YAML_SUFFIXES, *TOML_SUFFIXES)


def scene_source(path: Path, cat: Catalogue) -> tuple[dict, SourceMap]:
    """The scene as written: a builder script's recording, or a YAML/TOML file's data."""
    path = Path(path)
    if path.suffix.lower() == ".py":
        recording = record_script(path, cat)
        recording.report()
        return recording.data, recording.smap
    return read_scene_file(path)


def convert_scene(source: Path, target: Path, catalogue: Catalogue | None = None) -> Path:
    source, target = Path(source), Path(target)
    if source.suffix.lower() not in SOURCES:
        raise SceneError(f"{source}: cannot convert {source.suffix or 'a file without suffix'!r}; "
                         "the source must be .py, .yaml, .yml or .toml")
    suffix = target.suffix.lower()
    if suffix not in TARGETS:
        raise SceneError(f"{target}: cannot write {suffix or 'a file without suffix'!r}; "
                         "convert writes .yaml, .yml or .toml")
    if target.exists() and source.exists() and target.resolve() == source.resolve():
        raise SceneError(f"{target}: is the source itself; choose another output file")
    cat = catalogue or load_catalogue(source.parent)
    data, smap = scene_source(source, cat)
    scene = validate_scene(data, smap, cat)
    header = f"converted from {source.name} by `morsec convert`"
    text = to_yaml(data, header) if suffix in YAML_SUFFIXES else to_toml(data, header)
    parsed, parsed_map = (parse_yaml if suffix in YAML_SUFFIXES else parse_toml)(text, str(target))
    again = validate_scene(parsed, parsed_map, cat)
    if again.model_dump(mode="json") != scene.model_dump(mode="json"):
        raise MorsecError(f"{source}: internal error: the converted scene differs from the source; please report it")
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(text, encoding="utf-8")
    return target


# ---------------------------------------------------------------- YAML

def _scalar(value: Any) -> bool:
    return not isinstance(value, (dict, list, tuple))


class _Dumper(yaml.SafeDumper):
    """Block style for the structure, flow style for short vectors and small flat mappings."""

    def ignore_aliases(self, data):
        return True


def _represent_list(dumper: yaml.SafeDumper, data: list):
    flow = all(_scalar(v) for v in data)
    return dumper.represent_sequence("tag:yaml.org,2002:seq", data, flow_style=flow)


def _represent_dict(dumper: yaml.SafeDumper, data: dict):
    flat = all(_scalar(v) or (isinstance(v, list) and all(_scalar(x) for x in v)) for v in data.values())
    flow = flat and len(json.dumps(data, default=str)) <= 60
    return dumper.represent_mapping("tag:yaml.org,2002:map", data.items(), flow_style=flow)


_Dumper.add_representer(list, _represent_list)
_Dumper.add_representer(tuple, _represent_list)
_Dumper.add_representer(dict, _represent_dict)


def to_yaml(data: dict, header: str | None = None) -> str:
    body = yaml.dump(data, Dumper=_Dumper, sort_keys=False, default_flow_style=False, allow_unicode=True, width=100)
    return (f"# {header}\n" if header else "") + body


# ---------------------------------------------------------------- TOML

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")
TABLE_ARRAYS = ("robots", "components", "objects", "zones")


def to_toml(data: dict, header: str | None = None) -> str:
    """TOML 1.0 for plain data: tables for sections, arrays of tables for robots, components, objects
    and zones, inline tables and arrays for the rest. Keys whose value is None are left out (TOML has no
    null; in a scene, None is always the default)."""
    out: list[str] = [f"# {header}"] if header else []
    _toml_table(out, (), data)
    text = "\n".join(out).strip("\n") + "\n"
    return text


def _toml_key(key: Any) -> str:
    key = str(key)
    return key if _BARE_KEY.match(key) else _toml_string(key)


def _toml_string(value: str) -> str:
    return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")


def _toml_value(value: Any, where: str) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value) or math.isinf(value):
            return ("-" if value < 0 else "") + ("nan" if math.isnan(value) else "inf")
        return repr(value)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, (list, tuple)):
        if any(v is None for v in value):
            raise SceneError(f"{where}: TOML cannot hold a null inside a list")
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    if isinstance(value, dict):
        items = [f"{_toml_key(k)} = {_toml_value(v, f'{where}.{k}')}" for k, v in value.items() if v is not None]
        return "{" + ", ".join(items) + "}" if items else "{}"
    raise SceneError(f"{where}: cannot write {type(value).__name__} values to TOML")


def _is_table(key: Any, value: Any) -> bool:
    if not isinstance(value, dict):
        return False
    flat = all(_scalar(v) or (isinstance(v, list) and all(_scalar(x) for x in v)) for v in value.values())
    return not flat or len(_toml_value(value, str(key))) > 60


def _is_table_array(key: Any, value: Any) -> bool:
    return key in TABLE_ARRAYS and isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _toml_table(out: list[str], path: tuple, table: dict) -> None:
    where = ".".join(str(p) for p in path) or "scene"
    items = [(k, v) for k, v in table.items() if v is not None]
    for key, value in items:
        if not _is_table(key, value) and not _is_table_array(key, value):
            out.append(f"{_toml_key(key)} = {_toml_value(value, f'{where}.{key}')}")
    for key, value in items:
        if _is_table(key, value):
            out += ["", "[" + ".".join(_toml_key(p) for p in (*path, key)) + "]"]
            _toml_table(out, (*path, key), value)
    for key, value in items:
        if _is_table_array(key, value):
            for item in value:
                out += ["", "[[" + ".".join(_toml_key(p) for p in (*path, key)) + "]]"]
                _toml_table(out, (*path, key), item)
