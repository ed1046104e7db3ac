"""What a component folder's `component.py` declares: the seed's add_data / add_property / add_level,
as class attributes.

    class Pose(Sensor):
        \"\"\"World pose of the sensor.\"\"\"
        short_descr = "Position and orientation of the sensor in the world frame"
        builder_name = "Pose"
        class Properties(ComponentProperties):
            pass
        data = (DataField("x", 0.0, "float", "x coordinate, world frame, m"), ...)

    COMPONENT = Pose

The runtime instantiates the class (or its level's class) once per scene component; `default_action`
reads or writes `local_data` only: components never talk to a middleware.
"""

from __future__ import annotations

import copy
import inspect
import struct
from collections import OrderedDict
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import mujoco
import numpy as np

from morsec.component.fields import check_type, object_schema
from morsec.component.properties import ComponentProperties, RobotProperties
from morsec.component.services import ServiceInfo, service
from morsec.errors import did_you_mean
from morsec.kits.geometry import matrix_to_euler
from morsec.modifiers.base import Modifier

if TYPE_CHECKING:  # an environment's layout is the compiler's to read: a run does not import it
    from morsec.kits.layout import Part, Terrain


@dataclass(frozen=True)
class DataField:
    """One entry of `local_data` (add_data): on the wire in declaration order, `timestamp` first for sensors.
    `type` is one of morsec.component.fields.FIELD_TYPES ("float", "vec3", "list[float]", ...)."""

    name: str
    default: Any
    type: str
    doc: str
    level: str | tuple[str, ...] | None = None  # None: present at every level

    def __post_init__(self) -> None:
        check_type(self.name, self.type)

    def at(self, level: str | None) -> bool:
        if self.level is None or level is None:
            return True
        levels = (self.level,) if isinstance(self.level, str) else self.level
        return level in levels


@dataclass(frozen=True)
class Level:
    """A level of realism (add_level): its name, the class implementing it (None: the component's own), a doc."""

    name: str
    cls: str | None
    doc: str
    default: bool = False


class Component:
    """Common declarations of every catalogue entry."""

    kind: ClassVar[str] = "component"
    builder_name: ClassVar[str | None] = None  # MORSE builder class name (MotionVW); default: CamelCase of the id
    short_descr: ClassVar[str] = ""
    Properties: ClassVar[type[ComponentProperties]] = ComponentProperties

    # filled in by the catalogue when the folder is loaded
    id: ClassVar[str] = ""
    folder: ClassVar[Any] = None

    @classmethod
    def doc(cls) -> str:
        return inspect.cleandoc(cls.__doc__ or "")


