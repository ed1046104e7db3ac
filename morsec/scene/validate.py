"""Plain scene data from a front end (+ its SourceMap) -> validated, fully-resolved IR, or one SceneError
naming file:line:column.

A pydantic ValidationError becomes one line: the problem that comes first in the file, at its key or
value, with its YAML path, a message that says what was expected and what was found, close matches
for unknown names, and a count of the other problems.
"""

from __future__ import annotations

import math
import re
from typing import Any

from pydantic import BaseModel, ValidationError
from pydantic_core import ErrorDetails

from morsec.component.catalogue import Catalogue
from morsec.constants import FORBIDDEN_NAME_CHARS
from morsec.errors import SceneError, close_matches, did_you_mean, one_of, yaml_path
from morsec.middleware.refused import refusal
from morsec.middleware.registry import middlewares
from morsec.scene.resolve import add_environment_objects, add_prop_defaults, add_robot_defaults, resolve
from morsec.scene.schema import scene_model, types_named
from morsec.scene.sourcemap import SourceMap

VECTOR_KEYS = {"translate": "[x, y, z]", "rotate": "[x, y, z]", "location": "[x, y, z]",
               "rotation": "[x, y, z]", "size": "[x, y, z]", "clip": "[near, far]",
               "color": "[r, g, b] or [r, g, b, a]"}


def validate_scene(data: dict, smap: SourceMap, cat: Catalogue) -> BaseModel:
    add_robot_defaults(data, cat)
    data = add_environment_objects(data, cat)
    data = add_prop_defaults(data, cat)
    try:  # the model of the types the scene names; any problem is reported by the whole model
        scene = scene_model(cat, types_named(data)).model_validate(data)
    except ValidationError:
        try:
            scene = scene_model(cat).model_validate(data)
        except ValidationError as err:
            raise scene_error(err, data, smap, cat) from None
    resolve(scene, cat, smap)
    scene._source = smap
    return scene


# ---------------------------------------------------------------- pydantic errors -> one clear line

def scene_error(err: ValidationError, data: Any, smap: SourceMap, cat: Catalogue | None = None) -> SceneError:
    """One located line for `err`; without a catalogue (a file that is not a scene: a sweep), the messages that
    name component types and properties are not asked for."""
    problems = []
    for error in err.errors(include_url=False):
        path, message, at_key = _explain(error, data, cat)
        pos = smap.find(path, key=at_key)
        problems.append((pos, -len(path), path, message))
    problems.sort(key=lambda p: (p[0] or (math.inf, math.inf), p[1]))
    pos, _, path, message = problems[0]
    where = yaml_path(path)
    if where:
        message = f"{where}: {message}"
    extra = len(problems) - 1
    if extra:
        message += f" (and {extra} more problem{'s' if extra > 1 else ''})"
    line, col = pos if pos else (None, None)
    return SceneError(message, smap.file, line, col)


