"""The Blender world a MORSE component sees, stood for by morsec's simulation: one `World` per simulation, holding a
game object (`GameObject`) for every robot, passive object and component, each robot as MORSE's robot object
(`RobotParent`: `robot_parent`), the scene (`blenderapi.scene()`) and the persistent storage
(`blenderapi.persistantstorage()`).

What a game object can do on MuJoCo it does (its name, pose, parent and children, game properties, vectors and
distances to other objects, rays); anything else a component asks of Blender stops the build or the run with one
line naming the component's file and line and what it asked for (`not_emulated`).
"""

from __future__ import annotations

import os
import sys
import weakref
from collections.abc import Mapping
from pathlib import Path
from typing import Any, NoReturn

import mujoco
import numpy as np

import morsec
from morse.core import mathutils
from morsec.errors import Unsupported
from morsec.kits.geometry import euler_to_quat, matrix_to_quat, quat_to_matrix

_OWN_CODE = (str(Path(__file__).resolve().parents[1]) + os.sep, str(Path(morsec.__file__).resolve().parent) + os.sep)
# the geom groups a ray meets: not 2 (visual geoms, component fragments) nor 5 (sites), as morsec's sensors
RAY_GROUPS = np.array([1, 1, 0, 1, 1, 0], dtype=np.uint8)
MAX_RAY_HOPS = 64  # objects an x-ray ray passes through before giving up


def user_location(skip: int = 1) -> str:
    """`file:line` of the innermost frame of the caller's stack that is neither the emulation nor morsec: the
    MORSE component's line that asked for something."""
    frame = sys._getframe(skip)
    while frame is not None:
        name = frame.f_code.co_filename
        if not name.startswith("<") and not os.path.abspath(name).startswith(_OWN_CODE):
            return f"{name}:{frame.f_lineno}"
        frame = frame.f_back
    return "<unknown>"


def not_emulated(what: str, why: str = "") -> NoReturn:
    """Stop: a MORSE component asked for `what`, which morsec does not emulate."""
    raise Unsupported(f"{user_location(2)}: {what} is not emulated by morsec" + (f": {why}" if why else "")
                      + " (docs/coming-from-morse.md lists what is)")


class CallableName(str):
    """A component's name: a string (morsec's `self.name`) that MORSE's `self.name()` also reads."""

    def __call__(self) -> str:
        return str(self)


