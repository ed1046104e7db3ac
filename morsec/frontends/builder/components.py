"""MORSE's builder classes, recording into the current session.

Every method only writes down what the script says, in the keys of the scene IR (`translate`,
`streams`, `properties` ...); the pipeline validates it all later and points errors at the script line
that wrote the value. A method MORSE has but morsec cannot honour (Blender materials, sub-objects of a
.blend) is accepted, recorded in `environment.morse_only` and warned about once.
"""

from __future__ import annotations

import copy
import os
from pathlib import Path
from typing import Any, ClassVar, get_args

from morsec.component.catalogue import camel_case, project_root
from morsec.errors import did_you_mean, one_of
from morsec.frontends.builder import session as _session
from morsec.frontends.builder.session import BuilderAttributeError, BuilderError
from morsec.middleware.refused import REFUSED, refusal
from morsec.modifiers.registry import MODIFIERS
from morsec.scene import models
from morsec.scene.naming import type_name

_PHYSICS_TYPES = {"STATIC": "static", "DYNAMIC": "dynamic", "RIGID_BODY": "rigid_body", "NO_COLLISION": "no_collision"}
_INTERNAL_PROPERTIES = ("Component_Tag", "Robot_Tag", "External_Robot_Tag", "Zone_Tag")


def middlewares() -> tuple[str, ...]:
    return tuple(get_args(models.Middleware))


def _plain(value: Any) -> Any:
    """numpy scalars and arrays, tuples -> plain Python values (what YAML would give)."""
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        return _plain(value.tolist())
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    return value


def _float(value: Any) -> Any:
    value = _plain(value)
    if isinstance(value, bool):
        return value
    try:
        return float(value)
    except (TypeError, ValueError):
        return value  # left for the pipeline to report, at this line


def _vector(value: Any) -> Any:
    value = _plain(value)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return [float(value)] * 3
    if isinstance(value, list):
        return [_float(v) for v in value]
    return value


