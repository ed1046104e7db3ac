"""Generate the concrete Scene model from a catalogue: each component and robot type gets its own model,
with its own `properties` and `level`, joined in a union discriminated on `type`."""

from __future__ import annotations

import json
import re
from functools import lru_cache
from typing import Annotated, Any, Literal, Union

from pydantic import Field, create_model
from typing_extensions import TypeAliasType

from morsec.component.catalogue import Catalogue, camel_case
from morsec.component.contract import ComponentProperties
from morsec.scene import models as m

GENERATED_MODULE = "morsec.scene.generated"


def _model_name(cid: str) -> str:
    """A model's name from a type id (a class path's dots too: a MORSE-API component's)."""
    return camel_case(re.sub(r"\W", "_", cid))


def _properties_model(cls) -> type[ComponentProperties]:
    return create_model(f"{_model_name(cls.id)}{cls.kind.capitalize()}Properties", __base__=cls.Properties,
                        __module__=GENERATED_MODULE, __doc__=f"Properties of {cls.id!r}.")


def _type_literal(cls) -> Any:
    if getattr(cls, "classpath", None):  # a MORSE-API class: its path only (its class name may be a catalogue's)
        return Literal[(cls.id,)]
    return Literal[tuple(sorted({cls.id, cls.builder_name}))]


def _literal(values: tuple[str, ...]) -> Any:
    """Literal[values]: a type made at run time, which a type checker cannot see."""
    return Literal[values]


def types_named(data: Any) -> frozenset[str]:
    """Every string under a `type` key of the scene data's robots, at any depth: the robot and component
    types (catalogue ids or builder names) a scene names."""
    found: set[str] = set()

    def walk(value: Any) -> None:
        if isinstance(value, dict):
            if isinstance(value.get("type"), str):
                found.add(value["type"])
            for item in value.values():
                walk(item)
        elif isinstance(value, list):
            for item in value:
                walk(item)

    walk(data.get("robots") if isinstance(data, dict) else None)
    return frozenset(found)


@lru_cache(maxsize=16)
def scene_model(cat: Catalogue, only: frozenset[str] | None = None) -> type[m.SceneBase]:
    """The Scene model of the catalogue. `only`: with the robot and component variants of these types
    alone (ids or builder names), which validates a scene naming no others as the whole model does,
    for a fraction of the cost of generating every variant's schema (a scene with an error is checked
    again with the whole model, whose messages list every known type)."""

    def wanted(cls, first: bool) -> bool:  # the first of each kind too: a union needs one type at least
        return only is None or first or cls.id in only or (cls.builder_name in only and not
                                                            getattr(cls, "classpath", None))

    device_variants = []
    for i, (cid, cls) in enumerate(sorted(cat.devices().items())):
        if not wanted(cls, i == 0):
            continue
        level_names = tuple(level.name for level in cls.levels)
        level_type: Any = (_literal(level_names) | None) if level_names else None
        props = _properties_model(cls)
        device_variants.append(create_model(
            f"{_model_name(cid)}Component", __base__=m.ComponentBase, __module__=GENERATED_MODULE,
            __doc__=f"{cls.kind} {cid!r}: {cls.short_descr}",
            type=(_type_literal(cls), Field(description=f"{cid} ({cls.builder_name})")),
            properties=(props, Field(default_factory=props, description="the component's properties")),
            level=(level_type, Field(None, description="level of realism: " + (", ".join(level_names) or "none"))),
        ))
    # A named type alias: pydantic makes it one definition that nested `components` refer to, so each
    # variant is generated once (a plain union would expand every variant inside every other one)
    # Union[tuple]: a union of the generated variants (the `X | Y` spelling cannot take a tuple)
    # (variants, any_component, any_robot: types made at run time, Any to a type checker)
    variants: Any = Union[tuple(device_variants)]  # noqa: UP007
    any_component: Any = TypeAliasType("AnyComponent", Annotated[variants, Field(discriminator="type")])
    namespace = {"AnyComponent": any_component}

    robot_variants = []
    for i, (rid, robot_cls) in enumerate(sorted(cat.by_kind.get("robots", {}).items())):
        if not wanted(robot_cls, i == 0):
            continue
        props = _properties_model(robot_cls)
        robot_variants.append(create_model(
            f"{camel_case(rid)}Robot", __base__=m.RobotBase, __module__=GENERATED_MODULE,
            __doc__=f"robot {rid!r}: {robot_cls.short_descr}",
            type=(_type_literal(robot_cls), Field(description=f"{rid} ({robot_cls.builder_name})")),
            properties=(props, Field(default_factory=props, description="robot properties")),
        ))
    any_robot: Any = Annotated[Union[tuple(robot_variants)], Field(discriminator="type")]  # noqa: UP007

    env_names = tuple(cat.ids("environments"))
    environment = create_model("Environment", __base__=m.EnvironmentBase, __module__=GENERATED_MODULE,
                               __doc__=m.EnvironmentBase.__doc__,
                               name=(_literal(env_names), Field("empty", description="environment id")))
    prop_names = tuple(cat.names("props"))
    obj = create_model("PassiveObject", __base__=m.ObjectSpec, __module__=GENERATED_MODULE,
                       __doc__=m.ObjectSpec.__doc__,
                       type=(_literal(prop_names), Field(description="prop id")))
    scene = create_model(
        "Scene", __base__=m.SceneBase, __module__=GENERATED_MODULE, __doc__=m.SceneBase.__doc__,
        environment=(environment, Field(default_factory=environment)),
        robots=(list[any_robot], Field(default_factory=list, description="robots and their components")),
        objects=(list[obj], Field(default_factory=list, description="passive objects")),
    )
    # one build of the whole tree: every variant's schema is generated once, inside the Scene's
    scene.model_rebuild(_types_namespace=namespace)
    scene.__morsec_aliases__ = namespace  # forward references left in the variants' own annotations
    return scene


def json_schema(cat: Catalogue) -> dict:
    schema = scene_model(cat).model_json_schema(by_alias=True)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["$id"] = "https://morsec.dev/schemas/scene.schema.json"
    schema["$comment"] = "generated by `morsec schema` from the scene models and the catalogue; do not edit"
    return schema


def json_schema_text(cat: Catalogue) -> str:
    return json.dumps(json_schema(cat), indent=2, sort_keys=True) + "\n"
