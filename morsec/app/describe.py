"""The catalogue for `morsec components`: a listing, or one component's page (as on the generated docs)."""

from __future__ import annotations

from morsec.app.docsgen import component_section
from morsec.component.catalogue import Catalogue, is_builtin
from morsec.errors import MorsecError, did_you_mean

KINDS = ("robots", "sensors", "actuators", "environments", "props")


def describe_component(cat: Catalogue, name: str) -> str:
    """One component's page (Markdown): what `morsec components NAME` shows."""
    for kind in KINDS:
        if cat.resolve(kind, name):
            cls = cat.get(kind, name)
            return f"{cls.short_descr}\n{component_section(kind, cls, None, None)}"
    every = [n for kind in KINDS for n in cat.names(kind)]
    raise MorsecError(f"no component {name!r} in the catalogue{did_you_mean(name, every)}")


def catalogue_listing(cat: Catalogue) -> str:
    lines = []
    for kind in KINDS:
        entries = cat.by_kind.get(kind, {})
        if not entries:
            continue
        lines.append(f"{kind}:")
        width = max(len(cid) for cid in entries)
        for cid, cls in sorted(entries.items()):
            source = "" if is_builtin(cls) else "  [MORSE API]" if getattr(cls, "classpath", None) else "  [project]"
            lines.append(f"  {cid:<{width}}  {cls.builder_name:<22} {cls.short_descr}{source}")
        lines.append("")
    return "\n".join(lines)
