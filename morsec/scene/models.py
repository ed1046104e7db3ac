"""The scene IR: pydantic models mirroring MORSE's builder API. Declared once; the JSON Schema, the
scene-format docs and the error messages are derived from these models.

The parts that depend on the component catalogue (a component's `type`, `properties` and `level`) are
generated per catalogue by `morsec.scene.schema.scene_model`, as a union discriminated on `type`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal, TypeAlias

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PrivateAttr,
    create_model,
    model_validator,
)
from pydantic_core import PydanticCustomError

from morsec.constants import (
    DEFAULT_FREQUENCY,
    DEFAULT_PHYSICS_SUBSTEPS,
    FORBIDDEN_NAME_CHARS,
    MAX_TIME_SCALE,
    MIN_TIME_SCALE,
    MULTINODE_PORT,
    TimeStrategy,
)
from morsec.errors import did_you_mean
from morsec.kits.display import DEFAULT_CAMERA_SPEED, DEFAULT_CLIP_END, DEFAULT_SHADE, SHADES
from morsec.middleware.registry import middlewares, service_middlewares
from morsec.modifiers.registry import MODIFIERS as MODIFIER_TABLE


class Strict(BaseModel):
    """Unknown keys are errors (with a suggestion); NaN and infinities are refused."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, validate_default=True)

    @model_validator(mode="before")
    @classmethod
    def _unknown_keys(cls, data: Any) -> Any:
        if isinstance(data, dict) and cls.model_config.get("extra") == "forbid":
            known = set(cls.model_fields)
            for key in data:
                if key not in known:
                    raise PydanticCustomError(
                        "unknown_key", "unknown key {shown}{hint}",
                        {"key": key, "shown": repr(key), "hint": did_you_mean(str(key), sorted(known)),
                         "allowed": sorted(known)})
        return data


def _check_name(name: str) -> str:
    if not name:
        raise PydanticCustomError("bad_name", "a name cannot be empty")
    bad = sorted({c for c in name if c in FORBIDDEN_NAME_CHARS or not c.isprintable()})
    if bad:
        shown = ", ".join(repr(c) for c in bad)
        raise PydanticCustomError(
            "bad_name", "name {name_shown} contains {shown}: names are joined with '.' into "
            "fully-qualified names (robot.child) and sent over line-based protocols",
            {"name": name, "name_shown": repr(name), "shown": shown})
    return name


Name = Annotated[str, AfterValidator(_check_name)]
Number = Annotated[float, Field(allow_inf_nan=False)]
Positive = Annotated[float, Field(gt=0, allow_inf_nan=False)]
Vec3 = Annotated[list[Number], Field(min_length=3, max_length=3)]
Size3 = Annotated[list[Positive], Field(min_length=3, max_length=3)]
Color = Annotated[list[Annotated[float, Field(ge=0, le=1)]], Field(min_length=3, max_length=4)]
Basic = bool | int | float | str
PropertyBag = dict[str, Basic]
# Blender's game lock flags (lock_location_x ... lock_rotation_z): world axes a body cannot move along or turn about
Lock = Literal["location_x", "location_y", "location_z", "rotation_x", "rotation_y", "rotation_z"]
TAGS_DESCRIPTION = ("game properties the type does not declare (MORSE's properties(...) with another name), kept "
                    "for other components to read: proximity's Track, collision's only_objects_with_property, "
                    "the semantic camera's tag, the thermometer's FireTag")
LOCKS_DESCRIPTION = ("Blender's game lock_location_x/y/z and lock_rotation_x/y/z: world axes the body cannot move "
                     "along or turn about (a stiff damper on its free joint); no effect on a static body")
# the registered middlewares (morsec.middleware.registry): a package that adds one extends these; known at
# run time only, so a type checker sees their names as strings
if TYPE_CHECKING:
    Middleware: TypeAlias = str
    ServiceMiddleware: TypeAlias = str
else:
    Middleware = Literal[tuple(middlewares())]
    ServiceMiddleware = Literal[service_middlewares()]


def _stream_shorthand(value: Any) -> Any:
    return {"middleware": value} if isinstance(value, str) else value


class StreamSpecBase(Strict):
    """A datastream binding (`add_stream(middleware, **kwargs)`)."""

    middleware: Middleware = Field(description="datastream middleware")
    topic: str | None = Field(None, description="topic name, for middlewares that have topics")
    frame_id: str | None = Field(None, description="frame id, for middlewares that carry one")
    method: str | None = Field(None, description="serialisation method of a full binding [classpath, method, path]")
    path: str | None = Field(None, description="path of a full binding")
    classpath: str | None = Field(None, description="middleware class of a full binding")
    direction: Literal["IN", "OUT"] | None = Field(None, description="default: OUT for sensors, IN for actuators")