class AbstractComponent:
    """Base of every builder object: name, transform, properties, children, middleware bindings."""

    _kind: ClassVar[str] = "component"  # robot, device, object, zone or environment
    _builder_node: ClassVar[bool] = True  # what the session recognises as a builder object (session.is_node)
    _type: ClassVar[str | None] = None  # the catalogue type this class places (generated classes set it)
    _classpath: ClassVar[str | None] = None

    def __init__(self, obj=None, filename="", category=""):
        self._start(register=True)
        if obj is not None:
            self._session.morse_only(self, "__init__", {"obj": repr(obj)},
                                     "wraps a Blender object; morsec has none")

    def _start(self, register: bool) -> None:
        session = _session.current()
        self._session = session
        self._raw: dict[str, Any] = {}
        self._where: dict[tuple, tuple] = {}
        self._children: list[AbstractComponent] = []
        self._parent: AbstractComponent | None = None
        self._explicit_name: str | None = None
        self._auto_name: str | None = None
        self._final_name: str | None = None
        self._type_name: str | None = type(self)._type
        self._position = session.position()
        if register:
            session.register(self)

    # ---- unknown methods: an error naming the script line (the runner adds file:line)

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        public = [n for n in dir(type(self)) if not n.startswith("_")]
        kind = {"robot": "robot", "device": "component", "object": "passive object", "zone": "zone",
                "environment": "environment"}.get(self._kind, "builder object")
        raise BuilderAttributeError(f"{type(self).__name__} ({kind}) has no method or attribute {name!r}"
                                    f"{did_you_mean(name, public)}")

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name!r}>"

    # ---- recording helpers

    def _pos(self) -> tuple:
        _, line, col = self._session.position()
        return (line, col or 1) if line else None

    def _put(self, *path: Any, value: Any) -> None:
        node = self._raw
        for key in path[:-1]:
            node = node.setdefault(key, {})
        node[path[-1]] = value
        self._mark(*path)

    def _mark(self, *path: Any) -> None:
        pos = self._pos()
        if pos:
            self._where[tuple(path)] = pos

    def _append_to(self, key: str, value: Any, unique: bool = False) -> None:
        items = self._raw.setdefault(key, [])
        if unique and value in items:
            return
        items.append(value)
        self._mark(key, len(items) - 1)

    def _require(self, method: str, *kinds: str) -> None:
        if self._kind not in kinds:
            what = {"robot": "robots", "device": "sensors and actuators", "object": "passive objects",
                    "zone": "zones"}
            allowed = " and ".join(what.get(k, k) for k in kinds)
            raise self._session.error(f"{type(self).__name__}.{method}(): only for {allowed}")

    def _morse_only(self, call: str, value: Any = None, reason: str | None = None) -> None:
        self._session.morse_only(self, call, value if value is not None else {}, reason)

    # ---- names

    @property
    def basename(self) -> str | None:
        return self._explicit_name or self._auto_name

    @basename.setter
    def basename(self, value: str | None) -> None:
        self._auto_name = value

    @property
    def name(self) -> str:
        """The fully-qualified name once the Environment is created (robot.pose), else the base name."""
        if self._session.renamed:
            return self._fqn()
        return self.basename or self._default_label()

    @name.setter
    def name(self, value: str | None) -> None:
        if not value:
            return
        value = str(value)
        if "." in value:
            raise self._session.error(f"invalid name {value!r}: dots are not allowed (names are joined with "
                                      "'.' into fully-qualified names: robot.pose)")
        self._explicit_name = value
        self._mark("name")
        if self._session.renamed:
            self._session.assign_names()

    @staticmethod
    def close_context(level=1):
        """Name the objects created so far after the variables holding them (for loops, as in MORSE)."""
        session = _session.current()
        frame = session.caller_frame()
        if frame is not None:
            session.scan(frame)

    def _default_label(self) -> str:
        emitted = self._emit_type()
        return type_name(emitted) if emitted else type(self).__name__.lower()

    def _morse_default_name(self) -> str:
        """The name MORSE gives an object no variable names: its .blend object's (the builder class name)."""
        return type(self).__name__

    def _fqn(self) -> str:
        parts = []
        node: AbstractComponent | None = self
        while node is not None:
            parts.append(node._final_name or node.basename or node._default_label())
            node = node._parent
        return _session.join(*reversed(parts))

    def _label(self) -> str:
        return self._fqn()

    @property
    def parent(self):
        return self._parent

    @property
    def children(self) -> list:
        return list(self._children)

    # ---- transform

    def _vec(self, key: str) -> list:
        vec = self._raw.get(key)
        if not isinstance(vec, list):
            vec = [0.0, 0.0, 0.0]
            self._raw[key] = vec
        return vec

    def translate(self, x=0.0, y=0.0, z=0.0):
        """Add (x, y, z) to the position, in metres (additive, as MORSE)."""
        vec = self._vec("translate")
        for i, d in enumerate((x, y, z)):
            vec[i] = _float(vec[i] + _float(d))
        self._mark("translate")

    def rotate(self, x=0.0, y=0.0, z=0.0):
        """Add (x, y, z) to the XYZ Euler rotation, in radians (additive, as MORSE)."""
        vec = self._vec("rotate")
        for i, d in enumerate((x, y, z)):
            vec[i] = _float(vec[i] + _float(d))
        self._mark("rotate")

    @property
    def location(self) -> list:
        return list(self._raw.get("translate", [0.0, 0.0, 0.0]))

    @location.setter
    def location(self, xyz) -> None:
        self._put("translate", value=_vector(xyz))

    @property
    def rotation_euler(self) -> list:
        return list(self._raw.get("rotate", [0.0, 0.0, 0.0]))

    @rotation_euler.setter
    def rotation_euler(self, xyz) -> None:
        self._put("rotate", value=_vector(xyz))

    @property
    def scale(self) -> list:
        return [1.0, 1.0, 1.0]

    @scale.setter
    def scale(self, xyz) -> None:
        self._morse_only("scale", {"scale": _vector(xyz)}, "scales a Blender mesh; robots and components keep "
                         "their catalogue geometry")

    # ---- properties

    def properties(self, **kwargs):
        """Set properties (MORSE game properties): checked against the component's properties later."""
        for key, value in kwargs.items():
            if key in _INTERNAL_PROPERTIES:
                continue
            if self._kind == "device" and key == "classpath":
                self._type_name = self._type_from_classpath(value)
                continue
            if self._kind == "device" and key == "abstraction_level":
                self.level(value)
                continue
            if self._kind == "device" and key == "frequency":
                self.frequency(value)
                continue
            self._put("properties", key, value=_plain(value))

    def property_value(self, name: str):
        return self._raw.get("properties", {}).get(name)

    def _split_tags(self, out: dict, prefix: tuple, smap) -> None:
        """Robots and components: the properties their catalogue type does not declare are MORSE game
        properties other components may read (proximity's Track, collision's only_objects_with_property):
        kept as `tags`, with a warning at the line that set them (and the close matches)."""
        if self._kind not in ("robot", "device") or not isinstance(out.get("properties"), dict):
            return
        cls = self._catalogue_class(out.get("type"))
        if cls is None:
            return  # an unknown type: validation reports it
        declared = list(cls.Properties.model_fields)
        for key in [k for k in out["properties"] if k not in declared]:
            out.setdefault("tags", {})[key] = out["properties"].pop(key)
            for table in (smap.values, smap.keys):
                if prefix + ("properties", key) in table:
                    table[prefix + ("tags", key)] = table.pop(prefix + ("properties", key))
            line, col = self._where.get(("properties", key), (self._position[1], self._position[2]))
            script = str(self._session.script) if self._session.script else None
            label = self.basename or self._default_label()
            self._session.warn(
                f"tag:{id(self)}:{key}",
                f"{label}.properties({key}=...): {cls.kind} type {cls.id!r} has no property {key!r}; kept as "
                f"a tag, a game property other components can read (`tags:` in a YAML scene)"
                f"{did_you_mean(key, declared)}", (script, line, col))
        if not out["properties"]:
            del out["properties"]

    def _catalogue_class(self, type_name):
        cat = self._session.catalogue
        if not isinstance(type_name, str):
            return None
        if self._kind == "robot":
            rid = cat.resolve("robots", type_name)
            return cat.by_kind["robots"][rid] if rid else None
        cid = cat.resolve("sensors", type_name) or cat.resolve("actuators", type_name)
        return cat.devices()[cid] if cid else None

    # ---- the Blender object behind (obj._bpy_object): see blender.py

    @property
    def _bpy_object(self):
        from morsec.frontends.builder.blender import BlenderObject
        return BlenderObject(self)

    def _locks(self) -> list[str]:
        return list(self._raw.get("locks", []))

    def _lock(self, axis: str, locked: bool) -> None:
        """Blender's game.lock_<axis> flag (robots and passive objects): `locks` in the scene."""
        locks = [a for a in self._raw.get("locks", []) if a != axis] + ([axis] if locked else [])
        from morsec.frontends.builder.blender import LOCKS
        self._put("locks", value=[a for a in LOCKS if a in locks])

    # ---- children

    def append(self, obj, child=None, level=1):
        """Attach a sensor or actuator to this robot (or to another component)."""
        if not isinstance(obj, AbstractComponent):
            raise self._session.error(f"{type(self).__name__}.append(): expected a sensor or an actuator, "
                                      f"got {obj!r}")
        if self._kind not in ("robot", "device"):
            raise self._session.error(f"{type(self).__name__}.append(): components attach to robots and to "
                                      "other components only")
        if obj._kind != "device":
            raise self._session.error(f"{type(self).__name__}.append({type(obj).__name__}): only sensors and "
                                      "actuators can be appended (robots, objects and zones are placed in the world)")
        node: AbstractComponent | None = self
        while node is not None:
            if node is obj:
                raise self._session.error(f"{type(self).__name__}.append(): cannot append a component to itself "
                                          "or to one of its own children")
            node = node._parent
        if child is not None:
            self._morse_only("append", {"child": child}, "attaches to a named sub-object of a Blender model; "
                             "the component is attached to the robot itself")
        if obj._parent is not None:
            obj._parent._children.remove(obj)
        obj._parent = self
        self._children.append(obj)
        self._session.name_from(self._session.caller_frame(), obj)

    def get_child(self, name, objects=None, recursive=True):
        self._morse_only("get_child", {"name": name}, "looks up Blender sub-objects; there are none")
        return None

    # ---- sensors and actuators: middleware, modifiers, levels, frequency

    def _middleware_of(self, binding, method: str) -> tuple[str, dict]:
        """A middleware name, or a full binding [classpath, method, path] -> (middleware, binding fields)."""
        if isinstance(binding, (list, tuple)):
            parts = [str(p) for p in binding]
            if not parts:
                raise self._session.error(f"{method}([]): give a middleware name or [classpath, method, path]")
            classpath = parts[0]
            for mw in middlewares():
                if mw in classpath.lower():
                    fields = {"classpath": classpath}
                    if len(parts) > 1:
                        fields["method"] = parts[1]
                    if len(parts) > 2:
                        fields["path"] = parts[2]
                    return mw, fields
            for module in classpath.lower().split("."):  # MORSE's yarp_datastream, moos ...: why not, and instead
                refused = next((refusal(name) for name in REFUSED if module.startswith(name)), None)
                if refused:
                    raise self._session.error(f"{method}({parts!r}): {refused}")
            raise self._session.error(f"{method}({parts!r}): no morsec middleware for classpath {classpath!r}; "
                                      f"available middlewares: {one_of(middlewares())}")
        return binding, {}

    def add_stream(self, datastream, method=None, path=None, classpath=None, direction=None, **kwargs):
        """Stream the component's data through a middleware ('socket', 'text', or a full binding)."""
        self._add_stream("add_stream", datastream, method, path, classpath, direction, **kwargs)

    def _add_stream(self, call, datastream, method=None, path=None, classpath=None, direction=None, **kwargs):
        self._require(call, "device")
        middleware, fields = self._middleware_of(datastream, call)
        entry: dict[str, Any] = {"middleware": middleware, **fields}
        for key, value in (("method", method), ("path", path), ("classpath", classpath), ("direction", direction)):
            if value is not None:
                entry[key] = value
        entry.update({k: _plain(v) for k, v in kwargs.items() if v is not None})
        self._append_to("streams", middleware if len(entry) == 1 else entry)

    def configure_mw(self, datastream, method=None, path=None, component=None):
        """Deprecated MORSE name of add_stream; also takes a full binding [classpath, method, path]."""
        self._require("configure_mw", "device")
        if component is not None:
            self._morse_only("configure_mw", {"component": component},
                             "(component=...) borrows another component's serializer; morsec has one per component")
        self._add_stream("configure_mw", datastream, method, path)

    def add_service(self, interface, component=None, config=None):
        """Expose the component's services through a middleware ('socket')."""
        self._require("add_service", "device")
        middleware, _ = self._middleware_of(interface, "add_service")
        if component is not None or config is not None:
            self._morse_only("add_service", {"component": component, "config": config},
                             "(component=, config=) selects MORSE request-manager classes")
        self._append_to("services", middleware, unique=True)

    def configure_service(self, interface, component=None, config=None):
        """Deprecated MORSE name of add_service."""
        self.add_service(interface, component, config)

    def add_interface(self, interface, **kwargs):
        """add_service + add_stream on one middleware."""
        self._require("add_interface", "device")
        middleware, fields = self._middleware_of(interface, "add_interface")
        self._append_to("interfaces", middleware, unique=True)
        extra = {k: _plain(v) for k, v in kwargs.items() if v is not None}
        if extra or fields:
            self._append_to("streams", {"middleware": middleware, **fields, **extra})

    def _modifier_from_classpath(self, classpath: str) -> str:
        parts = str(classpath).split(".")
        module = parts[-2] if len(parts) > 1 else parts[0]
        # MORSE's modules in `morse.modifiers` are the registry's names with underscores: pose_noise -> posenoise
        if module.replace("_", "") in MODIFIERS:
            return module.replace("_", "")
        if "noise" in parts[-1].lower():
            return "noise"
        raise self._session.error(f"alter(classpath={classpath!r}): no morsec modifier for this class; "
                                  f"modifiers: {one_of(MODIFIERS)}")

    def alter(self, modifier_name=None, classpath=None, direction=None, **kwargs):
        """Add a modifier (Noise, NED, UTM, ...) with its parameters."""
        self._require("alter", "device")
        name = modifier_name or (self._modifier_from_classpath(classpath) if classpath else None)
        if not name:
            raise self._session.error("alter(): give a modifier name, e.g. alter('Noise', pos_std=0.1)")
        entry = {"name": name}
        entry.update({k: _plain(v) for k, v in kwargs.items() if v is not None})
        self._append_to("modifiers", entry)

    def configure_modifier(self, mod, config=None, **kwargs):
        """Deprecated MORSE name of alter; `mod` is a modifier name or [classpath, method]."""
        if isinstance(mod, (list, tuple)):
            self.alter(classpath=mod[0] if mod else None, **kwargs)
        else:
            self.alter(mod, **kwargs)

    def add_overlay(self, datastream, overlay, config=None, **kwargs):
        """Expose the component's services reshaped by an overlay class, for one middleware."""
        self._require("add_overlay", "device")
        middleware, _ = self._middleware_of(datastream, "add_overlay")
        entry = {"middleware": middleware, "overlay": overlay}
        entry.update({k: _plain(v) for k, v in kwargs.items() if v is not None})
        self._append_to("overlays", entry)

    def configure_overlay(self, datastream, overlay, config=None, **kwargs):
        """Deprecated MORSE name of add_overlay."""
        self.add_overlay(datastream, overlay, config, **kwargs)

    def level(self, level):
        """Select the component's level of realism (e.g. Odometry: raw, differential, integrated)."""
        self._require("level", "device")
        self._put("level", value=level)

    def frequency(self, frequency=None):
        """Ticks per simulated second."""
        self._require("frequency", "device")
        if frequency is not None:
            self._put("frequency", value=_float(frequency))

    def profile(self):
        """Report the time spent in this component."""
        self._require("profile", "device")
        self._put("profile", value=True)

    def set_color(self, r=0.1, g=0.1, b=0.1, a=None):
        """RGB colour in 0..1 (a: optional alpha, a morsec extension)."""
        self._require("set_color", "robot", "device", "object")
        self._put("color", value=[_float(v) for v in ((r, g, b) if a is None else (r, g, b, a))])

    # ---- MORSE's Blender plumbing: accepted, recorded

    def morseable(self, calling_module=None):
        return None

    def is_morseable(self) -> bool:
        return self._kind in ("robot", "device")

    def select(self):
        return None

    def is_exportable(self) -> bool:
        return True

    def mark_unexportable(self):
        self._morse_only("mark_unexportable", {}, "is decided by the component's catalogue entry (exportable)")

    def append_meshes(self, objects=None, component=None, prefix=None):
        self._morse_only("append_meshes", {"objects": objects, "component": component, "prefix": prefix},
                         "imports meshes from a .blend file")
        return []

    def append_scenes(self, *args, **kwargs):
        self._morse_only("append_scenes", kwargs, "imports scenes from a .blend file")
        return []

    def append_collada(self, component=None):
        self._morse_only("append_collada", {"component": component}, "imports a Collada mesh")
        return []

    def create_laser_arc(self):
        """MORSE's laser scanners: draw the scan arc as a Blender mesh (accepted, recorded)."""
        self._morse_only("create_laser_arc", {}, "draws the scan arc as a Blender mesh")
        return None

    # ---- the catalogue

    def _catalogue_kinds(self) -> tuple[str, ...]:
        return {"robot": ("robots",), "device": ("sensors", "actuators"), "object": ("props",)}.get(self._kind, ())

    def _lookup(self, name: str) -> str | None:
        cat = self._session.catalogue
        text = str(name)
        candidates = [text]
        base = text[:-6] if text.endswith(".blend") else text
        stem = base.replace("\\", "/").rstrip("/").rsplit("/", 1)[-1]
        candidates += [base, stem, stem.lower(), camel_case(stem)]
        for kind in self._catalogue_kinds():
            for candidate in candidates:
                found = cat.resolve(kind, candidate)
                if found:  # an object of a props file is named by its own name: it says which
                    return candidate if kind == "props" and cat.variant(candidate) is not None else found
        return None

    def _emit_type(self) -> str | None:
        if self._type_name is None:
            return None
        return self._lookup(self._type_name) or self._type_name

    def _type_from_classpath(self, classpath) -> str:
        cat = self._session.catalogue
        text = str(classpath or "")
        kinds = self._catalogue_kinds()
        if not text:
            raise self._session.error(f"{type(self).__name__}: set _classpath to the component it places, "
                                      "e.g. _classpath = 'morse.sensors.pose.Pose'")
        ref = text.split(":", 1)[0]
        if "/" in ref:
            kind, _, cid = ref.partition("/")
            if kind in kinds and cat.resolve(kind, cid):
                return cat.resolve(kind, cid)
        if "." in text and not text.startswith("morse."):  # a class of the simulation's own (src/<sim>/...)
            found = cat.classpath(kinds, text)
            if found:
                return found
        parts = text.split(".")
        class_name = parts[-1]
        module = parts[-2] if len(parts) > 1 else None
        for kind in kinds:
            found = cat.resolve(kind, class_name)
            if found:
                return found
            for cid, cls in sorted(cat.by_kind.get(kind, {}).items()):
                if cls.__name__ == class_name:
                    return cid
            if module and cat.resolve(kind, module):
                return cat.resolve(kind, module)
        names = sorted({n for kind in kinds for n in cat.names(kind)})
        raise self._session.error(
            f"{type(self).__name__}: _classpath {text!r} names no component of the catalogue"
            f"{did_you_mean(class_name, names)} "
            "(a class of your own is found by its path from the MORSE simulation's src/ folder, "
            "e.g. 'mysim.sensors.thermo.Thermo', or written as a component folder: see docs/coming-from-morse.md)")

    # ---- emission

    def _emit_fields(self) -> dict:
        return copy.deepcopy(self._raw)

    def _emit(self, prefix: tuple, smap) -> dict:
        if self._position[1]:
            pos = (self._position[1], self._position[2] or 1)
            smap.values[prefix] = pos
            smap.keys[prefix] = pos
        out: dict[str, Any] = {}
        if self._final_name:
            out["name"] = self._final_name
        kind_type = self._emit_type()
        if kind_type is not None:
            out["type"] = kind_type
        out.update(self._emit_fields())
        for path, pos in self._where.items():
            smap.values[prefix + path] = pos
            smap.keys[prefix + path] = pos
        self._split_tags(out, prefix, smap)
        if self._children:
            out["components"] = [child._emit(prefix + ("components", i), smap)
                                 for i, child in enumerate(self._children)]
        return out


