"""MORSE's `morse.core.object.Object`, the base of MORSE's sensors and actuators, as an adapter onto morsec's
component contract (`morsec.component.Device`): a MORSE component class IS a morsec component class, which the
catalogue lists, the compiler places and the runtime ticks like any other; only the way it is declared and built
is MORSE's.

When the class is created, its `add_data` / `add_property` / `add_level` tables become morsec's declarations
(`data`, the `Properties` model, `levels`), its `_short_desc` the `short_descr`; its services are already marked
by morse.core.services' decorators. When the runtime builds it (`cls(context)`), MORSE's `__init__(obj, parent)`
runs with the component's game object and its robot (morse.core.emulation), and morse's Object.__init__ gives
it what MORSE's did: `bge_object`, `robot_parent`, `position_3d`, `local_data` at its level, each property under
its Python name, `frequency`. Before each `default_action`, `position_3d` and the robot's are brought up to the
frame, as MORSE's `action` did.
"""

from __future__ import annotations

import copy
import functools
import os
import traceback
from collections import OrderedDict
from typing import Any, Optional

from pydantic import Field, create_model

from morse.core import status
from morse.core.emulation import CallableName, user_location, world_of
from morse.helpers.transformation import Transformation3d
from morsec.component.contract import DataField, Device, Level
from morsec.component.properties import ComponentProperties
from morsec.errors import MorsecError, RuntimeFailure

__all__ = ["Object"]

# MORSE's data field types (documentation only, in MORSE) -> morsec's vocabulary (morsec.component.fields)
_FIELD_TYPES = {"float": "float", "double": "float", "int": "int", "integer": "int", "bool": "bool",
                "boolean": "bool", "str": "str", "string": "str", "vec3": "vec3", "vec3<float>": "vec3",
                "vec4": "vec4", "vec4<float>": "vec4", "quaternion": "vec4", "mat3": "mat3", "mat3<float>": "mat3",
                "dict": "dict", "list(float)": "list[float]", "list<float>": "list[float]"}
_PROPERTY_TYPES = {"float": float, "double": float, "int": int, "integer": int, "bool": bool, "boolean": bool,
                   "str": str, "string": str}


def field_type(declared: str, default: Any) -> str:
    """morsec's type of a MORSE data field: its declared type, else what its default is."""
    known = _FIELD_TYPES.get(str(declared).strip().lower().replace(" ", ""))
    if known:
        return known
    if isinstance(default, bool):
        return "bool"
    if isinstance(default, int):
        return "int"
    if isinstance(default, float):
        return "float"
    if isinstance(default, str):
        return "str"
    if isinstance(default, dict):
        return "dict"
    if isinstance(default, (list, tuple)):
        if default and all(isinstance(v, dict) for v in default):
            return "list[dict]"
        if default and all(isinstance(v, (list, tuple)) and len(v) == 3 for v in default):
            return "list[vec3]"
        return "list[float]"
    return "dict"


def _merged(cls, table: str) -> OrderedDict:
    out: OrderedDict = OrderedDict()
    for klass in reversed(cls.__mro__):
        out.update(vars(klass).get(table, {}))
    return out


def _level_ref(classpath, cls) -> str | None:
    """A level's class as morsec's Level names it: a class of the same module by its name, else its path."""
    if not classpath:
        return None
    module, _, name = str(classpath).rpartition(".")
    return name if module == cls.__module__ else str(classpath)


def _properties_model(cls) -> tuple[type[ComponentProperties], dict[str, tuple[str, Any]]]:
    """The Properties model of MORSE's properties of basic types (what a builder script sets), and every
    property's (python name, default)."""
    fields: dict[str, Any] = {}
    python_names = {}
    for name, (default, declared, doc, python_name) in _merged(cls, "_properties").items():
        python_names[name] = (python_name, default)
        declared_kind = _PROPERTY_TYPES.get(str(declared).strip().lower())
        kind = None
        if default is None:
            kind = declared_kind
        elif isinstance(default, (bool, int, float, str)):
            # the declared type when the default is one (Range: sys.maxsize, 'float'), else the default's
            kind = declared_kind if declared_kind is float and type(default) is int else type(default)
        if kind is None or name.startswith("_") or not name.isidentifier():
            continue  # a list, a dict ...: MORSE's game properties could not hold it either; the default stays
        fields[name] = (Optional[kind] if default is None else kind,  # noqa: UP045 (pydantic's annotation)
                        Field(default, description=str(doc) if doc else None))
    model = create_model(f"{cls.__name__}Properties", __base__=ComponentProperties,
                         __module__=cls.__module__, **fields)
    return model, python_names


def _ticking(action):
    """default_action, after bringing `position_3d` and the robot's up to this frame (MORSE's action did); an
    exception of the component's own names its file and line."""

    @functools.wraps(action)
    def default_action(self):
        world = self._morse_world
        if world.current is self:  # a subclass's default_action calling its parent's
            return action(self)
        if not self._active:
            return None
        world_of(world.sim)
        previous, world.current = world.current, self
        try:
            self.position_3d.update(self.bge_object)
            parent = self.robot_parent
            if parent is not None:
                parent.position_3d.update(parent.bge_object)
            return action(self)
        except MorsecError:
            raise
        except Exception as err:
            raise ComponentError(_located(err)) from None
        finally:
            world.current = previous

    default_action._morse_ticking = True
    return default_action


class ComponentError(Exception):
    """An exception raised by a MORSE component's own code, with its file and line (the runtime logs it once
    and the simulation goes on, as MORSE's game loop did)."""


