"""Generate the concrete Scene model from a catalogue: each component and robot type gets its own model,
with its own `properties` and `level`, joined in a union discriminated on `type`."""

from __future__ import annotations

import json
from functools import lru_cache
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, Field, create_model

from morsec.catalogue import Catalogue, camel_case
from morsec.component import ComponentProperties
from morsec.scene import models as m

GENERATED_MODULE = "morsec.scene.generated"


def _properties_model(cls) -> type[ComponentProperties]:
    return create_model(f"{camel_case(cls.id)}{cls.kind.capitalize()}Properties", __base__=cls.Properties,
                        __module__=GENERATED_MODULE, __doc__=f"Properties of {cls.id!r}.")


def _type_literal(cls) -> Any:
    return Literal[tuple(sorted({cls.id, cls.builder_name}))]


@lru_cache(maxsize=16)
def scene_model(cat: Catalogue) -> type[BaseModel]:
    device_variants = []
    for cid, cls in sorted(cat.devices().items()):
        level_names = tuple(level.name for level in cls.levels)
        level_type = (Literal[level_names] | None) if level_names else None
        props = _properties_model(cls)
        device_variants.append(create_model(
            f"{camel_case(cid)}Component", __base__=m.ComponentBase, __module__=GENERATED_MODULE,
            __doc__=f"{cls.kind} {cid!r}: {cls.short_descr}",
            type=(_type_literal(cls), Field(description=f"{cid} ({cls.builder_name})")),
            properties=(props, Field(default_factory=props, description="the component's properties")),
            level=(level_type, Field(None, description="level of realism: " + (", ".join(level_names) or "none"))),
        ))
    any_component = Annotated[Union[tuple(device_variants)], Field(discriminator="type")]
    namespace = {"AnyComponent": any_component}
    for variant in device_variants:
        variant.model_rebuild(_types_namespace=namespace)

    robot_variants = []
    for rid, cls in sorted(cat.by_kind.get("robots", {}).items()):
        props = _properties_model(cls)
        robot_variants.append(create_model(
            f"{camel_case(rid)}Robot", __base__=m.RobotBase, __module__=GENERATED_MODULE,
            __doc__=f"robot {rid!r}: {cls.short_descr}",
            type=(_type_literal(cls), Field(description=f"{rid} ({cls.builder_name})")),
            properties=(props, Field(default_factory=props, description="robot properties")),
        ))
    for variant in robot_variants:
        variant.model_rebuild(_types_namespace=namespace)
    any_robot = Annotated[Union[tuple(robot_variants)], Field(discriminator="type")]

    env_names = tuple(cat.ids("environments"))
    environment = create_model("Environment", __base__=m.EnvironmentBase, __module__=GENERATED_MODULE,
                               __doc__=m.EnvironmentBase.__doc__,
                               name=(Literal[env_names], Field("empty", description="environment id")))
    prop_names = tuple(cat.names("props"))
    obj = create_model("PassiveObject", __base__=m.ObjectSpec, __module__=GENERATED_MODULE,
                       __doc__=m.ObjectSpec.__doc__,
                       type=(Literal[prop_names], Field(description="prop id")))
    return create_model(
        "Scene", __base__=m.SceneBase, __module__=GENERATED_MODULE, __doc__=m.SceneBase.__doc__,
        environment=(environment, Field(default_factory=environment)),
        robots=(list[any_robot], Field(default_factory=list, description="robots and their components")),
        objects=(list[obj], Field(default_factory=list, description="passive objects")),
    )


def json_schema(cat: Catalogue) -> dict:
    schema = scene_model(cat).model_json_schema(by_alias=True)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["$id"] = "https://morsec.dev/schemas/scene.schema.json"
    return schema


def json_schema_text(cat: Catalogue) -> str:
    return json.dumps(json_schema(cat), indent=2, sort_keys=True) + "\n"