def _stream_spec() -> type[StreamSpecBase]:
    """StreamSpecBase plus the options each registered middleware declares (socket: port; text: file, format)."""
    options: dict[str, Any] = {}
    for name, cls in middlewares().items():
        for option, info in cls.Options.model_fields.items():
            if option in options or option in StreamSpecBase.model_fields:
                raise ValueError(f"middleware {name!r} declares stream option {option!r}, which another has")
            options[option] = (info.annotation, info)
    return create_model("StreamSpec", __base__=StreamSpecBase, __module__=__name__, **options)


if TYPE_CHECKING:  # the options are known at run time only
    StreamSpec: TypeAlias = StreamSpecBase
else:
    StreamSpec = _stream_spec()


# `streams: [socket]` is shorthand for `streams: [{middleware: socket}]`; the JSON Schema accepts both spellings
Stream = Annotated[StreamSpec, BeforeValidator(_stream_shorthand, json_schema_input_type=Middleware | StreamSpec)]


class ModifierSpec(Strict):
    """`alter(name, **params)`: a post-processor on a sensor's output or an actuator's input."""

    model_config = ConfigDict(extra="allow", allow_inf_nan=False)
    name: Annotated[str, BeforeValidator(lambda v: v.lower() if isinstance(v, str) else v)] = Field(
        description="modifier: " + ", ".join(MODIFIER_TABLE))

    @model_validator(mode="after")
    def _known(self) -> ModifierSpec:
        if self.name not in MODIFIERS:
            raise PydanticCustomError("unknown_modifier", "unknown modifier {shown}{hint}",
                                      {"name": self.name, "shown": repr(self.name),
                                       "hint": did_you_mean(self.name, MODIFIERS)})
        for key, value in (self.model_extra or {}).items():
            if not isinstance(value, (bool, int, float, str, dict)):
                raise PydanticCustomError("bad_param", "modifier parameter {shown} must be a number, a string, "
                                          "a bool or a per-axis mapping", {"key": key, "shown": repr(key)})
        return self


MODIFIERS = tuple(MODIFIER_TABLE)


class OverlaySpec(Strict):
    """`add_overlay(middleware, overlay, **kwargs)`: services renamed or reshaped for one middleware."""

    model_config = ConfigDict(extra="allow", allow_inf_nan=False)
    middleware: ServiceMiddleware = Field(description="the middleware whose services are overlaid")
    overlay: str = Field(description="overlay class path")


class ComponentBase(Strict):
    """A sensor or an actuator placed on a robot (or on another component)."""

    name: Name | None = Field(None, description="component name (default: its type); the fully-qualified "
                              "name is robot.name")
    type: str = Field(description="catalogue id (motion_vw) or MORSE builder class name (MotionVW)")
    translate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="position in the parent frame, m")
    rotate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0],
                         description="XYZ Euler rotation in the parent frame, rad")
    frequency: Positive | None = Field(None, description="ticks per simulated second (default: the component's)")
    streams: list[Stream] = Field(default_factory=list, description="add_stream: middleware names or bindings")
    services: list[ServiceMiddleware] = Field(default_factory=list, description="add_service: middlewares")
    interfaces: list[Middleware] = Field(default_factory=list, description="add_interface: stream + service")
    modifiers: list[ModifierSpec] = Field(default_factory=list, description="alter: modifiers, in order")
    overlays: list[OverlaySpec] = Field(default_factory=list, description="add_overlay")
    color: Color | None = Field(None, description="set_color: RGB(A) in 0..1")
    profile: bool = Field(False, description="profile: report time spent in this component")
    components: list[AnyComponent] = Field(default_factory=list, description="children (append on a component)")
    tags: PropertyBag = Field(default_factory=dict, description=TAGS_DESCRIPTION)


# AnyComponent: the union of the catalogue's component models (subclasses of ComponentBase), generated by
# morsec.scene.schema.scene_model, which resolves this name when it builds them; not defined here at run time
if TYPE_CHECKING:
    AnyComponent: TypeAlias = ComponentBase