class Device(Component):
    """A sensor or an actuator: data fields, levels, a frequency, services."""

    kind: ClassVar[Literal["sensor", "actuator"]]  # set by Sensor and Actuator
    direction: ClassVar[Literal["IN", "OUT"]]  # of its streams by default: OUT for a sensor, IN for an actuator
    frequency: ClassVar[float] = 60.0
    data: ClassVar[tuple[DataField, ...]] = ()
    levels: ClassVar[tuple[Level, ...]] = ()
    exportable: ClassVar[bool] = True  # False: no stream (keyboard, drag)
    # robot class attributes this component reads (e.g. motion_vw_diff: wheel_radius, wheel_track, ...):
    # checked at build time, so mounting it on a robot without them is a clear scene error
    robot_requires: ClassVar[tuple[str, ...]] = ()
    # a device with moving parts (a pan-tilt unit, an arm) may describe them in a xacro file of its folder,
    # placed in its own body (links `<fqn>/L`, joints `<fqn>/J`), with optional joint armature (kg m^2; the
    # key "*" for every joint not named)
    xacro: ClassVar[str | None] = None
    joint_armature: ClassVar[dict[str, float]] = {}
    # a class whose methods MORSE's builder class of this component had besides the common ones (Joystick's
    # `index` argument, Sound's `open`): the builder's class for it inherits them. It calls only builder methods
    # (`self.properties(...)`, `super().__init__(name)`), never imports the builder
    builder_mixin: ClassVar[type | None] = None
    # where child components attach: a body of this component's model, relative to it ("tilt" -> the
    # `<fqn>/tilt` body), e.g. a camera on a pan-tilt unit follows the tilt; None: the component's body
    mount_body: ClassVar[str | None] = None
    # True: the children's translate / rotate are in this component's own frame with its joints at zero (not
    # in the mount body's), and they keep that place on the mount body: MORSE's armatures, whose children
    # are placed in the arm's frame and ride on its end
    mount_in_own_frame: ClassVar[bool] = False
    # the modifiers (`alter(name)`) that apply to this component: {name: Modifier class}, names from
    # morsec.modifiers.registry, e.g. {"noise": PoseNoise, "ned": ToNED}. A subclass (a preset, a level)
    # inherits them, as any class attribute; to add some: {**Base.modifiers, "feet": ToFeet}
    modifiers: ClassVar[dict[str, type[Modifier]]] = {}
    # the stream's message, when it is not `local_data`'s fields: a sensor whose serialize() has its own
    # format (cameras: pictures in base64, their size) declares the fields of that message here
    message_fields: ClassVar[tuple[DataField, ...] | None] = None
    # keys besides the declared fields, named at run time (an armature's joints, a compound's sensors): one
    # DataField giving their type and meaning ("<joint>": float); None: no other key
    extra_field: ClassVar[DataField | None] = None
    # a class found by its dotted path rather than in a component folder (a MORSE-API component of a `morse
    # create` folder's src/: morse.core.sensor.Sensor's subclasses): the path, which is also its id, and the
    # folder it is imported from. Set by the catalogue; such a class has no builder class of its own (its
    # SensorCreator / ActuatorCreator names it by `_classpath`)
    classpath: ClassVar[str | None] = None
    import_root: ClassVar[Any] = None

    @classmethod
    def default_level(cls) -> str | None:
        for level in cls.levels:
            if level.default:
                return level.name
        return cls.levels[0].name if cls.levels else None

    @classmethod
    def fields_at(cls, level: str | None) -> list[DataField]:
        return [f for f in cls.data if f.at(level)]

    @classmethod
    def wire_fields(cls, level: str | None) -> list[DataField]:
        """The fields of a stream message at `level`, in order."""
        if cls.message_fields is None:
            return cls.fields_at(level)
        return [f for f in cls.message_fields if f.at(level)]

    @classmethod
    def message_schema(cls, level: str | None = None) -> dict:
        """JSON Schema of one message of this component's stream at `level` (a component whose message the
        fields cannot describe, e.g. one nesting other components' messages, overrides it)."""
        sensor = getattr(cls, "direction", "OUT") == "OUT"
        what = ("what the sensor publishes each tick: one JSON object per line of its socket stream" if sensor
                else "a command to the actuator: one JSON object per line of its socket stream; a field left "
                "out takes its default")
        title = f"{cls.id} message" + (f" (level {level})" if level else "")
        return object_schema(cls.wire_fields(level), cls.extra_field, required=sensor, title=title,
                             description=what)

    @classmethod
    def services(cls) -> dict[str, ServiceInfo]:
        found: dict[str, ServiceInfo] = {}
        for klass in reversed(cls.__mro__):
            for attr in vars(klass).values():
                info = getattr(attr, "_morsec_service", None)
                if info is not None:
                    found[info.name] = info
        return dict(sorted(found.items()))

    # ---- run time: the simulation creates one instance per scene component
    def __init__(self, context: Any = None):
        self.context = context
        self.local_data: OrderedDict[str, Any] = OrderedDict()
        if context is None:  # declaration-only use (docs, schema)
            return
        self.sim = context.sim
        self.name: str = context.fqn
        self.robot = context.robot
        self.body_id: int = context.body_id
        self.properties = context.properties
        self.level: str | None = context.level
        self.frequency: float = context.frequency
        for f in self.fields_at(self.level):
            self.local_data[f.name] = copy.deepcopy(f.default)

    def start(self) -> None:
        """Called once, after the first forward kinematics, before the loop starts."""

    def default_action(self) -> None:
        """Sensors compute `local_data`; actuators apply it. Called at the component's frequency."""

    def interrupt(self) -> None:
        """A running asynchronous service of this component was cancelled or preempted."""

    def reset(self) -> None:
        """`simulation reset_objects` put every object back at its initial pose: forget targets that would
        move it away again (a teleport's pose, an arm's joint set-points). Commands such as speeds stay."""

    def finalize(self) -> None:
        """Called once when the simulation closes: free what `start` took (renderers, files)."""

    def completed(self, status: str = "SUCCESS", result: Any = None, request: Any = None) -> None:
        """End a running asynchronous service (the one started last, unless `request` is given)."""
        self.sim.requests.complete(self.name, status, result, request)

    # ---- services every component has (reference §2)
    @service
    def get_properties(self) -> dict:
        """The component's properties: {name: value}."""
        return self.properties.model_dump(mode="json")

    @service
    def set_property(self, prop_name: str, prop_val: Any) -> None:
        """Change one property (validated against the component's property model)."""
        if prop_name not in type(self.properties).model_fields:
            raise ValueError(f"no property {prop_name!r}{did_you_mean(prop_name, type(self.properties).model_fields)}")
        setattr(self.properties, prop_name, prop_val)

    @service
    def get_configurations(self) -> dict:
        """Level, frequency, streams, services and modifiers of this component."""
        return self.context.configuration

    # ---- frame helpers: this component's frame in the world
    def position(self):
        return self.sim.data.xpos[self.body_id]

    def rotation(self):
        return self.sim.data.xmat[self.body_id].reshape(3, 3)

    def euler(self) -> tuple[float, float, float]:
        """(roll, pitch, yaw) of this component's frame, XYZ Euler, rad."""
        return matrix_to_euler(self.rotation())

    def velocity(self, local: bool = True):
        """(linear, angular) velocity of this component's frame, in its own frame or the world's."""
        res = np.zeros(6)
        # XBODY: the body's own frame (xpos, xmat); BODY would be its inertial frame, which MuJoCo puts
        # elsewhere for a massless component body
        mujoco.mj_objectVelocity(self.sim.model, self.sim.data, mujoco.mjtObj.mjOBJ_XBODY, self.body_id, res,
                                 1 if local else 0)
        return res[3:], res[:3]