# ---------------------------------------------------------------- components (sensors and actuators)

class Component(AbstractComponent):
    """A catalogue component by category and name: Component('sensors', 'pose')."""

    def __init__(self, category="", filename="", blender_object_name=None, make_morseable=True):
        kind = {"robots": "robot", "sensors": "device", "actuators": "device", "props": "object"}.get(category)
        if kind is None:
            self._kind = "device"
            self._start(register=True)
            raise self._session.error(f"Component({category!r}, {filename!r}): category must be one of "
                                      f"{one_of(['robots', 'sensors', 'actuators', 'props'])}")
        self._kind = kind
        self._start(register=True)
        self._type_name = str(filename)
        if blender_object_name:
            self._morse_only("__init__", {"blender_object_name": blender_object_name},
                             "(blender_object_name=) picks an object inside a .blend file")


class ComponentCreator(AbstractComponent):
    """Base of sensors and actuators: a catalogue component, or a custom one named by `_classpath`."""

    _kind = "device"
    APPEND_EMPTY = 0
    USE_BLEND = 1
    LINK_EXISTING_OBJECT = 2
    LINK_EXISTING_BLEND = 2

    def __init__(self, cname=None, category="sensors", filename=None, action=0, make_morseable=True):
        self._start(register=True)
        self._type_name = self._own_type()
        if cname:
            self.name = cname

    def _own_type(self) -> str:
        """The most derived of `_type` (catalogue classes) and `_classpath` (custom components)."""
        for klass in type(self).__mro__:
            own = vars(klass)
            if own.get("_type"):
                return own["_type"]
            if own.get("_classpath"):
                return self._type_from_classpath(own["_classpath"])
        return self._type_from_classpath(None)