class GameObject:
    """A Blender game object (KX_GameObject), as far as a MuJoCo body stands for one."""

    def __init__(self, world: World, name: str, body: int, kind: str, parent: str | None, defaults: dict):
        self._world = world
        self._name = name
        self._body = body
        self._kind = kind  # robot, object, component or scene (the script holder)
        self._parent = parent
        self._defaults = defaults  # game properties it has unless written (a component's properties ...)
        self._found_bag: dict | None = None  # its game properties in the running simulation, once found (property_bag)

    # ---- identity
    @property
    def name(self) -> str:
        return self._name

    def __repr__(self) -> str:
        return self._name

    __str__ = __repr__

    @property
    def parent(self) -> GameObject | None:
        return self._world.objects.get(self._parent) if self._parent else None

    @property
    def children(self) -> list[GameObject]:
        return [o for o in self._world.objects.values() if o._parent == self._name]

    @property
    def childrenRecursive(self) -> list[GameObject]:
        out = []
        for child in self.children:
            out += [child, *child.childrenRecursive]
        return out

    # ---- game properties: read and written as obj['Fire']; sensors of morsec read what is written
    def _bag(self, create: bool = False) -> dict | None:
        return self._world.property_bag(self, create)

    def __getitem__(self, key: str):
        bag = self._bag()
        if bag is not None and key in bag:
            return bag[key]
        return self._defaults[key]

    def __setitem__(self, key: str, value) -> None:
        self._bag(create=True)[key] = value

    def __delitem__(self, key: str) -> None:
        bag = self._bag()
        if bag is not None and key in bag:
            del bag[key]
        self._defaults.pop(key, None)

    def __contains__(self, key: str) -> bool:
        bag = self._bag()
        return (bag is not None and key in bag) or key in self._defaults

    def get(self, key: str, default=None):
        return self[key] if key in self else default

    def getPropertyNames(self) -> list[str]:
        return list(dict.fromkeys([*self._defaults, *(self._bag() or {})]))

    # ---- pose
    def _morsec_pose(self) -> tuple[list[float], list[float]]:
        """World position and row-major rotation, in double precision (Transformation3d reads them)."""
        d = self._world.sim.data
        return d.xpos[self._body].tolist(), d.xmat[self._body].tolist()

    def _position(self) -> np.ndarray:
        return self._world.sim.data.xpos[self._body].copy()

    def _rotation(self) -> np.ndarray:
        return self._world.sim.data.xmat[self._body].reshape(3, 3).copy()

    @property
    def worldPosition(self) -> mathutils.Vector:
        return mathutils.Vector(self._position())

    @worldPosition.setter
    def worldPosition(self, value) -> None:
        self._world.put(self, _vector(value), self._rotation())

    @property
    def worldOrientation(self) -> mathutils.Matrix:
        return mathutils.Matrix(self._rotation())

    @worldOrientation.setter
    def worldOrientation(self, value) -> None:
        self._world.put(self, self._position(), _rotation(value))

    position = worldPosition  # Blender 2.5's names, which MORSE's older components use
    orientation = worldOrientation

    def _parent_frame(self) -> tuple[np.ndarray, np.ndarray]:
        parent = self.parent
        if parent is None:
            return np.zeros(3), np.eye(3)
        return parent._position(), parent._rotation()

    @property
    def localPosition(self) -> mathutils.Vector:
        """In the parent's frame (the world's for an object without a parent)."""
        origin, rot = self._parent_frame()
        return mathutils.Vector(rot.T @ (self._position() - origin))

    @localPosition.setter
    def localPosition(self, value) -> None:
        origin, rot = self._parent_frame()
        self._world.put(self, origin + rot @ _vector(value), self._rotation())

    @property
    def localOrientation(self) -> mathutils.Matrix:
        _, rot = self._parent_frame()
        return mathutils.Matrix(rot.T @ self._rotation())

    @localOrientation.setter
    def localOrientation(self, value) -> None:
        _, rot = self._parent_frame()
        self._world.put(self, self._position(), rot @ _rotation(value))

    # ---- velocities (read)
    def _velocity(self, local: bool) -> tuple[np.ndarray, np.ndarray]:
        res = np.zeros(6)
        sim = self._world.sim
        mujoco.mj_objectVelocity(sim.model, sim.data, mujoco.mjtObj.mjOBJ_XBODY, self._body, res, 1 if local else 0)
        return res[3:], res[:3]

    def getLinearVelocity(self, local: bool = False) -> mathutils.Vector:
        return mathutils.Vector(self._velocity(local)[0])

    def getAngularVelocity(self, local: bool = False) -> mathutils.Vector:
        return mathutils.Vector(self._velocity(local)[1])

    worldLinearVelocity = property(lambda self: self.getLinearVelocity(False))
    localLinearVelocity = property(lambda self: self.getLinearVelocity(True))
    worldAngularVelocity = property(lambda self: self.getAngularVelocity(False))
    localAngularVelocity = property(lambda self: self.getAngularVelocity(True))

    def getPhysicsId(self) -> int:
        """Nonzero for an object that physics moves (a robot or object with a free joint)."""
        return 0 if self._world.free_joint(self._body) is None else self._body + 1

    # ---- towards other objects
    def _point(self, other) -> np.ndarray:
        if isinstance(other, GameObject):
            return other._position()
        if isinstance(other, str):
            return self._world.objects[other]._position()
        return _vector(other)

    def getVectTo(self, other) -> tuple[float, mathutils.Vector, mathutils.Vector]:
        """(distance, unit vector towards `other` in the world frame, the same in this object's frame)."""
        delta = self._point(other) - self._position()
        distance = float(np.linalg.norm(delta))
        unit = delta / distance if distance > 0 else delta
        return distance, mathutils.Vector(unit), mathutils.Vector(self._rotation().T @ unit)

    def getDistanceTo(self, other) -> float:
        return float(np.linalg.norm(self._point(other) - self._position()))

    def rayCast(self, objto, objfrom=None, dist=0.0, prop="", face=0, xray=0, poly=0, mask=0xFFFF):
        """The first object hit on the ray from `objfrom` (this object) towards `objto`, within `dist` (0: up to
        `objto`), having property `prop` if given (`xray`: through those that do not): (object, point,
        normal), or Nones; `poly` adds Blender's polygon (and uv), which MuJoCo has not: None."""
        start = self._point(objfrom) if objfrom is not None else self._position()
        hit = self._world.ray(start, self._point(objto), float(dist), str(prop), bool(xray), self._carrier())
        result = hit if hit is not None else (None, None, None)
        return result + (None,) * (1 if poly == 1 else 2 if poly else 0)

    def rayCastTo(self, other, dist=0.0, prop=""):
        """The first object hit from this object towards `other` within `dist` having `prop`, or None."""
        hit = self._world.ray(self._position(), self._point(other), float(dist), str(prop), False, self._carrier())
        return hit[0] if hit is not None else None

    def _carrier(self) -> GameObject:
        """What a ray from this object passes through: the object, and the robot carrying it (a component
        inside its robot's shape: Bullet's rays did not meet a shape from inside)."""
        top = self
        while top.parent is not None:
            top = top.parent
        return top

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        not_emulated(f"KX_GameObject.{name} ({self._name})")