def _explain(error: ErrorDetails, data: Any, cat: Catalogue | None) -> tuple[tuple, str, bool]:
    """(path in the file, message, whether the position is the key's rather than the value's)."""
    path, at_key = _data_path(error["loc"], data)
    kind = error["type"]
    ctx = error.get("ctx") or {}
    got = error.get("input", _MISSING)
    last = path[-1] if path else None

    if kind == "unknown_key":
        key, allowed = ctx["key"], ctx.get("allowed", ())
        hint = did_you_mean(str(key), allowed) or f"; allowed keys: {', '.join(allowed)}"
        return path + (key,), f"unknown key {key!r}{hint}", True
    if cat is not None and kind == "extra_forbidden" and len(path) >= 2 and path[-2] == "properties":
        return path, _unknown_property(path, data, cat), True
    if cat is not None and kind == "union_tag_invalid":
        tag = ctx.get("tag")
        tags = re.findall(r"'([^']*)'", ctx.get("expected_tags", ""))
        label = "robot" if len(path) == 2 and path[0] == "robots" else "component"
        value = _value_at(data, path + ("type",))
        shown = value if value is not _MISSING else tag
        hint = _suggest(str(shown), tags, cat)
        if not hint:
            ids = [t for t in tags if t == t.lower()] or tags
            hint = f" (known: {one_of(ids)})"
        return path + ("type",), f"unknown {label} type {shown!r}{hint}", False
    if cat is not None and kind == "union_tag_not_found":
        robot = len(path) == 2 and path[0] == "robots"
        ids = cat.ids("robots") if robot else sorted(cat.devices())
        example = f", e.g. {ids[0]!r}" if ids else ""
        return path, f"missing key 'type': the {'robot' if robot else 'component'}'s catalogue id{example}", True
    if kind == "literal_error":
        choices = re.findall(r"'([^']*)'", ctx.get("expected", ""))
        return path, _literal(path, got, choices, data), at_key
    if kind == "none_required" and last == "level":
        owner = _value_at(data, path[:-1] + ("type",))
        return path, f"component type {owner!r} has no levels; remove 'level'", False
    if kind in ("too_short", "too_long"):
        n = len(got) if isinstance(got, (list, tuple)) else "?"
        if last in VECTOR_KEYS:
            numbers = "3 or 4" if last == "color" else ("2" if last == "clip" else "3")
            return path, f"must be a list of {numbers} numbers {VECTOR_KEYS[last]}, got {n}: {_show(got)}", False
        limit = ctx.get("min_length") if kind == "too_short" else ctx.get("max_length")
        return path, f"must have {'at least' if kind == 'too_short' else 'at most'} {limit} items, got {n}", False
    if kind == "finite_number":
        return path, f"must be a finite number (NaN and infinities are not allowed), got {_show(got)}", False
    if kind == "missing":
        return path[:-1], f"missing required key {last!r}", True
    if kind == "unknown_modifier":
        return path + ("name",), str(error["msg"]), False
    if kind == "bad_name":
        return path, _bad_name(ctx), False
    if kind in _EXPECTED:
        message = f"must be {_EXPECTED[kind]}"
        if len(path) >= 2 and path[-2] == "streams" and isinstance(last, int):
            message = "must be a middleware name (socket) or a mapping {middleware: socket, port: ...}"
        if last in VECTOR_KEYS and kind == "list_type":
            message = f"must be a list {VECTOR_KEYS[last]}"
        return path, f"{message}, got {describe_value(got)}", False
    if kind in _BOUNDS:
        word, key = _BOUNDS[kind]
        return path, f"must be {word} {_show(ctx.get(key))}, got {_show(got)}", False
    message = str(error["msg"])
    message = re.sub(r"^(Value error|Assertion failed), ", "", message)
    message = re.sub(r"^Input should be\b", "must be", message)
    message = message[:1].lower() + message[1:]
    if got is not _MISSING and not isinstance(got, (dict, list)) and kind not in ("unknown_modifier", "bad_param"):
        message += f", got {_show(got)}"
    return path, message, at_key


_EXPECTED = {
    "list_type": "a list", "tuple_type": "a list",
    "dict_type": "a mapping (key: value)", "model_type": "a mapping (key: value)",
    "model_attributes_type": "a mapping (key: value)",
    "string_type": "a string", "string_unicode": "a string",
    "int_type": "an integer", "int_parsing": "an integer", "int_from_float": "an integer",
    "float_type": "a number", "float_parsing": "a number",
    "bool_type": "true or false", "bool_parsing": "true or false",
}
_BOUNDS = {
    "greater_than": ("greater than", "gt"), "greater_than_equal": ("at least", "ge"),
    "less_than": ("less than", "lt"), "less_than_equal": ("at most", "le"),
}