class SensorCreator(ComponentCreator):
    """Base of every sensor class; subclass it with `_classpath` for a custom sensor."""

    def __init__(self, name=None, action=ComponentCreator.APPEND_EMPTY, make_morseable=True, *args, **kwargs):
        if isinstance(action, str) and "." in action and not getattr(type(self), "_classpath", None):
            type(self)._classpath = action  # MORSE 1.0: SensorCreator(name, classpath, ...)
        ComponentCreator.__init__(self, name, "sensors")


class ActuatorCreator(ComponentCreator):
    """Base of every actuator class; subclass it with `_classpath` for a custom actuator."""

    def __init__(self, name=None, action=ComponentCreator.APPEND_EMPTY, blendfile=None, blendobject=None,
                 make_morseable=True, *args, **kwargs):
        if isinstance(action, str) and "." in action and not getattr(type(self), "_classpath", None):
            type(self)._classpath = action
        ComponentCreator.__init__(self, name, "actuators")


class Sensor(AbstractComponent):
    """A catalogue sensor by name: Sensor('pose') (MORSE's older API)."""

    _kind = "device"

    def __init__(self, filename="", name=None):
        self._start(register=True)
        self._type_name = str(filename)
        if name:
            self.name = name


class Actuator(Sensor):
    """A catalogue actuator by name: Actuator('motion_vw') (MORSE's older API)."""