def _located(err: BaseException) -> str:
    """`file:line: Type: message` of an exception, at the innermost frame of the component's own code."""
    frames = [f for f in traceback.extract_tb(err.__traceback__) if not _own(f.filename)]
    where = f"{frames[-1].filename}:{frames[-1].lineno}: " if frames else ""
    text = str(err).strip().splitlines()
    return f"{where}{type(err).__name__}" + (f": {text[0]}" if text else "")


def _own(filename: str) -> bool:
    from morse.core.emulation import _OWN_CODE
    return os.path.abspath(filename).startswith(_OWN_CODE)


class _MorseComponent(type):
    """Builds a MORSE component from morsec's context: `cls(context)` runs MORSE's `__init__(obj, parent)`."""

    def __call__(cls, *args, **kwargs):
        context = args[0] if len(args) == 1 and not kwargs else None
        if context is None or not hasattr(context, "sim") or not hasattr(context, "fqn"):
            if args or kwargs:
                raise RuntimeFailure(f"{user_location()}: {cls.__name__}(...): a MORSE component is built by the "
                                     "simulation from its builder script, not by hand")
            instance = cls.__new__(cls)
            Device.__init__(instance, None)  # declaration-only use (docs, schema)
            return instance
        instance = cls.__new__(cls)
        instance._morsec_context = context
        world = world_of(context.sim)
        instance._morse_world = world
        previous, world.current = world.current, instance
        try:
            instance.__init__(world.objects[context.fqn], world.robots.get(context.robot.name))
        except MorsecError:
            raise
        except Exception as err:
            raise RuntimeFailure(f"{_located(err)} (building {context.fqn})") from None
        finally:
            world.current = previous
        if not getattr(instance, "_morse_initialised", False):
            raise RuntimeFailure(f"{context.fqn}: {cls.__module__}.{cls.__name__}.__init__ did not call its base "
                                 "class's __init__(obj, parent)")
        return instance


class Object(Device, metaclass=_MorseComponent):
    """MORSE's base of components, over morsec's Device."""

    _morse_api = True  # a class written in MORSE's API (morsec.component.catalogue's classpath components)

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        data_fields = _merged(cls, "_data_fields")
        cls.data = tuple(
            DataField(name, default, field_type(declared, default), str(doc),
                      None if level == "all" else (tuple(level) if isinstance(level, (list, tuple)) else level))
            for name, (default, declared, doc, level) in data_fields.items() if name != "timestamp")
        cls.levels = tuple(Level(name, _level_ref(classpath, cls), str(doc), bool(default))
                           for name, (classpath, doc, default) in _merged(cls, "_levels").items())
        cls.Properties, cls._morse_properties = _properties_model(cls)
        if "_short_desc" in vars(cls):
            cls.short_descr = str(cls._short_desc)
        action = vars(cls).get("default_action")
        if action is not None and not getattr(action, "_morse_ticking", False):
            cls.default_action = _ticking(action)

    def __init__(self, obj, parent=None):
        context = self._morsec_context
        Device.__init__(self, context)
        self.name = CallableName(context.fqn)
        self.bge_object = obj
        self.robot_parent = parent
        self.level = context.level or "default"
        self._active = True
        self.del_functions: list = []
        if parent is not None:
            self.relative_position = obj.getVectTo(parent.bge_object)
        self.position_3d = Transformation3d(obj)
        self.update_properties()
        self._morse_initialised = True

    # ---- MORSE's Object
    def update_properties(self) -> None:
        """Each property under its Python name: the builder script's value, else the default."""
        for name, (python_name, default) in self._morse_properties.items():
            value = getattr(self.properties, name) if name in type(self.properties).model_fields \
                else copy.deepcopy(default)
            setattr(self, python_name, value)

    def fetch_properties(self) -> OrderedDict:
        return _merged(type(self), "_properties")

    def initialize_local_data(self) -> None:
        for field in self.fields_at(self.context.level):
            self.local_data[field.name] = copy.deepcopy(field.default)

    def set_property(self, prop_name: str, prop_val: Any) -> None:
        Device.set_property(self, prop_name, prop_val)
        self.update_properties()

    set_property._morsec_service = Device.set_property._morsec_service  # type: ignore[attr-defined]
    set_property.__doc__ = Device.set_property.__doc__

    @property
    def blender_obj(self):
        """MORSE 0.x's name of bge_object."""
        return self.bge_object

    @property
    def _frequency(self) -> float:
        return self.frequency

    def toggle_active(self) -> None:
        self._active = not self._active

    def in_zones(self, name=None, type=None):
        from morse.core.emulation import not_emulated
        not_emulated("Object.in_zones", "MORSE's zone manager")

    def action(self) -> None:
        self.default_action()

    def default_action(self) -> None:
        """Overridden by every MORSE component."""

    # ---- MORSE's AbstractObject: services
    @property
    def on_completion(self):
        """A callable ending the running asynchronous service ((status, result)), or None when none runs."""
        running = self.sim.requests.running.get(self.name) if self.context is not None else None
        return (lambda outcome: self.completed(*outcome)) if running else None

    @on_completion.setter
    def on_completion(self, value) -> None:
        pass  # morsec's request manager keeps the running requests

    def interrupt(self, cause=None) -> None:
        """A running asynchronous service is preempted (a new request, a cancel): MORSE's components override
        it to stop what the service started, then call this."""
        self.completed(status.PREEMPTED, [cause or "by incoming request"])

    def set_service_callback(self, cb) -> None:
        pass  # the request manager does it

    def register_services(self) -> None:
        pass  # the request manager serves the marked methods

    def print_data(self) -> None:
        import logging
        logging.getLogger("morse." + type(self).__module__).info("%s", dict(self.local_data))

    def finalize(self) -> None:
        self._active = False
