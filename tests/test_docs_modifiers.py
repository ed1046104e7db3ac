"""docs/modifiers.md lists every modifier of the registry with every component it applies to (as the
built-in components declare them)."""

import re
from pathlib import Path

import pytest

from morsec.component.catalogue import load_catalogue
from morsec.modifiers.registry import MODIFIERS

ROOT = Path(__file__).resolve().parent.parent
PAGE = ROOT / "docs" / "modifiers.md"


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


def test_every_modifier_and_component_is_documented():
    rows = {}
    for line in PAGE.read_text().splitlines():
        m = re.match(r"\| `(\w+)` \| (.+?) \|", line)
        if m:
            rows.setdefault(m.group(1), set()).update(re.findall(r"`(\w+)`", m.group(2)))
    assert set(rows) == set(MODIFIERS)
    for name, table in load_catalogue(ROOT).modifiers().items():
        assert set(table) == rows[name], f"docs/modifiers.md: {name!r} applies to {sorted(table)}"
