"""The build contract: `manifest.json`, what the compiler decided and the runtime runs, nothing left to decide.

Every component's importable class (its catalogue root, kind and id) and level class, resolved properties,
every stream once with its final endpoint, services per middleware, every modifier with its resolved
parameters, the loop's rates, versions and content hashes. The runtime validates it against this model
(`load_manifest`) and reads nothing else but `scene.xml`. Its JSON Schema is schemas/manifest.schema.json.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from morsec.component.catalogue import BUILTIN_ROOT
from morsec.errors import RuntimeFailure

FORMAT_VERSION = 2
MANIFEST = "manifest.json"


class Entry(BaseModel):
    # inf is a value components use (an orientation actuator's default speed): written as JSON's Infinity
    model_config = ConfigDict(extra="forbid", frozen=True, ser_json_inf_nan="constants", defer_build=True)


class ComponentRef(Entry):
    """Where a component class is: `<root>/<kind>/<id>/component.py`, class `name`."""

    root: str = Field(description=f"'{BUILTIN_ROOT}' for a built-in component, else the catalogue folder's "
                      "absolute path")
    kind: Literal["robots", "sensors", "actuators", "environments", "props"]
    id: str
    name: str = Field(description="the class declared by COMPONENT")
    module: str | None = Field(None, description="a class named by its dotted path (a MORSE-API component): its "
                               "module, imported from `root`; `id` is the class path")


class Loop(Entry):
    frequency: float = Field(description="main-loop frames per simulated second")
    physics_substeps: int
    timestep: float = Field(description="MuJoCo's timestep, s")


class RobotEntry(Entry):
    name: str
    type: str
    component: ComponentRef
    builder_name: str = Field(description="MORSE's class name, as `simulation details` reports it")
    urdf: str = Field(description="its URDF in the build folder")
    free: bool = Field(description="whether it has a free joint (false: static)")
    friction: float | None = Field(None, description="set_friction's value (none: Blender's default)")
    properties: dict[str, Any]


class ModifierEntry(Entry):
    name: str
    cls: str = Field(description="the modifier class, importable: module:Class")
    params: dict[str, Any] = Field(description="parameters, environment defaults resolved")


class OverlayEntry(Entry):
    middleware: str
    overlay: str = Field(description="the overlay as the scene names it (MORSE's class path)")
    cls: str = Field(description="the overlay class the middleware serves it with, importable: module:Class")
    params: dict[str, Any] = Field(description="its keyword arguments (a namespace ...)")


class ComponentEntry(Entry):
    fqn: str
    robot: str
    parent: str
    type: str
    kind: Literal["sensor", "actuator"]
    component: ComponentRef
    level_class: str = Field(description="the class implementing the level, in the same component.py")
    level: str | None
    frequency: float
    properties: dict[str, Any]
    data_fields: list[str]
    services: list[str] = Field(description="middlewares its services are exposed on")
    service_names: list[str]
    modifiers: list[ModifierEntry]
    overlays: list[OverlayEntry] = Field([], description="its services adapted for one middleware")
    tags: dict[str, Any] = Field(description="game properties its type does not declare, which sensors read")
    path: list[str | int] = Field(description="where it is in the scene (for messages)")


class StreamEntry(Entry):
    component: str
    direction: Literal["IN", "OUT"]
    middleware: str
    endpoint: dict[str, Any] = Field(description="what the middleware assigned: a port, a file ...")


class ServiceEntry(Entry):
    middleware: str
    endpoint: dict[str, Any]
    components: list[str] = Field(description="components whose services it carries")


class Manifest(Entry):
    format: Literal[2]
    morsec: str
    mujoco: str
    loop: Loop
    scene: dict[str, Any] = Field(description="the resolved IR")
    scene_sha256: str
    robots: list[RobotEntry]
    components: list[ComponentEntry]
    streams: list[StreamEntry]
    services: list[ServiceEntry]
    stream_managers: dict[str, dict[str, Any]] = Field(description="configure_stream_manager, per middleware")
    files: dict[str, str] = Field(description="sha256 of every other file of the build")


def load_manifest(build_dir: Path) -> Manifest:
    """The manifest of a build folder, or one line saying why it cannot be run."""
    path = Path(build_dir) / MANIFEST
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise RuntimeFailure(f"{build_dir}: not a usable build folder: {err.strerror or err}") from None
    try:
        return Manifest.model_validate_json(text)
    except ValidationError as err:
        first = err.errors(include_url=False)[0]
        where = ".".join(str(p) for p in first["loc"])
        if first["loc"][:1] == ("format",) and first["type"] != "missing":
            raise RuntimeFailure(f"{build_dir}: built by another morsec (this one reads format {FORMAT_VERSION}); "
                                 "rebuild it (morsec build)") from None
        raise RuntimeFailure(f"{build_dir}: not a usable build folder: {MANIFEST}: {where}: {first['msg']}; "
                             "rebuild it (morsec build)") from None


def manifest_schema_text() -> str:
    """schemas/manifest.schema.json: `morsec schema --manifest`."""
    import json
    schema = Manifest.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["$id"] = "https://morsec.dev/schemas/manifest.schema.json"
    schema["$comment"] = "generated by `morsec schema --manifest` from morsec.scene.manifest; do not edit"
    return json.dumps(schema, indent=2, sort_keys=True) + "\n"