TIMESTAMP = DataField("timestamp", 0.0, "float", "simulated time of the measure, s: since the Unix epoch (the clock "
                      "starts at the wall-clock time of the start), or since the start with environment.time.relative")


class Sensor(Device):
    kind = "sensor"
    direction = "OUT"
    # a sensor with a ComputationMode: "Velocity" or "Position", resolved by its start() (Automatic per robot)
    mode: str | None = None

    @classmethod
    def fields_at(cls, level: str | None) -> list[DataField]:
        return [TIMESTAMP] + super().fields_at(level)

    @classmethod
    def wire_fields(cls, level: str | None) -> list[DataField]:
        fields = super().wire_fields(level)
        return fields if cls.message_fields is None else [TIMESTAMP] + fields

    @service
    def get_local_data(self) -> dict:
        """The last data this sensor computed."""
        return dict(self.local_data)

    def serialize(self) -> dict | None:
        """The message its streams publish for this tick: `local_data` (MORSE's straight JSON) unless the
        sensor has its own format (cameras: pictures in base64); None: publish nothing this tick."""
        return self.local_data

    def apply_modifiers(self, modifiers: list[Modifier]) -> None:
        """Run the scene's modifiers on this tick's data, in order (after default_action)."""
        for modifier in modifiers:
            modifier.modify(self.local_data)


_POSITION, _ROTATION = struct.Struct("=3d"), struct.Struct("=9d")  # MjData's rows of xpos and xmat, native doubles


def body_position(poses: tuple[bytes, bytes], body: int) -> tuple[float, float, float]:
    """A body's world position (x, y, z), in a copy of the bodies' poses (Simulation.body_poses)."""
    return _POSITION.unpack_from(poses[0], 24 * body)


def body_rotation(poses: tuple[bytes, bytes], body: int) -> tuple[float, ...]:
    """A body's world rotation, row-major (9 floats), in a copy of the bodies' poses (Simulation.body_poses)."""
    return _ROTATION.unpack_from(poses[1], 72 * body)


