"""The types a data field may have (`DataField.type`): a closed vocabulary, declared once here with the JSON
Schema of each type as the socket stream carries it (json.dumps of the message: numpy arrays become lists,
pictures and point clouds travel as base64 text).

    DataField("x", 0.0, "float", "x coordinate, world frame, m")
    DataField("velocity", [0.0, 0.0, 0.0], "vec3", "velocity along x, y, z, m/s")

The message a stream carries is described from its fields (`Device.message_schema`), published as
schemas/messages/<kind>/<id>.schema.json and shown on each component's page.
"""

from __future__ import annotations

import copy
from typing import Any

from morsec.errors import did_you_mean

JSON_SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"

_NUMBER = {"type": "number"}
_VEC3 = {"type": "array", "items": _NUMBER, "minItems": 3, "maxItems": 3}

# name -> (what it is, its JSON Schema on the wire)
FIELD_TYPES: dict[str, tuple[str, dict[str, Any]]] = {
    "bool": ("true or false", {"type": "boolean"}),
    "int": ("an integer", {"type": "integer"}),
    "float": ("a number (inf or NaN where the field says so)", _NUMBER),
    "str": ("a string", {"type": "string"}),
    "vec3": ("3 numbers: [x, y, z] (or the three values the field names)", _VEC3),
    "vec4": ("4 numbers", {"type": "array", "items": _NUMBER, "minItems": 4, "maxItems": 4}),
    "mat3": ("a 3 x 3 matrix, row major: 3 lists of 3 numbers",
             {"type": "array", "items": _VEC3, "minItems": 3, "maxItems": 3}),
    "list[float]": ("a list of numbers", {"type": "array", "items": _NUMBER}),
    "list[vec3]": ("a list of [x, y, z]", {"type": "array", "items": _VEC3}),
    "list[dict]": ("a list of mappings (the field says which keys)", {"type": "array", "items": {"type": "object"}}),
    "dict": ("a mapping (the field says which keys)", {"type": "object"}),
    "dict[str, float]": ("a mapping of names to numbers", {"type": "object", "additionalProperties": _NUMBER}),
    "base64": ("binary data (a numpy array in local_data): base64 text of its bytes on the wire",
               {"type": "string", "contentEncoding": "base64"}),
}


def type_schema(name: str) -> dict[str, Any]:
    """The JSON Schema of one field type (a copy: callers may add to it)."""
    return copy.deepcopy(FIELD_TYPES[name][1])


def check_type(field: str, name: Any) -> None:
    """ValueError naming the field when `name` is not a type of the vocabulary."""
    if name in FIELD_TYPES:
        return
    raise ValueError(f"data field {field!r}: type {name!r} is not one of {', '.join(map(repr, FIELD_TYPES))}"
                     f"{did_you_mean(str(name), FIELD_TYPES)}")


def object_schema(fields, extra=None, *, required: bool = True, title: str = "",
                  description: str = "") -> dict[str, Any]:
    """The JSON Schema of a message made of `fields` (DataFields, in order); `extra` (a DataField or None):
    the type of the keys the message has besides them (names known only at run time). `required`: every
    field is in every message (a sensor's); an actuator's command may leave fields out."""
    schema: dict[str, Any] = {"type": "object"}
    if title:
        schema["title"] = title
    if description:
        schema["description"] = description
    props = {}
    for f in fields:
        prop = type_schema(f.type)
        if f.doc:
            prop["description"] = f.doc
        props[f.name] = prop
    schema["properties"] = props
    if required and props:
        schema["required"] = list(props)
    if extra is None:
        schema["additionalProperties"] = False
    else:
        more = type_schema(extra.type)
        if extra.doc:
            more["description"] = f"{extra.name}: {extra.doc}"
        schema["additionalProperties"] = more
    return schema
