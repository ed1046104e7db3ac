"""The JSON Schema of each stream's message, from the components' data fields (`Device.message_schema`):
one file per sensor or actuator that has a stream, schemas/messages/<kind>/<id>.schema.json, written by
`morsec schema --messages schemas/messages` and checked for staleness by the tests.

A component with levels gets one schema per level under `$defs/<level>`; the file itself validates the
default level's message (`"$ref": "#/$defs/<default level>"`)."""

from __future__ import annotations

import json
from pathlib import Path

from morsec.component.catalogue import Catalogue
from morsec.component.fields import JSON_SCHEMA_DIALECT

MESSAGES_DIR = "schemas/messages"
REGENERATE = f"morsec schema --messages {MESSAGES_DIR}"
STREAM_KINDS = ("sensors", "actuators")


def message_document(cls) -> dict:
    """The published schema of one component's stream message (every level)."""
    if not cls.levels:
        return {"$schema": JSON_SCHEMA_DIALECT, **cls.message_schema(None)}
    default = cls.default_level()
    return {
        "$schema": JSON_SCHEMA_DIALECT,
        "title": f"{cls.id} message",
        "description": f"the message at the default level, {default!r}; each level's message is under "
                       f"$defs/<level> ({', '.join(lv.name for lv in cls.levels)})",
        "$ref": f"#/$defs/{default}",
        "$defs": {lv.name: cls.message_schema(lv.name) for lv in cls.levels},
    }


def schema_path(kind: str, cid: str) -> str:
    """The file of a component's message schema, relative to the messages folder."""
    return f"{kind}/{cid}.schema.json"


def message_schema_files(cat: Catalogue) -> dict[str, str]:
    """{path relative to the messages folder: JSON text} for every component with a stream."""
    files = {}
    for kind in STREAM_KINDS:
        for cid in cat.ids(kind):
            cls = cat.by_kind[kind][cid]
            if cls.exportable:
                files[schema_path(kind, cid)] = message_schema_text(cls)
    return files


def message_schema_text(cls) -> str:
    return json.dumps(message_document(cls), indent=2, ensure_ascii=False) + "\n"


def write_message_schemas(out_dir: Path, cat: Catalogue) -> list[Path]:
    """Write every message schema under `out_dir`, and remove the schemas of components that are gone."""
    out_dir = Path(out_dir)
    files = message_schema_files(cat)
    for kind in STREAM_KINDS:
        for old in sorted((out_dir / kind).rglob("*.schema.json")) if (out_dir / kind).is_dir() else ():
            if old.relative_to(out_dir).as_posix() not in files:
                old.unlink()
    written = []
    for name, text in files.items():
        path = out_dir / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        written.append(path)
    return written


__all__ = ["MESSAGES_DIR", "REGENERATE", "message_document", "message_schema_files", "message_schema_text",
           "schema_path", "write_message_schemas"]