class RobotBase(Strict):
    """A robot: a catalogue body with its components."""

    name: Name | None = Field(None, description="robot name (default: its type)")
    type: str = Field(description="catalogue id (atrv) or MORSE builder class name (ATRV)")
    translate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="world position, m")
    rotate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="XYZ Euler rotation, rad")
    default_interface: Middleware | None = Field(
        None, description="add_default_interface: stream + service on every component lacking one")
    mass: Positive | None = Field(None, description="set_mass: total mass, kg (default: the robot's)")
    friction: Annotated[float, Field(ge=0, allow_inf_nan=False)] | None = Field(
        None, description="set_friction: sliding friction coefficient of the robot's geoms")
    ghost: Annotated[float, Field(ge=0, le=1)] | None = Field(
        None, description="make_ghost: transparency alpha; a ghost does not collide")
    collision: bool = Field(True, description="False: set_no_collision")
    physics_type: Literal["dynamic", "static", "rigid_body", "no_collision"] | None = Field(
        None, description="set_physics_type; static robots have no free joint")
    color: Color | None = Field(None, description="set_color")
    locks: list[Lock] = Field(default_factory=list, description=LOCKS_DESCRIPTION)
    components: list[AnyComponent] = Field(default_factory=list, description="sensors and actuators")
    without: list[Name] = Field(default_factory=list, description="components the robot type carries that this "
                                "robot leaves out, by name (MORSE's NavPR2(with_keyboard=False): [keyboard])")
    tags: PropertyBag = Field(default_factory=dict, description=TAGS_DESCRIPTION)


class ObjectSpec(Strict):
    """A passive object (PassiveObject / basic mesh): a shape with a property bag sensors can read."""

    name: Name | None = Field(None, description="object name (default: its type)")
    type: str = Field(description="prop id: box, cylinder, sphere")
    translate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="world position of the centre, m")
    rotate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="XYZ Euler rotation, rad")
    size: Size3 = Field(default_factory=lambda: [0.5, 0.5, 0.5],
                        description="full extent along x, y, z, m (cylinder: diameter, diameter, height)")
    color: Color = Field(default_factory=lambda: [0.6, 0.6, 0.6], description="RGB(A) in 0..1")
    dynamic: bool = Field(False, description="True: moves under physics (needs a mass); False: static")
    mass: Positive = Field(1.0, description="kg, used when dynamic")
    locks: list[Lock] = Field(default_factory=list, description=LOCKS_DESCRIPTION)
    properties: PropertyBag = Field(default_factory=dict,
                                    description="game properties: Label, Description, Type, Object, Graspable, "
                                                "Fire, ...")


class ZoneSpec(Strict):
    """Zone(type): an invisible axis-aligned box with a type (Charging, ...), tested by containment."""

    name: Name | None = Field(None, description="zone name (default: the type)")
    type: str = Field(description="zone type, e.g. Charging")
    translate: Vec3 = Field(default_factory=lambda: [0.0, 0.0, 0.0], description="centre, world frame, m")
    size: Size3 = Field(default_factory=lambda: [1.0, 1.0, 1.0], description="full extent along x, y, z, m")
    properties: PropertyBag = Field(default_factory=dict, description="extra properties")


class TimeSpec(Strict):
    strategy: TimeStrategy = Field(
        "best_effort", description="set_time_strategy: follow the wall clock, or run as fast as possible")
    frequency: Positive = Field(DEFAULT_FREQUENCY, description="simulator_frequency: main loop, Hz")
    scale: Annotated[float, Field(ge=MIN_TIME_SCALE, le=MAX_TIME_SCALE, allow_inf_nan=False)] = Field(
        1.0, description=f"set_time_scale: simulated seconds per wall-clock second ({MIN_TIME_SCALE:g} to "
        f"{MAX_TIME_SCALE:g})")
    relative: bool = Field(False, description="use_relative_time: timestamps start at 0 instead of the Unix epoch")
    physics_substeps: Annotated[int, Field(ge=1, le=1000)] = Field(
        DEFAULT_PHYSICS_SUBSTEPS, description="physics steps per main-loop frame")
    auto_tune: bool = Field(True, description="raise the main loop to the highest component frequency")


class CameraSpec(Strict):
    location: Vec3 = Field(default_factory=lambda: [5.0, -5.0, 5.0], description="set_camera_location, m")
    rotation: Vec3 = Field(default_factory=lambda: [0.7854, 0.0, 0.7854],
                           description="set_camera_rotation: XYZ Euler, rad (Blender camera: looks along -Z)")
    clip: Annotated[list[Positive], Field(min_length=2, max_length=2)] = Field(
        default_factory=lambda: [0.1, 100.0], description="set_camera_clip: near, far, m")
    focal: Positive = Field(20.0, description="set_camera_focal_length, mm (32 mm sensor width)")
    speed: Positive = Field(DEFAULT_CAMERA_SPEED, description="set_camera_speed: MORSE's fly speed (no MuJoCo "
                            "viewer has one)")


class MultinodeSpec(Strict):
    """configure_multinode: the scene's robots split over several `morsec run --node NAME` processes."""

    protocol: Literal["socket", "hla"] = Field(
        "socket", description="multinode protocol: socket (`morsec multinode-server`); hla is refused (no HLA "
        "run-time infrastructure can be installed)")
    server_address: str = Field("localhost", description="address of the multinode server")
    server_port: Annotated[int, Field(ge=1, le=65535)] = Field(MULTINODE_PORT,
                                                               description="port of the multinode server")
    distribution: dict[str, list[Name]] = Field(
        default_factory=dict, description="node name -> the robots it simulates (every robot on one node)")