# ---------------------------------------------------------------- robots

class Robot(AbstractComponent):
    """A robot of the catalogue; Robot('atrv') or a catalogue class (ATRV())."""

    _kind = "robot"

    def __init__(self, filename="", name=None, blender_object_name=None):
        self._start(register=True)
        if self._type_name is None:
            if not filename:
                raise self._session.error("Robot(): name the robot model, e.g. Robot('atrv'), or use its class "
                                          "(ATRV(), ...)")
            self._type_name = str(filename)
        if blender_object_name:
            self._morse_only("__init__", {"blender_object_name": blender_object_name},
                             "(blender_object_name=) picks an object inside a .blend file")
        if name:
            self.name = name

    # ---- the catalogue robot's own components (MORSE builder robots that append theirs in __init__)

    def _add_default_components(self, without: tuple[str, ...] = ()) -> None:
        """The robot type's `default_components` (BasePR2's torso, head ...) but those named in `without`, as
        children, each an attribute of the robot by its name (nested ones `<parent>_<name>`: MORSE's
        `pr2.torso_pose`, unless the entry names its `attribute`: the Human's `human.joint_states`)."""
        cls = self._catalogue_class(self._type_name)
        for spec in getattr(cls, "default_components", ()) if cls else ():
            if spec["name"] not in without:
                self._default_child(self, spec, "")

    def _default_child(self, parent: AbstractComponent, spec: dict, prefix: str) -> None:
        child = Sensor(spec["type"])  # a catalogue sensor or actuator by id
        child.name = spec["name"]
        if spec.get("translate"):
            child.translate(*spec["translate"])
        if spec.get("rotate"):
            child.rotate(*spec["rotate"])
        if spec.get("properties"):
            child.properties(**spec["properties"])
        for middleware in spec.get("streams", ()):
            child.add_stream(middleware)
        for middleware in spec.get("services", ()):
            child.add_service(middleware)
        parent.append(child)
        attribute = spec.get("attribute") or f"{prefix}{spec['name']}"
        if not hasattr(type(self), attribute):
            setattr(self, attribute, child)
        for sub in spec.get("components", ()):
            self._default_child(child, sub, f"{attribute}_")

    def _builder_interface(self, middleware: str | None = None) -> dict:
        """The robot type's own interface for `middleware` (its "*" entry for others); {} if it has none."""
        cls = self._catalogue_class(self._type_name)
        table = getattr(cls, "builder_interface", {}) if cls else {}
        return table.get(middleware, table.get("*", {})) if middleware is not None else table

    def add_interface(self, interface, **kwargs):
        """On a robot type that defines it (BasePR2): streams, services and overlays of its own components, as
        MORSE's builder class did; on others, an error (interfaces are set on sensors and actuators)."""
        if not self._builder_interface():
            return super().add_interface(interface, **kwargs)
        middleware, _ = self._middleware_of(interface, "add_interface")
        table = self._builder_interface(middleware)

        def named_after_robot(component, key: str) -> None:
            """The robot's name is known when the scene is emitted: "{robot}" is filled in then."""
            entry = component._raw[key][-1]
            if isinstance(entry, dict):
                self.__dict__.setdefault("_named_after_robot", [])
                self._named_after_robot += [(entry, k, v) for k, v in entry.items()
                                            if isinstance(v, str) and "{robot}" in v]

        for entry in table.get("streams", ()):
            name, options = (entry, {}) if isinstance(entry, str) else entry
            if (component := self._descendant(name)) is not None:
                component.add_stream(interface, **{**options, **kwargs})
                named_after_robot(component, "streams")
        for name in table.get("services", ()):
            if (component := self._descendant(name)) is not None:
                component.add_service(interface)
        for name, overlay, options in table.get("overlays", ()):
            if (component := self._descendant(name)) is not None:
                component.add_overlay(interface, overlay, **options)
                named_after_robot(component, "overlays")

    def _descendant(self, path: str) -> AbstractComponent | None:
        """A component of this robot by its builder attribute (`torso_pose`) or its name relative to it
        (`skeleton.joint_states`), or None."""
        found = getattr(self, path, None) if "." not in path else None
        if isinstance(found, AbstractComponent) and found._parent is not None:
            return found
        node: AbstractComponent = self
        for part in path.split("."):
            node = next((c for c in node._children if c.basename == part), None)
            if node is None:
                return None
        return node

    def add_stream(self, datastream, method=None, path=None, classpath=None, direction=None, **kwargs):
        """On a robot type with its own interface (BasePR2): as add_interface (MORSE's did nothing; old
        PR2 scripts stream it this way)."""
        if self._builder_interface() and method is None and path is None and classpath is None:
            return self.add_interface(datastream, **kwargs)
        return super().add_stream(datastream, method, path, classpath, direction, **kwargs)

    def _emit(self, prefix: tuple, smap) -> dict:
        name = self._final_name or self.name
        for entry, key, template in self.__dict__.get("_named_after_robot", ()):
            entry[key] = template.replace("{robot}", name)
        return super()._emit(prefix, smap)

    def add_default_interface(self, stream):
        """Stream + service `stream` on every component of the robot that has none."""
        middleware, _ = self._middleware_of(stream, "add_default_interface")
        self._put("default_interface", value=middleware)

    def set_mass(self, mass):
        """Total mass of the robot, kg."""
        self._put("mass", value=_float(mass))

    def set_friction(self, friction=0.0):
        """Sliding friction coefficient of the robot's geoms."""
        self._put("friction", value=_float(friction))

    def make_ghost(self, alpha=0.3):
        """Transparent, with no collision."""
        self._put("ghost", value=_float(alpha))

    def set_no_collision(self):
        self._put("collision", value=False)

    def set_physics_type(self, physics_type="STATIC"):
        """STATIC, DYNAMIC, RIGID_BODY or NO_COLLISION."""
        text = str(physics_type)
        self._put("physics_type", value=_PHYSICS_TYPES.get(text.upper(), text.lower()))

    def set_rigid_body(self):
        self._put("physics_type", value="rigid_body")

    def set_dynamic(self):
        self._put("physics_type", value="dynamic")

    def make_external(self):
        self._morse_only("make_external", {}, "is decided per node by configure_multinode's distribution")

    def set_use_record_animation(self, record=True):
        self._morse_only("set_use_record_animation", {"record": record}, "records a Blender animation")

    def set_collision_bounds(self):
        self._morse_only("set_collision_bounds", {}, "sets Bullet collision bounds; MuJoCo uses the robot's "
                         "collision geometry")

    def make_grasper(self, obj_name=None):
        self._morse_only("make_grasper", {"obj_name": obj_name}, "adds a Blender NEAR sensor")

    def unparent_wheels(self):
        return None

    def after_renaming(self):
        return None


