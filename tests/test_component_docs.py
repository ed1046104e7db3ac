"""Each fact about a component is declared once, in its component.py: every property and data field has its
description there, and the generated pages show them. A README keeps prose only (what it models, an
example, where it differs from MORSE, provenance): no table of properties or data fields to drift."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from morsec.component.catalogue import load_catalogue

ROOT = Path(__file__).resolve().parent.parent
CATALOGUE = load_catalogue(ROOT)
COMPONENTS = [(cls.kind, cls.id, cls) for cls in CATALOGUE.all()]
IDS = [f"{kind}-{cid}" for kind, cid, _ in COMPONENTS]
# a README table whose header names one of these declares what component.py declares
DECLARED_HEADERS = {"property", "properties", "field", "fields", "data field", "data fields", "level", "levels"}


def declared_names(cls) -> set[str]:
    names = set(cls.Properties.model_fields)
    for f in (*getattr(cls, "data", ()), *(getattr(cls, "message_fields", None) or ())):
        names.add(f.name)
    names.update(level.name for level in getattr(cls, "levels", ()))
    return names


def tables(text: str) -> list[tuple[int, list[str], list[list[str]]]]:
    """Markdown tables outside code blocks: (line number of the header, header cells, rows of cells)."""
    lines = text.splitlines()
    fenced = False
    found = []
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        if fenced or not line.lstrip().startswith("|") or i + 1 >= len(lines):
            continue
        if not re.fullmatch(r"\s*\|?[\s:|-]*-[\s:|-]*\|?\s*", lines[i + 1]) or (i and lines[i - 1].lstrip().startswith("|")):
            continue
        rows = []
        for row in lines[i + 2:]:
            if not row.lstrip().startswith("|"):
                break
            rows.append(_cells(row))
        found.append((i + 1, _cells(line), rows))
    return found


def _cells(row: str) -> list[str]:
    return [c.strip() for c in row.strip().strip("|").split("|")]


def _plain(cell: str) -> str:
    return re.sub(r"[`*_]", "", cell).strip().lower()


@pytest.mark.parametrize("kind, cid, cls", COMPONENTS, ids=IDS)
def test_every_property_has_a_description(kind, cid, cls):
    missing = [name for name, info in cls.Properties.model_fields.items() if not (info.description or "").strip()]
    assert not missing, (f"{cls.folder / 'component.py'}: properties without a description: {missing} "
                         "(declare them as Field(default, description=...))")


@pytest.mark.parametrize("kind, cid, cls", COMPONENTS, ids=IDS)
def test_every_data_field_has_a_description(kind, cid, cls):
    fields = (*getattr(cls, "data", ()), *(getattr(cls, "message_fields", None) or ()))
    extra = getattr(cls, "extra_field", None)
    missing = [f.name for f in (*fields, *((extra,) if extra else ())) if not f.doc.strip()]
    assert not missing, f"{cls.folder / 'component.py'}: data fields without a description: {missing}"


@pytest.mark.parametrize("kind, cid, cls", COMPONENTS, ids=IDS)
def test_readme_has_no_table_of_declared_facts(kind, cid, cls):
    """Properties, data fields and levels are tabulated on the generated page, from component.py."""
    readme = Path(cls.folder) / "README.md"
    if not readme.is_file():
        pytest.skip("no README")
    names = declared_names(cls)
    for line, header, rows in tables(readme.read_text(encoding="utf-8")):
        named = {_plain(cell) for cell in header} & DECLARED_HEADERS
        assert not named, (f"{readme}:{line}: a table of {sorted(named)[0]}s; component.py declares them and the "
                           "generated page shows them: move what the table says into the descriptions in code")
        for row in rows:
            first = re.findall(r"`([^`]+)`", row[0]) if row else []
            assert not (first and set(first) <= names), (
                f"{readme}:{line}: a table row about {first} (declared in component.py): describe them in code")


def test_the_table_rule_finds_tables():
    text = ("intro\n\n| Property | default | meaning |\n|---|---|---|\n| `x` | 1 | a |\n\n```\n| field |\n|---|\n```\n"
            "\n| | |\n|:-|-:|\n| `speed` | fast |\n")
    found = tables(text)
    assert [(line, header) for line, header, _ in found] == [(3, ["Property", "default", "meaning"]), (12, ["", ""])]
    assert found[1][2] == [["`speed`", "fast"]]
