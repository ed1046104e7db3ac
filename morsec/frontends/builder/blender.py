"""Stand-ins for the Blender objects MORSE scripts reach: `obj._bpy_object` and `bpymorse.get_object(name)`.

morsec has no Blender, but a MORSE script sometimes steps past the builder API into the Blender object
behind a builder object, or into an object of MORSE's Blender environment file:

    robot._bpy_object.game.lock_location_z = True     # the robot cannot move along world z
    ground = bpymorse.get_object('Ground')            # an object of the .blend environment
    ground.game.use_actor = True

What has a meaning in the scene IR is recorded there: the `lock_location_x/y/z` and
`lock_rotation_x/y/z` flags of a robot or a passive object become its `locks`; `game.physics_type` and
`game.mass` are `set_physics_type` / `set_mass`; `location`, `rotation_euler`, `scale` and `name` are the
builder object's. Everything else (an environment object's settings, a component's locks, any other
Blender attribute) is accepted, recorded in `environment.morse_only` and warned about once, naming the
script line, like the other MORSE-only calls.
"""

from __future__ import annotations

from typing import Any

LOCKS = ("location_x", "location_y", "location_z", "rotation_x", "rotation_y", "rotation_z")


class BlenderPath:
    """Something reached through a Blender object that morsec does not map. Reading an attribute gives
    another BlenderPath; setting one, setting an item or calling it records the value in
    environment.morse_only and warns once, naming the script line. Iterating gives nothing."""

    def __init__(self, session, owner, path: str, shown: str, reason: str):
        object.__setattr__(self, "_session", session)
        object.__setattr__(self, "_owner", owner)  # the builder object behind it, None for environment objects
        object.__setattr__(self, "_path", path)  # the key in environment.morse_only (after the owner's name)
        object.__setattr__(self, "_shown", shown)  # how the script wrote it
        object.__setattr__(self, "_reason", reason)

    def _child(self, name: str) -> BlenderPath:
        return BlenderPath(self._session, self._owner, f"{self._path}.{name}", f"{self._shown}.{name}", self._reason)

    def _record(self, key: str, shown: str, value: Any) -> None:
        self._session.morse_only(self._owner, key, value, self._reason, shown=shown)

    def __getattr__(self, name: str):
        if name.startswith("__"):
            raise AttributeError(name)
        return self._child(name)

    def __setattr__(self, name: str, value: Any) -> None:
        if isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
            return
        self._record(f"{self._path}.{name}", f"{self._shown}.{name} = {value!r}", value)

    def __getitem__(self, key):
        return BlenderPath(self._session, self._owner, f"{self._path}[{key!r}]", f"{self._shown}[{key!r}]",
                           self._reason)

    def __setitem__(self, key, value) -> None:
        self._record(f"{self._path}[{key!r}]", f"{self._shown}[{key!r}] = {value!r}", value)

    def __call__(self, *args, **kwargs):
        shown_args = ", ".join([repr(a) for a in args] + [f"{k}={v!r}" for k, v in kwargs.items()])
        self._record(self._path, f"{self._shown}({shown_args})", {"args": list(args), **kwargs})
        return BlenderPath(self._session, self._owner, f"{self._path}()", f"{self._shown}(...)", self._reason)

    def __iter__(self):
        return iter(())

    def __len__(self) -> int:
        return 0

    def __bool__(self) -> bool:
        return True

    def __repr__(self) -> str:
        return f"<Blender {self._shown} (morsec has no Blender)>"


class BlenderObject(BlenderPath):
    """`obj._bpy_object` of a builder object (robot, component, passive object, zone, environment)."""

    def __init__(self, node):
        label = f"{_variable(node)}._bpy_object"
        super().__init__(node._session, node, "_bpy_object", label,
                         "is a Blender setting with no meaning in morsec")

    @property
    def name(self) -> str:
        return self._owner.name

    @name.setter
    def name(self, value) -> None:
        self._owner.name = value

    @property
    def location(self):
        return self._owner.location

    @location.setter
    def location(self, xyz) -> None:
        self._owner.location = xyz

    @property
    def rotation_euler(self):
        return self._owner.rotation_euler

    @rotation_euler.setter
    def rotation_euler(self, xyz) -> None:
        self._owner.rotation_euler = xyz

    @property
    def scale(self):
        return self._owner.scale

    @scale.setter
    def scale(self, xyz) -> None:
        self._owner.scale = xyz

    @property
    def game(self) -> GameSettings:
        return GameSettings(self)


class GameSettings(BlenderPath):
    """`obj._bpy_object.game`: Blender's game-engine settings of one builder object."""

    def __init__(self, obj: BlenderObject):
        super().__init__(obj._session, obj._owner, f"{obj._path}.game", f"{obj._shown}.game", obj._reason)

    def __getattr__(self, name: str):
        if name.startswith("lock_") and name[5:] in LOCKS:
            return name[5:] in self._owner._locks()
        if name == "mass" and self._owner._kind in ("robot", "object"):
            return self._owner._raw.get("mass", 0.0)
        return super().__getattr__(name)

    def __setattr__(self, name: str, value: Any) -> None:
        owner = self._owner
        if name.startswith("lock_") and name[5:] in LOCKS:
            if owner._kind in ("robot", "object"):
                owner._lock(name[5:], bool(value))
                return
            self._record(f"{self._path}.{name}", f"{self._shown}.{name} = {value!r}", value,
                         reason="locks only robots and passive objects in morsec (a component is fixed to "
                                "its robot; the environment does not move)")
            return
        if name == "physics_type" and owner._kind in ("robot", "object"):
            owner.set_physics_type(value)
            return
        if name == "mass" and owner._kind in ("robot", "object"):
            owner.set_mass(value)
            return
        super().__setattr__(name, value)

    def _record(self, key: str, shown: str, value: Any, reason: str | None = None) -> None:
        self._session.morse_only(self._owner, key, value, reason or self._reason, shown=shown)


def _variable(node) -> str:
    return node.basename or type(node).__name__.lower()