class RobotParent:
    """A robot as MORSE's components see it (`self.robot_parent`, MORSE's morse.core.robot.Robot)."""

    def __init__(self, world: World, info):
        from morse.helpers.transformation import Transformation3d
        self._world = world
        self._handle = info.handle
        self.name = CallableName(info.name)
        self.bge_object = world.objects[info.name]
        self.position_3d = Transformation3d(self.bge_object)
        self.is_dynamic = self._handle.free
        self._no_gravity = bool(getattr(self._handle.properties, "NoGravity", False))
        self.move_status = "Stop"
        self.time_shift = 0.0
        self.level = "default"

    def gettime(self) -> float:
        """Simulated time as the robot sees it, s (a sensor's timestamp)."""
        return self._world.sim.clock.now() + self.time_shift

    def apply_speed(self, kind, linear_speed, angular_speed) -> None:
        """MORSE's robot.apply_speed: 'Velocity' sets the robot's body velocity (m/s, rad/s, robot frame),
        'Position' moves it by these amounts (the actuator divided them by its frequency), as morsec's own
        actuators do (morsec.runtime.robot.RobotHandle.apply_speed)."""
        current = self._world.current
        if kind == "Position":
            self._handle.apply_speed(kind, linear_speed, angular_speed, 1.0)
        else:
            self._handle.apply_speed(kind, linear_speed, angular_speed,
                                     float(getattr(current, "frequency", self._world.sim.clock.frequency)))

    def force_pose(self, position, orientation) -> None:
        """Put the robot at `position` (a vector or None) with `orientation` (a matrix or None)."""
        handle = self._handle
        pos, rot = handle.pose()
        self._world.put(self.bge_object, pos if position is None else _vector(position),
                        rot if orientation is None else _rotation(orientation))

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        not_emulated(f"robot_parent.{name} ({self.name})")


class Scene:
    """`blenderapi.scene()`: its objects (by index, by name, `in`, `get`)."""

    def __init__(self, world: World):
        self._world = world
        self.name = "Scene"

    @property
    def objects(self) -> ObjectList:
        return ObjectList(self._world.objects)

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        not_emulated(f"KX_Scene.{name}")


class ObjectList:
    """KX_Scene.objects: a list of game objects, also indexed by name."""

    def __init__(self, objects: dict[str, GameObject]):
        self._objects = objects

    def __iter__(self):
        return iter(list(self._objects.values()))

    def __len__(self) -> int:
        return len(self._objects)

    def __getitem__(self, key):
        if isinstance(key, int):
            return list(self._objects.values())[key]
        return self._objects[key]

    def __contains__(self, key) -> bool:
        return (key in self._objects) if isinstance(key, str) else key in self._objects.values()

    def get(self, key, default=None):
        return self._objects.get(key, default)

    def keys(self) -> list[str]:
        return list(self._objects)