class GroundRobot(Robot):
    """A robot that stays on the ground (property GroundRobot=True)."""

    def __init__(self, filename="", name=None, blender_object_name=None):
        Robot.__init__(self, filename, name, blender_object_name)
        self.properties(GroundRobot=True)


class WheeledRobot(Robot):
    """A robot with wheels (MORSE's wheel-name properties come from the catalogue's description)."""


class CatalogueRobot(Robot):
    """Base of the catalogue's robot classes (ATRV(), BasePR2() ...): MORSE's `ATRV(name=None)`, with the robot
    type's own components. A type whose MORSE class took more arguments (NavPR2(with_keyboard=False)) has a
    `builder_mixin` with that __init__, which calls this one; `_without` names default components left out."""

    def __init__(self, name=None, debug=True, *, _without: tuple[str, ...] = ()):
        Robot.__init__(self, "", name)
        self._add_default_components(_without)
        if _without:
            self._put("without", value=list(_without))


class FakeRobot(Robot):
    """A robot with no body, to hold sensors that are not on a robot (catalogue type FakeRobot)."""

    _type = "FakeRobot"

    def __init__(self, name=None):
        Robot.__init__(self, "", name)


# ---------------------------------------------------------------- passive objects

def _default_object_size() -> list[float]:
    return list(models.ObjectSpec.model_fields["size"].default_factory())