def _literal(path: tuple, got: Any, choices: list[str], data: Any) -> str:
    last = path[-1] if path else None
    hint = did_you_mean(str(got), choices)
    ids = [c for c in choices if c == c.lower()] or choices  # the catalogue ids, without builder class names
    if path == ("environment", "name"):
        return f"unknown environment {got!r} (known: {', '.join(map(repr, ids))}){hint}"
    if last == "level":
        owner = _value_at(data, path[:-1] + ("type",))
        return f"unknown level {got!r} of component type {owner!r} (levels: {', '.join(map(repr, choices))}){hint}"
    if last == "type" and path[:1] == ("objects",):
        return f"unknown object type {got!r} (known: {', '.join(map(repr, ids))}){hint}"
    refused = refusal(str(got)) if choices and set(choices) <= set(middlewares()) else None
    if refused:  # a middleware MORSE had and morsec refuses: why, and what to use instead
        return refused
    return f"{_show(got)} is not one of {one_of(choices)}{hint}"


def _unknown_property(path: tuple, data: Any, cat: Catalogue) -> str:
    key = path[-1]
    owner_path = path[:-2]
    type_name = _value_at(data, owner_path + ("type",))
    kind = "robots" if len(owner_path) == 2 and owner_path[0] == "robots" else None
    cls = None
    for k in ([kind] if kind else ["sensors", "actuators"]):
        resolved = cat.resolve(k, str(type_name))
        if resolved:
            cls = cat.by_kind[k][resolved]
            break
    known = sorted(cls.Properties.model_fields) if cls is not None else []
    owner = f"{cls.kind} type {cls.id!r}" if cls is not None else f"type {type_name!r}"
    if not known:
        return f"unknown property {key!r}: {owner} has no properties"
    listed = ", ".join(map(repr, known))
    return f"unknown property {key!r} of {owner} (properties: {listed}){did_you_mean(str(key), known)}"


def _bad_name(ctx: dict) -> str:
    name = str(ctx.get("name", ""))
    if not name:
        return "a name cannot be empty"
    fixed = "".join("_" if (c in FORBIDDEN_NAME_CHARS or not c.isprintable()) else c for c in name)
    return (f"name {name!r} contains {ctx.get('shown')}: names are joined with '.' into fully-qualified names "
            f"(robot.child) and sent over line-based protocols; try {fixed!r}")


def _suggest(word: str, tags: list[str], cat: Catalogue) -> str:
    """Close matches among ids and builder names, one spelling per component."""
    matches = close_matches(word, tags, n=6)
    seen, unique = set(), []
    for m in matches:
        key = _canonical(m, cat)
        if key not in seen:
            seen.add(key)
            unique.append(m)
    return did_you_mean(word, unique[:3]) if unique else ""


def _canonical(name: str, cat: Catalogue) -> str:
    for kind in ("robots", "sensors", "actuators", "props", "environments"):
        resolved = cat.resolve(kind, name)
        if resolved:
            return f"{kind}/{resolved}"
    return name


_MISSING = object()


def _data_path(loc: tuple, data: Any) -> tuple[tuple, bool]:
    """Drop pydantic's union tags and function names from `loc`, keeping the keys and indices of the file.
    Also says whether the error is about a mapping key (`[key]` in loc) rather than its value."""
    path: list = []
    node = data
    at_key = False
    for part in loc:
        if part == "[key]":
            at_key = True
            continue
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
        elif isinstance(node, str) and part == "middleware":
            continue  # a stream written as a bare middleware name
        else:
            path.append(part)
            node = _MISSING
    return tuple(path), at_key


def _value_at(data: Any, path: tuple) -> Any:
    node = data
    for part in path:
        try:
            node = node[part]
        except (KeyError, IndexError, TypeError):
            return _MISSING
    return node


def _show(value: Any) -> str:
    if value is _MISSING:
        return "nothing"
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def describe_value(value: Any) -> str:
    if value is None:
        return "nothing (null)"
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return f"a list {_show(value)}" if len(repr(value)) <= 30 else "a list"
    if isinstance(value, bool):
        return repr(value).lower()
    if isinstance(value, str):
        return f"the string {_show(value)}"
    if isinstance(value, (int, float)):
        return f"the number {_show(value)}"
    return _show(value)