class Clock:
    """`persistantstorage().time`: the simulated time MORSE's time strategies kept."""

    def __init__(self, world: World):
        self._world = world

    @property
    def time(self) -> float:
        """Simulated time, s (a sensor's timestamp)."""
        return self._world.sim.clock.now()

    @property
    def frequency(self) -> float:
        return self._world.sim.clock.frequency

    def name(self) -> str:
        return self._world.sim.clock.strategy


class PersistantStorage(dict):
    """`blenderapi.persistantstorage()`: what components read there (the time, the robots, the components)."""

    def __getattr__(self, name: str):
        if name in self:
            return self[name]
        if name.startswith("_"):
            raise AttributeError(name)
        not_emulated(f"blenderapi.persistantstorage().{name}")

    def __setattr__(self, name: str, value) -> None:
        self[name] = value


class Components(Mapping):
    """`persistantstorage().componentDict`: every component of the simulation by name (its instance)."""

    def __init__(self, sim):
        self._sim = sim

    def _all(self) -> dict:
        return {c.fqn: c.instance for c in getattr(self._sim, "components", ())}

    def __getitem__(self, key):
        return self._all()[key]

    def __iter__(self):
        return iter(self._all())

    def __len__(self) -> int:
        return len(self._all())


class World:
    """The MORSE view of one simulation, built when its first MORSE component is."""

    def __init__(self, sim):
        self.sim = sim
        self.current: Any = None  # the MORSE component being ticked or built
        self.objects: dict[str, GameObject] = {}
        model = sim.model
        body = lambda name: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)  # noqa: E731
        # their game properties, until the simulation's scene objects (which morsec's sensors read) exist
        for robot in sim.scene["robots"]:
            self._add(robot["name"], body(robot["name"]), "robot", None,
                      {"Robot_Tag": True, **robot["properties"], **robot.get("tags", {})})
        for obj in sim.scene["objects"]:
            self._add(obj["name"], body(obj["name"]), "object", None, dict(obj["properties"]))
        for entry in sim.manifest.components:
            self._add(entry.fqn, body(entry.fqn), "component", entry.parent,
                      {"Component_Tag": True, **entry.properties, **entry.tags})
        self.script_holder = GameObject(self, "Scene_Script_Holder", 0, "scene", None,
                                        dict(sim.scene["environment"].get("properties", {})))
        self.robots = {info.name: RobotParent(self, info) for info in sim.robots}
        self.scene = Scene(self)
        self.storage = PersistantStorage(
            time=Clock(self), robotDict={r.bge_object: r for r in self.robots.values()},
            componentDict=Components(sim))
        # body -> the game object it is part of (a robot's links are the robot's)
        owner = {}
        for obj in self.objects.values():
            owner[obj._body] = obj
        self._owner = []
        for b in range(model.nbody):
            found, walk = None, b
            while walk > 0 and found is None:
                found, walk = owner.get(walk), model.body_parentid[walk]
            self._owner.append(found)
        self._free: dict[int, tuple[int, int] | None] = {}

    def _add(self, name: str, body: int, kind: str, parent: str | None, defaults: dict) -> None:
        self.objects[name] = GameObject(self, name, body, kind, parent, defaults)

    def property_bag(self, obj: GameObject, create: bool) -> dict | None:
        """The game properties morsec's sensors read of `obj` (robots, objects, tagged components): one dict,
        shared; a component without tags gets one when a property is first written."""
        if obj._found_bag is not None:  # found before: the simulation's objects and their dicts stay put
            return obj._found_bag
        for scene_object in getattr(self.sim, "objects", ()):
            if scene_object.name == obj.name:
                obj._found_bag = scene_object.properties
                return obj._found_bag
        if obj._kind == "scene" or (create and not hasattr(self.sim, "objects")):
            return obj._defaults  # the script holder; or written while the simulation is being built
        if not create:
            return None
        from morsec.runtime.simulation import SceneObject
        made = SceneObject(obj.name, obj._body, obj._kind, {})
        self.sim.objects.append(made)
        obj._found_bag = made.properties
        return obj._found_bag

    def free_joint(self, body: int):
        if body not in self._free:
            from morsec.runtime.robot import free_joint
            self._free[body] = free_joint(self.sim.model, body)
        return self._free[body]

    def put(self, obj: GameObject, pos, rot) -> None:
        """Move `obj` to a world pose: a robot or an object through its free joint (held there through this
        frame's physics, as a teleport), a component by moving its body on its parent."""
        sim = self.sim
        if obj._kind in ("robot", "object"):
            sim.place_body(obj._body, pos, rot)
            sim.pin(obj._body)
            mujoco.mj_kinematics(sim.model, sim.data)
            return
        if obj._kind != "component":
            not_emulated(f"moving {obj.name}")
        m, d = sim.model, sim.data
        parent = m.body_parentid[obj._body]
        parent_pos, parent_rot = d.xpos[parent], d.xmat[parent].reshape(3, 3)
        m.body_pos[obj._body] = parent_rot.T @ (np.asarray(pos, float) - parent_pos)
        m.body_quat[obj._body] = matrix_to_quat(parent_rot.T @ np.asarray(rot, float))
        mujoco.mj_kinematics(m, d)
        sim.poses_changed()

    def ray(self, start, target, dist: float, prop: str, xray: bool, ignored: GameObject):
        """(object, point, normal) of the first hit from `start` towards `target` within `dist` (0: up to the
        target), of an object with property `prop` if given, passing through `ignored` and the components it
        carries; None if nothing."""
        sim = self.sim
        direction = np.asarray(target, float) - np.asarray(start, float)
        length = float(np.linalg.norm(direction))
        if length == 0:
            return None
        direction /= length
        reach = dist if dist > 0 else length
        origin, travelled = np.asarray(start, float).copy(), 0.0
        geom, normal = np.zeros(1, dtype=np.int32), np.zeros(3)
        exclude = ignored._body
        for _ in range(MAX_RAY_HOPS):
            found = mujoco.mj_ray(sim.model, sim.data, origin, direction, RAY_GROUPS, 1, exclude, geom, normal)
            if found < 0 or travelled + found > reach:
                return None
            point = origin + found * direction
            body = sim.model.geom_bodyid[geom[0]]
            hit = self._owner[body]
            passing = hit is not None and hit._carrier() is ignored
            if not passing and (not prop or (hit is not None and prop in hit)):
                return hit, mathutils.Vector(point), mathutils.Vector(normal)
            if not passing and not xray:
                return None
            exclude = body  # on through it
            origin, travelled = point, travelled + found
        return None