class StreamManagerSpec(Strict):
    """configure_stream_manager(middleware, **kwargs)."""

    time_sync: bool = Field(False, description="socket lockstep: each message on sync_port advances one frame")
    sync_port: Annotated[int, Field(ge=1, le=65535)] = Field(6000, description="lockstep port")


def _check_recording(name: str) -> str:
    from morsec.middleware.text import check_output_file
    check_output_file(name, "a recording")
    if not name.endswith(".mcap"):
        raise ValueError("a recording is an MCAP file: its name ends with .mcap")
    return name


class RecordSpec(Strict):
    """env.record(file, services=False): every run of the scene recorded (docs/recording.md)."""

    file: Annotated[str, AfterValidator(_check_recording)] = Field(
        description="the MCAP file, relative to the run's output folder (morsec run --output-dir)")
    services: bool = Field(False, description="also record the service requests and their answers")


class ViewportSpec(Strict):
    shade: Literal[tuple(SHADES)] = Field(  # type: ignore[valid-type]
        DEFAULT_SHADE, description="viewport_shade: how the viewers and `morsec render` draw the scene "
        "(see running.md's display settings)")
    clip_end: Positive = Field(DEFAULT_CLIP_END, description="clip_end: Blender's 3D-view clipping, m; morsec "
                               "clips at camera.clip")


class EnvironmentBase(Strict):
    """Environment(name): the world, time, the viewer camera and global settings."""

    name: str = Field("empty", description="environment id: empty, sandbox, indoors-1/boxes, ...")
    fastmode: bool = Field(False, description="Environment(..., fastmode=True): wireframe display (as "
                           "viewport.shade WIREFRAME)")
    gravity: Annotated[float, Field(ge=0, allow_inf_nan=False)] = Field(9.81, description="set_gravity, m/s^2")
    time: TimeSpec = Field(default_factory=TimeSpec, description="time strategy and main-loop frequency")
    camera: CameraSpec = Field(default_factory=CameraSpec, description="the viewer's camera")
    properties: PropertyBag = Field(
        default_factory=dict, description="env.properties: longitude, latitude (deg), altitude (m), ...")
    services: list[ServiceMiddleware] = Field(
        default_factory=list,
        description="add_service: middlewares exposing supervision services (socket is always on)")
    stream_managers: dict[Middleware, StreamManagerSpec] = Field(
        default_factory=dict, description="configure_stream_manager")
    multinode: MultinodeSpec | None = Field(None, description="configure_multinode")
    seed: Annotated[int, Field(ge=0)] | None = Field(None, description="random seed for noise modifiers")
    record: RecordSpec | None = Field(
        None, description="env.record: record every run's streams in MCAP (morsec run --record overrides the file)")
    show_framerate: bool = Field(False, description="show_framerate: the viewers show the frame rate")
    show_physics: bool = Field(False, description="show_physics: collision shapes and contacts in the viewers "
                               "and `morsec render`")
    show_debug: bool = Field(False, description="show_debug_properties: the viewers list each robot's pose and "
                             "each component's data")
    viewport: ViewportSpec = Field(default_factory=ViewportSpec, description="set_viewport")
    auto_start: bool = Field(True, description="set_auto_start: false opens a viewer paused (space runs it)")
    fullscreen: bool = Field(False, description="fullscreen: full-screen native viewer window")
    stereo: Literal["NONE", "STEREO", "DOME", "ANAGLYPH", "QUADBUFFERED", "ABOVEBELOW", "INTERLACED",
                    "VINTERLACE", "SIDEBYSIDE"] = Field(
        "NONE", description="set_stereo: stereo display mode (SIDEBYSIDE: `morsec render` draws both eyes)")
    debug: bool = Field(False, description="set_debug: morsec's log at DEBUG level")
    morse_only: dict[str, Any] = Field(
        default_factory=dict, description="MORSE settings with no MuJoCo meaning, recorded as given")


class SceneBase(Strict):
    """A morsec scene."""

    environment: EnvironmentBase = Field(default_factory=EnvironmentBase, description="the world and global settings")
    robots: list[Any] = Field(default_factory=list, description="robots and their components")
    objects: list[ObjectSpec] = Field(default_factory=list, description="passive objects")
    zones: list[ZoneSpec] = Field(default_factory=list, description="zones")
    _source: Any = PrivateAttr(None)  # the SourceMap of the file it came from, to place compile errors
    # the generated Scene class: the names its variants' annotations use (see morsec.scene.schema.scene_model)
    __morsec_aliases__: ClassVar[dict[str, Any]]


# The concrete Scene type is generated per catalogue (morsec.scene.schema); this alias is for type hints.
Scene = SceneBase
