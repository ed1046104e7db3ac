"""The catalogue as a terminal listing, for `morsec components` (one component's details come from
morsec.docsgen.component_section, as on the generated pages)."""

from __future__ import annotations

from morsec.catalogue import Catalogue, is_builtin


def catalogue_listing(cat: Catalogue) -> str:
    lines = []
    for kind in ("robots", "sensors", "actuators", "environments", "props"):
        entries = cat.by_kind.get(kind, {})
        if not entries:
            continue
        lines.append(f"{kind}:")
        width = max(len(cid) for cid in entries)
        for cid, cls in sorted(entries.items()):
            source = "" if is_builtin(cls) else "  [project]"
            lines.append(f"  {cid:<{width}}  {cls.builder_name:<22} {cls.short_descr}{source}")
        lines.append("")
    return "\n".join(lines)