class SampledSensor(Sensor):
    """A sensor whose data at a tick follows from a few numbers read at that tick, its sample (a pose; the
    previous one too), by arithmetic that costs far more than reading them (Euler angles, changes of frame).
    Its tick only takes the sample; `local_data` is computed from the last sample when something reads it (a
    stream with a reader, a service, a modifier, a recording, another component): the same data as if
    computed at every tick, at no cost for the ticks nobody reads. A subclass implements `sample()` (read at
    every tick) and `compute(*sample)`, which fills every field of local_data but the timestamp; its data
    must follow from the last sample alone, never from what earlier ticks computed (those may never be
    computed). A deferrable modifier (Modifier.deferrable: Gaussian noise) draws at the tick and applies
    when the data is read; any other runs at the tick, and so computes the data there."""

    # True: the sensor's sample is (or holds) `self.sim.body_poses`, the copy of the bodies' world poses the loop
    # takes once a frame (at the first sensor due) when a sensor reads it; `compute` reads its body's pose from it
    # with body_position and body_rotation. A tick then costs no read of its own.
    reads_body_poses: ClassVar[bool] = False
    _sample: tuple | None = None  # the last tick's sample, while local_data is not computed from it yet
    # (modifier, what it drew) of the deferrable modifiers of the ticks since the last sample, not applied yet
    _deferred: list[tuple[Modifier, Any]] | None = None

    @property  # type: ignore[override]
    def local_data(self) -> OrderedDict[str, Any]:
        sample, deferred = self._sample, self._deferred
        if sample is not None or deferred is not None:
            self._sample = self._deferred = None
            if sample is not None:
                self.compute(*sample)
            if deferred is not None:
                for modifier, drawn in deferred:
                    modifier.apply(self.local_dict, drawn)
        return self.local_dict

    @local_data.setter
    def local_data(self, value: OrderedDict[str, Any]) -> None:
        self.local_dict = value  # the dict itself: the loop writes the timestamp in it, computing nothing

    def default_action(self) -> None:
        sample = self.sample()
        if sample is not None:  # a new sample: the modifiers deferred since the last one applied to data that
            self._sample, self._deferred = sample, None  # compute() overwrites (deferrable: its fields only)

    def apply_modifiers(self, modifiers: list[Modifier]) -> None:
        for modifier in modifiers:
            if modifier.deferrable:
                drawn = modifier.draw()  # at the tick, read or not: the same draws in the same order
                if self._deferred is None:
                    self._deferred = [(modifier, drawn)]
                else:
                    self._deferred.append((modifier, drawn))
            else:
                modifier.modify(self.local_data)  # computes the data and applies the deferred ones first

    def sample(self) -> tuple | None:
        """What local_data at this tick is computed from (read from MuJoCo at the tick); None: this tick
        takes no sample, the data stays the last one's."""
        raise NotImplementedError

    def compute(self, *sample: Any) -> None:
        """Fill local_data from a sample."""
        raise NotImplementedError


class Actuator(Device):
    kind = "actuator"
    direction = "IN"
    # True: the robot gets velocity servos (forward, lateral, yaw) on its base site, driven through
    # RobotHandle.apply_speed; MuJoCo runs them inside the physics sub-steps, no Python per sub-step
    base_servo: ClassVar[bool] = False


