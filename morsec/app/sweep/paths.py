"""Scene paths, as a sweep names what it varies: `environment.gravity`, `robots[robot].translate`,
`robots[robot].components[motion].properties.speed`, `objects[0].translate`.

A `.key` (or the first word) is a mapping key; `[i]` an item of a list by its index; `[name]` the item of a
list whose `name` is that (a zone without a name goes by its `type`, as morsec names it). Setting a value
creates the mappings on the way that the scene does not write (`properties`, `environment.time`): the
scene's defaults stand for them, and a key that means nothing there is an error of the scene's validation."""

from __future__ import annotations

import re
from typing import Any

from morsec.errors import did_you_mean, yaml_path

_SEGMENT = re.compile(r"\.([^.\[\]\s]+)|\[([^\[\]]+)\]")
_FIRST = re.compile(r"[^.\[\]\s]+")


class PathError(ValueError):
    """A path that cannot be read, or that the scene does not have."""


def parse_path(text: str) -> tuple[str | int | tuple[str], ...]:
    """`robots[robot].translate` -> ('robots', ('robot',), 'translate'): a str is a key, an int an index, a
    1-tuple the name of a list item."""
    first = _FIRST.match(text)
    if not first:
        raise PathError("not a scene path: it starts with a key, as in robots[robot].translate")
    parts: list[str | int | tuple[str]] = [first.group()]
    at = first.end()
    while at < len(text):
        m = _SEGMENT.match(text, at)
        if not m:
            raise PathError(f"not a scene path: cannot read {text[at:]!r} (keys are joined with '.', "
                            "list items are [index] or [name])")
        key, item = m.groups()
        if key is not None:
            parts.append(key)
        else:
            item = item.strip()
            parts.append(int(item) if re.fullmatch(r"-?\d+", item) else (item,))
        at = m.end()
    return tuple(parts)


def set_value(data: dict, text: str, value: Any) -> tuple:
    """Set the value at path `text` in scene data (in place); returns the concrete path (keys and indices, as
    the scene's errors name them: ('robots', 0, 'translate')). PathError when the scene has no such place."""
    parts = parse_path(text)
    node: Any = data
    concrete: list = []
    for k, part in enumerate(parts):
        last = k == len(parts) - 1
        where = yaml_path(concrete) or "the scene"
        if isinstance(part, str):
            if not isinstance(node, dict):
                raise PathError(f"{where} is {_kind(node)}, not a mapping: no key {part!r} in it")
            concrete.append(part)
            if last:
                node[part] = value
            else:
                node = node.setdefault(part, {})
            continue
        if not isinstance(node, list):
            raise PathError(f"{where} is {_kind(node)}, not a list")
        if isinstance(part, int):
            if not -len(node) <= part < len(node):
                raise PathError(f"{where} has {len(node)} items, no item {part}")
            index = part % len(node)
        else:
            index = _named(node, part[0], text, where)
        concrete.append(index)
        if last:
            node[index] = value
        else:
            node = node[index]
    return tuple(concrete)


def _named(items: list, name: str, text: str, where: str) -> int:
    names = [_name_of(item) for item in items]
    if name in names:
        return names.index(name)
    known = [n for n in names if n is not None]
    hint = did_you_mean(name, known) or (f" (names: {', '.join(map(repr, known))})" if known else "")
    raise PathError(f"{where} has no item named {name!r}{hint}")


def _name_of(item: Any) -> str | None:
    if not isinstance(item, dict):
        return None
    name = item.get("name", item.get("type"))  # a zone without a name goes by its type
    return name if isinstance(name, str) else None


def _kind(node: Any) -> str:
    if isinstance(node, list):
        return "a list"
    if isinstance(node, dict):
        return "a mapping"
    return f"the value {node!r}"
