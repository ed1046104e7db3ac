"""What a catalogue component declares, as text: for `morsec components` and the generated component pages.
Everything here is read from the component class (fields, properties, levels, services, frequency)."""

from __future__ import annotations

from typing import Literal, get_args, get_origin

from morsec.catalogue import Catalogue
from morsec.component import Device, Robot


def _default(value) -> str:
    return "—" if value is None else f"`{value!r}`" if isinstance(value, str) else f"`{value}`"


def properties_table(cls) -> list[str]:
    fields = cls.Properties.model_fields
    if not fields:
        return ["(no properties)"]
    rows = ["| property | type | default | meaning |", "|---|---|---|---|"]
    for name, info in fields.items():
        choices = get_args(info.annotation) if get_origin(info.annotation) is Literal else ()
        annotation = " \\| ".join(repr(c) for c in choices) if choices else getattr(info.annotation, "__name__", str(info.annotation))
        rows.append(f"| `{name}` | {annotation} | {_default(info.default)} | {info.description or ''} |")
    return rows


def fields_table(cls: type[Device]) -> list[str]:
    levels = [lv.name for lv in cls.levels] or [None]
    rows = ["| field | type | default | level | meaning |", "|---|---|---|---|---|"]
    seen = set()
    for level in levels:
        for f in cls.fields_at(level):
            key = (f.name, f.level if isinstance(f.level, str) or f.level is None else tuple(f.level))
            if key in seen:
                continue
            seen.add(key)
            where = "all" if f.level is None else (f.level if isinstance(f.level, str) else ", ".join(f.level))
            rows.append(f"| `{f.name}` | {f.type} | {_default(f.default)} | {where} | {f.doc} |")
    return rows


def component_markdown(cls) -> str:
    lines = [f"# {cls.id}", "", f"**{cls.kind}** · builder class `{cls.builder_name}` · {cls.short_descr}", ""]
    if cls.doc():
        lines += [cls.doc(), ""]
    if isinstance(cls, type) and issubclass(cls, Device):
        lines += [f"Default frequency: {cls.frequency:g} Hz.", ""]
        if cls.levels:
            lines += ["Levels:", ""]
            lines += [f"- `{lv.name}`{' (default)' if lv.default else ''}: {lv.doc}" for lv in cls.levels]
            lines.append("")
        lines += ["## Data fields", ""] + fields_table(cls) + [""]
        services = cls.services()
        lines += ["## Services", ""]
        for name, info in services.items():
            method = getattr(cls, _attr(cls, info), None)
            doc = (method.__doc__ or "").strip().splitlines()[0] if method is not None and method.__doc__ else ""
            kind = "asynchronous" if info.asynchronous else "synchronous"
            lines.append(f"- `{name}` ({kind}){': ' + doc if doc else ''}")
        lines.append("")
    lines += ["## Properties", ""] + properties_table(cls) + [""]
    if isinstance(cls, type) and issubclass(cls, Robot):
        lines += [f"Kinematics: `{cls.xacro}` (xacro → URDF → MJCF); origin {cls.spawn_height:g} m above the ground.", ""]
    return "\n".join(lines)


def _attr(cls, info) -> str:
    for klass in cls.__mro__:
        for attr, value in vars(klass).items():
            if getattr(value, "_morsec_service", None) is info:
                return attr
    return info.name


def catalogue_listing(cat: Catalogue) -> str:
    lines = []
    for kind in ("robots", "sensors", "actuators", "environments", "props"):
        entries = cat.by_kind.get(kind, {})
        if not entries:
            continue
        lines.append(f"{kind}:")
        width = max(len(cid) for cid in entries)
        for cid, cls in sorted(entries.items()):
            source = "" if cls.folder and _builtin(cls, cat) else "  [project]"
            lines.append(f"  {cid:<{width}}  {cls.builder_name:<22} {cls.short_descr}{source}")
        lines.append("")
    return "\n".join(lines)


def _builtin(cls, cat: Catalogue) -> bool:
    from morsec.resources import data_dir
    try:
        cls.folder.relative_to(data_dir("components"))
        return True
    except ValueError:
        return False
