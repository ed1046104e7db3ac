"""Every class MORSE's builder exported is in morsec's builder, or refused with its reason: the list is the
table of docs/coming-from-morse.md (declared there once), checked here row by row."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import morsec.frontends.builder as builder
from morsec.frontends.builder import UnknownBuilderName, builder_attribute, builder_names

PAGE = Path(__file__).resolve().parents[1] / "docs" / "coming-from-morse.md"
ROW = re.compile(r"^\| `(?P<name>\w+)` \| (?P<kind>base|robot|sensor|actuator) \| (?P<status>.+) \|$")
MODULES = {"base": "morse.builder", "robot": "morse.builder.robots", "sensor": "morse.builder.sensors",
           "actuator": "morse.builder.actuators"}


def morse_classes() -> list[tuple[str, str, str]]:
    text = PAGE.read_text(encoding="utf-8")
    block = text.split("<!-- morse-builder-classes")[1].split("<!-- /morse-builder-classes -->")[0]
    rows = [ROW.match(line) for line in block.splitlines() if line.startswith("| `")]
    assert all(rows), "a row of the table does not read as | `Name` | kind | status |"
    return [(m["name"], m["kind"], m["status"]) for m in rows if m]


def test_the_list_names_each_class_once_and_covers_every_kind():
    names = [name for name, _, _ in morse_classes()]
    assert len(names) == len(set(names))
    assert {kind for _, kind, _ in morse_classes()} == set(MODULES)
    assert len(names) > 120


@pytest.mark.parametrize("name,kind,status", morse_classes(), ids=lambda v: v if v.isidentifier() else "")
def test_morse_builder_class(name, kind, status):
    available = set(builder_names())
    if status == "yes":
        assert name in available
        assert builder_attribute(MODULES[kind], name) is getattr(builder, name)
    elif status.startswith("alias of "):
        target = status.removeprefix("alias of ")
        assert builder_attribute(MODULES[kind], name) is getattr(builder, target)
    else:
        verdict, _, reason = status.partition(": ")
        assert verdict in ("refused", "coming") and len(reason) > 20, "a refused class says why in one line"
        assert name not in available, f"{name} is in morsec's builder now: mark it yes"
        with pytest.raises(UnknownBuilderName):
            builder_attribute(MODULES[kind], name)