_WORLDS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_ACTIVE: list[World] = []  # the world of the simulation whose MORSE component runs (blenderapi.scene())


def world_of(sim) -> World:
    world = _WORLDS.get(sim)
    if world is None:
        world = _WORLDS[sim] = World(sim)
    if not _ACTIVE or _ACTIVE[-1] is not world:
        _ACTIVE[:] = [world]
    return world


def active_world(what: str) -> World:
    if not _ACTIVE:
        not_emulated(what, "called outside a running simulation (at import time?)")
    return _ACTIVE[-1]


def _vector(value) -> np.ndarray:
    out = np.asarray(list(value), dtype=float)
    if out.shape != (3,):
        raise ValueError(f"a position has 3 coordinates, got {list(value)!r}")
    return out


def _rotation(value) -> np.ndarray:
    """A rotation as Blender accepts one: a 3x3 matrix, a quaternion, an Euler (or 3 angles, XYZ)."""
    if isinstance(value, mathutils._blender.Quaternion):
        value = value.to_matrix()
    elif isinstance(value, mathutils._blender.Euler):
        value = value.to_matrix()
    rows = [list(row) if hasattr(row, "__iter__") else row for row in value]
    if len(rows) == 3 and all(isinstance(r, list) and len(r) >= 3 for r in rows):
        return np.array([r[:3] for r in rows], dtype=float)
    if len(rows) == 3:
        return quat_to_matrix(euler_to_quat(*(float(v) for v in rows)))
    raise ValueError(f"an orientation is a 3x3 matrix, a quaternion or 3 Euler angles, got {value!r}")