class Robot(Component):
    """A robot: a xacro file in its folder describing links and joints, plus physics settings."""

    kind = "robot"
    Properties = RobotProperties
    xacro: ClassVar[str] = "robot.urdf.xacro"
    # height of the origin above the ground when the robot stands on it: a robot placed lower stands on the
    # ground, its origin this high (an ATRV's origin is 0.10 m up, as MORSE's); see origin_z
    spawn_height: ClassVar[float] = 0.0
    # XYZ Euler angles (rad) of the robot's object in MORSE's .blend, to which the builder's rotate() adds:
    # the robot's frame where a scene puts it with no rotation (the Hummer's: -pi/2 about z)
    origin_rotation: ClassVar[tuple[float, float, float]] = (0.0, 0.0, 0.0)
    static: ClassVar[bool] = False  # True: no free joint (e.g. a fake robot holding sensors)
    joint_armature: ClassVar[dict[str, float]] = {}  # {URDF joint name: rotor inertia, kg m^2}
    collision: ClassVar[bool] = True
    # Blender's game damping and rotation damping of the robot's body (its .blend's Physics panel; Blender's
    # defaults 0.04 and 0.1): the fraction of its linear and angular velocity a free robot loses per second
    # (Bullet: v *= (1 - damping) ** dt at each step). Given to robots that move under physics (not static,
    # colliding); (0, 0): none
    damping: ClassVar[tuple[float, float]] = (0.04, 0.1)
    # components every robot of this type carries unless the scene lists one of the same name, e.g.
    # ({"name": "motion", "type": "motion_vw"}, {"name": "pose", "type": "pose"}) — MORSE builder robots
    # that append their own actuators and sensors in __init__
    default_components: ClassVar[tuple[dict, ...]] = ()
    # a default component that rides on a body of another one's model rather than on the robot's base:
    # {component: (component, body)}, e.g. the PR2's {"head": ("torso", "torso_lift_link")}; the first keeps
    # its name (robot.head) and its `translate` is then relative to that body
    component_mounts: ClassVar[dict[str, tuple[str, str]]] = {}
    # what the builder's robot.add_interface(middleware) does (MORSE builder robots that define it, BasePR2),
    # per middleware ("*": any other): {"streams": (component or (component, {stream options}), ...),
    # "services": (component, ...), "overlays": ((component, overlay class path, {kwargs}), ...)}. Components
    # are named as the builder's attributes of the robot (`torso_pose` for the torso's `pose`); "{robot}" in an
    # option's text is the robot's name
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {}

    @classmethod
    def origin_z(cls, z: float, properties) -> float:
        """Where the compiler puts the origin of a robot that `translate` puts at height z. MORSE puts the
        origin there, then physics acts: a robot that floats (NoGravity) stays there (`RMax().translate(z=20)`
        reads z = 20 on its pose sensor); one that gravity holds falls from there, or, put lower than it
        stands, is pushed up by the ground till it stands on it (a Segway at z = 0.1 rests at once at 0.20)."""
        if getattr(properties, "NoGravity", False):
            return z
        return max(z, cls.spawn_height)


class Environment(Component):
    """A world: `environment.xml.j2` in its folder, placed in the worldbody."""

    kind = "environment"
    template: ClassVar[str] = "environment.xml.j2"
    # the passive objects the world holds, as entries of a scene's `objects:` (name, type, translate, size,
    # color, properties ...): MORSE's named .blend objects with their game properties, which sensors find
    # (the semantic camera's RedBox); a scene object of the same name replaces one
    objects: ClassVar[tuple[dict, ...]] = ()
    # its static shapes (walls, furniture, buildings, trees) and its uneven ground, as data
    # (morsec.kits.layout: block, column, ball, blob, Terrain), written by the compiler after environment.xml.j2
    layout: ClassVar[tuple[Part, ...]] = ()
    terrain: ClassVar[Terrain | None] = None
    # the box the world fills, ((xmin, ymin, zmin), (xmax, ymax, zmax)) m, as its README states it (the
    # gallery frames it); None: unbounded (an open plane)
    bounds: ClassVar[tuple[tuple[float, float, float], tuple[float, float, float]] | None] = None


class Prop(Component):
    """A passive object shape: `model.xml.j2` in its folder, given size and colour."""

    kind = "prop"
    template: ClassVar[str] = "model.xml.j2"
    # the prop's own values of the fields an `objects:` entry leaves out (size, color, dynamic, mass,
    # properties), e.g. a MORSE .blend object's: {"size": [0.04, 0.12, 0.2], "dynamic": True}; properties
    # the entry gives are added to the prop's
    defaults: ClassVar[dict] = {}
    # a prop kind holding several objects, as a MORSE props file does (props/objects: RollingChair,
    # BlackVideotape, ...): {object name: its defaults (size, color, dynamic, mass, properties) and its
    # "parts" (morsec.kits.layout.PropPart, at that size, around the object's origin)}. Each name is a `type:`
    # of its own (and PassiveObject's name); the kind's template draws the named object's parts
    variants: ClassVar[dict[str, dict]] = {}


KINDS: dict[str, type[Component]] = {
    "robots": Robot,
    "sensors": Sensor,
    "actuators": Actuator,
    "environments": Environment,
    "props": Prop,
}
