"""MORSE's naming: fully-qualified names robot.child.grandchild; unnamed duplicates get _001, _002 ...

A name written in the scene is the user's: writing the same name twice among siblings is an error.
A name taken by default (the type id, or a builder variable in a loop) is suffixed instead, as MORSE does.
"""

from __future__ import annotations

from typing import Any

from morsec.constants import DUPLICATE_SUFFIX, SEPARATOR


def type_name(type_id: str) -> str:
    """The name an unnamed entry takes from its type: the id; for a class path (a MORSE-API component,
    `mysim.sensors.thermometer.Thermometer`), its module's name (`thermometer`): names hold no dots."""
    return type_id.rsplit(".", 2)[-2] if "." in type_id else type_id


def assign_names(entries: list[Any], default, on_duplicate) -> list[str]:
    """Fill `name` on each entry (pydantic models); `on_duplicate(index, name)` reports explicit clashes."""
    taken: set[str] = set()
    explicit = {e.name for e in entries if e.name}
    names: list[str] = []
    for index, entry in enumerate(entries):
        if entry.name:
            if entry.name in taken:
                on_duplicate(index, entry.name)
            name = entry.name
        else:
            base = default(entry)
            name, n = base, 0
            while name in taken or name in explicit:
                n += 1
                name = base + DUPLICATE_SUFFIX.format(n)
        taken.add(name)
        names.append(name)
    for entry, name in zip(entries, names):
        entry.name = name
    return names


def join(*parts: str) -> str:
    return SEPARATOR.join(parts)
