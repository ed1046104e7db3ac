"""docs/modifiers.md lists every modifier of the registry with every component it applies to."""

import re
from pathlib import Path

from morsec.modifiers.registry import MODIFIERS

PAGE = Path(__file__).resolve().parent.parent / "docs" / "modifiers.md"


def test_every_modifier_and_component_is_documented():
    rows = {}
    for line in PAGE.read_text().splitlines():
        m = re.match(r"\| `(\w+)` \| (.+?) \|", line)
        if m:
            rows.setdefault(m.group(1), set()).update(re.findall(r"`(\w+)`", m.group(2)))
    assert set(rows) == set(MODIFIERS)
    for name, table in MODIFIERS.items():
        assert set(table) == rows[name], f"docs/modifiers.md: {name!r} applies to {sorted(table)}"