class _Object(AbstractComponent):
    _kind = "object"
    _unit_mesh: ClassVar[bool] = False  # True: a Blender primitive, 2 m wide at scale 1 (±1)

    def _base_size(self) -> list[float]:
        """The full size at scale 1: 2 m for a Blender primitive, else the catalogue prop's default."""
        return [2.0, 2.0, 2.0] if self._unit_mesh else _default_object_size()

    def _start(self, register: bool) -> None:
        super()._start(register)
        self._scale: list | None = None

    @property
    def scale(self) -> list:
        return list(self._scale) if self._scale is not None else [1.0, 1.0, 1.0]

    @scale.setter
    def scale(self, xyz) -> None:
        """MORSE's Blender scale: a basic mesh is ±1, so its full size is 2 * scale."""
        self._raw.pop("size", None)
        self._scale = _vector(xyz)
        self._mark("size")

    @property
    def size(self) -> list:
        """Full extent along x, y, z, m (morsec's `size`)."""
        if "size" in self._raw:
            return list(self._raw["size"])
        return [b * s for b, s in zip(self._base_size(), self.scale)]

    @size.setter
    def size(self, xyz) -> None:
        self._scale = None
        self._put("size", value=_vector(xyz))

    def color(self, r=0.1, g=0.1, b=0.1):
        """MORSE Mesh.color(r, g, b)."""
        self._put("color", value=[_float(r), _float(g), _float(b)])

    def set_mass(self, mass):
        """Mass, kg (for dynamic objects)."""
        self._put("mass", value=_float(mass))

    def set_dynamic(self):
        """The object moves under physics (morsec objects are static unless told)."""
        self._put("dynamic", value=True)

    def set_static(self):
        self._put("dynamic", value=False)

    def set_physics_type(self, physics_type="STATIC"):
        self._put("dynamic", value=str(physics_type).upper() in ("DYNAMIC", "RIGID_BODY"))

    def setgraspable(self):
        """Object=True, Graspable=True and Label=<name> (unless a Label is set)."""
        self.properties(Object=True, Graspable=True)
        self._graspable = True

    def _emit_fields(self) -> dict:
        out = copy.deepcopy(self._raw)
        if self._scale is not None:
            if isinstance(self._scale, list):
                out["size"] = [b * s if isinstance(s, (int, float)) else s
                               for b, s in zip(self._base_size(), self._scale)] + self._scale[3:]
            else:
                out["size"] = self._scale
        elif self._unit_mesh and "size" not in out:
            out["size"] = [2.0, 2.0, 2.0]
        if getattr(self, "_graspable", False):
            out.setdefault("properties", {}).setdefault("Label", self._final_name or self._default_label())
        return out


class Mesh(_Object):
    """A Blender primitive: a basic shape, ±1 at scale 1 (so 2 m wide), as MORSE's blenderobjects."""

    _unit_mesh = True

    def __init__(self, name=None):
        self._start(register=True)
        if name:
            self.name = name


class Cube(Mesh):
    _type = "Cube"


class Cylinder(Mesh):
    _type = "Cylinder"


class Sphere(Mesh):
    _type = "Sphere"


class IcoSphere(Mesh):
    _type = "IcoSphere"


class Cone(Mesh):
    _type = "Cone"


class Torus(Mesh):
    _type = "Torus"


class Plane(Mesh):
    _type = "Plane"


class EnvironmentObject(_Object):
    """An object of the environment's own (indoors-1/boxes' RedBox) that the script reached with
    `bpymorse.get_object(name)`: the environment's definition, written in the scene under its name (which
    replaces the environment's), so what the script sets on it (`bpymorse.properties(box, Type='Box')`)
    applies to it."""

    def __init__(self, definition: dict):
        self._start(register=True)
        definition = copy.deepcopy(definition)
        self._type_name = definition.pop("type")
        self.name = definition.pop("name")
        self._raw.update(definition)


class CatalogueProp(_Object):
    """A catalogue prop by its builder name (generated per catalogue)."""

    def __init__(self, name=None):
        self._start(register=True)
        if name:
            self.name = name


class PassiveObject(_Object):
    """MORSE's PassiveObject(filename, prefix, keep_pose): an object of a .blend file. Here a catalogue prop
    named by `prefix` (or the file's stem), or an object of a catalogue environment
    (`PassiveObject('environments/indoors-1/boxes', 'GreenBox')`), taken out of it with its shape, colour
    and properties; placed at the origin (as MORSE resets the pose) unless `keep_pose`."""

    def __init__(self, filename="props/objects", prefix=None, keep_pose=False):
        self._start(register=True)
        self._own_size: list | None = None  # the object's size at scale 1
        self._blend_object = str(prefix) if prefix else Path(str(filename)).name.removesuffix(".blend")
        what = f"PassiveObject({filename!r}" + (f", {prefix!r})" if prefix else ")")
        if self._from_environment(str(filename), prefix, keep_pose, what):
            return
        cat = self._session.catalogue
        if prefix:  # the object of a props file morsec import-blend read (a project's, or $MORSE_ROOT's)
            stem = str(filename).replace("\\", "/").removesuffix(".blend").removeprefix("props/")
            found = cat.resolve("props", f"{stem}/{prefix}")
            if found:
                self._type_name = found
                self._own_size = cat.get("props", found).defaults.get("size")
                return
        self._not_a_prop(str(filename), prefix, what)
        for candidate in (prefix, filename):
            if candidate:
                found = self._lookup(candidate)
                if found:
                    held = self._session.catalogue.get("props", found).variants
                    if held and found not in held and prefix:
                        raise self._session.error(f"{what}: no catalogue prop by that name"
                                                  f"{did_you_mean(str(prefix), held)} (the objects of "
                                                  f"{found!r}: {', '.join(held)})")
                    if held and found not in held:
                        raise self._session.error(f"{what}: {found!r} holds several objects: name one "
                                                  f"({', '.join(held)})")
                    self._type_name = found
                    self._own_size = self._session.catalogue.prop_defaults(found).get("size")
                    return
        searched = asset_search_path(self._session.script)
        found_file = find_asset(str(filename), searched)
        props = ", ".join(cat.names("props"))
        if found_file:
            stem = Path(found_file).stem
            raise self._session.error(f"{what}: found {found_file}: import it first, `morsec import-blend "
                                      f"{found_file} --kind props`, then PassiveObject('props/{stem}', "
                                      f"'{prefix or '<object>'}') names its object")
        shown = ", ".join(str(p) for p in searched) or "(nothing)"
        wanted = str(prefix or self._blend_object)
        raise self._session.error(f"{what}: no catalogue prop by that name{did_you_mean(wanted, cat.names('props'))} "
                                  f"(props: {props}) and no asset file found; searched {shown} (add folders with "
                                  "MORSE_RESOURCE_PATH)")

    def _not_a_prop(self, filename: str, prefix, what: str) -> None:
        """MORSE's props/basics.blend holds its viewer's camera and head-up display, not objects to place."""
        if filename.replace("\\", "/").removesuffix(".blend").endswith("props/basics"):
            raise self._session.error(f"{what}: MORSE's props/basics holds its viewer's camera and head-up display "
                                      "(CameraFP, Screen, HUD_plane), not objects: morsec's viewers have their own")

    def _from_environment(self, filename: str, prefix, keep_pose: bool, what: str) -> bool:
        """`environments/<id>`: the object `prefix` of that catalogue environment (its `objects`)."""
        text = filename.replace("\\", "/").removesuffix(".blend")
        if not text.startswith("environments/"):
            return False
        cat = self._session.catalogue
        eid = cat.resolve("environments", text.removeprefix("environments/"))
        if eid is None:
            return False  # not a catalogue environment: maybe a file
        held = {o["name"]: o for o in cat.get("environments", eid).objects}
        if not prefix or str(prefix) not in held:
            names = ", ".join(held) or "none"
            raise self._session.error(f"{what}: environment {eid!r} has no object {str(prefix or '')!r}"
                                      f"{did_you_mean(str(prefix or ''), held)} (its objects: {names})")
        entry = copy.deepcopy(held[str(prefix)])
        self._type_name = entry.pop("type")
        self._own_size = entry.get("size")
        entry.pop("name", None)
        pose = {k: entry.pop(k) for k in ("translate", "rotate") if k in entry}
        if keep_pose:
            entry.update(pose)
        for key, value in entry.items():
            self._put(key, value=value)
        return True

    def _base_size(self) -> list[float]:
        return list(self._own_size) if self._own_size else super()._base_size()

    def _morse_default_name(self) -> str:
        return self._blend_object


def asset_search_path(script: Path | None) -> list[Path]:
    """$MORSE_RESOURCE_PATH, then the script's folder, then the project's folder and its data/ folder."""
    paths: list[Path] = []
    for item in os.environ.get("MORSE_RESOURCE_PATH", "").split(os.pathsep):
        if item:
            paths.append(Path(item))
    folder = Path(script).resolve().parent if script else Path.cwd()
    paths.append(folder)
    root = project_root(folder)
    if root is not None:
        paths += [root, root / "data"]
    unique: list[Path] = []
    for p in paths:
        if p not in unique:
            unique.append(p)
    return unique


def find_asset(filename: str, searched: list[Path]) -> Path | None:
    names = [filename] if filename.endswith(".blend") else [filename, filename + ".blend"]
    for name in names:
        path = Path(name)
        if path.is_absolute():
            if path.is_file():
                return path
            continue
        for folder in searched:
            if (folder / path).is_file():
                return folder / path
    return None


# ---------------------------------------------------------------- zones

class Zone(AbstractComponent):
    """Zone(type): an invisible box with a type. MORSE's `size` is the half-extent (the cube is ±1)."""

    _kind = "zone"

    def __init__(self, type="Zone", name=None):
        self._start(register=True)
        self._type_name = str(type)
        self._half: list | None = None
        if name:
            self.name = name

    @property
    def size(self) -> list:
        return list(self._half) if self._half is not None else [1.0, 1.0, 1.0]

    @size.setter
    def size(self, xyz) -> None:
        self._half = _vector(xyz)
        self._mark("size")

    scale = size

    def rotate(self, x=0.0, y=0.0, z=0.0):
        self._session.warn("Zone.rotate", "Zone.rotate() is not supported (zones are axis-aligned, as in MORSE); "
                           "ignored")

    def _default_label(self) -> str:
        return self._type_name or "zone"

    def _emit_type(self) -> str | None:
        return self._type_name

    def _emit_fields(self) -> dict:
        out = copy.deepcopy(self._raw)
        half = self._half if self._half is not None else [1.0, 1.0, 1.0]
        out["size"] = [2.0 * s if isinstance(s, (int, float)) else s for s in half] if isinstance(half, list) else half
        return out


def builder_error(message: str) -> BuilderError:
    return _session.current().error(message)
