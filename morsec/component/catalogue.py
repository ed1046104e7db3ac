"""Component discovery: one folder per component, found on a search path.

Built-in components, a project's own `components/` folders and folders registered by other packages
(entry point group `morsec.components`) go through this same mechanism; nothing about built-ins is special.
A folder is a component when it holds `component.py` defining `COMPONENT = <class>`. The folder is loaded as
a package, so component.py imports the modules beside it as usual (`from .ik import solve`, `from . import
helpers`).
"""

from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import os
import re
import sys
import traceback
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any, Literal, Protocol, get_args, get_origin, overload

from morsec.component.contract import (
    KINDS,
    Actuator,
    Component,
    ComponentProperties,
    DataField,
    Device,
    Environment,
    Prop,
    Robot,
    Sensor,
)
from morsec.component.morse_data import MorseData
from morsec.errors import MorsecError, did_you_mean, one_of
from morsec.modifiers.base import Modifier
from morsec.modifiers.registry import MODIFIERS
from morsec.resources import (  # noqa: F401 (the search path's names, where they used to be)
    ENTRY_POINT_GROUP,
    ENV_VAR,
    PROJECT_FILE,
    classpath_roots,
    data_dir,
    morse_data,
    project_component_dirs,
    project_root,
    search_path,
)

BUILTIN_ROOT = "morsec"  # how a build names the folder of the built-in components
BASIC_TYPES = (bool, int, float, str)


def camel_case(identifier: str) -> str:
    return "".join(part[:1].upper() + part[1:] for part in re.split(r"[_\-/]+", identifier) if part)


@dataclass(eq=False)  # identity hash: generated scene models are cached per catalogue
class Catalogue:
    roots: tuple[Path, ...]
    by_kind: dict[str, dict[str, type[Component]]] = field(default_factory=dict)
    aliases: dict[str, dict[str, str]] = field(default_factory=dict)  # kind -> builder name -> id
    variant_of: dict[str, tuple[str, str]] = field(default_factory=dict)  # prop object name -> (prop id, name)
    _devices: dict | None = field(default=None, repr=False)
    sources: tuple[Path, ...] = ()  # folders of packages holding components named by class path (a MORSE src/)
    morse: MorseData | None = field(default=None, repr=False)  # $MORSE_ROOT's environments and props

    def ids(self, kind: str) -> list[str]:
        return sorted(set(self.by_kind.get(kind, {})) | set(self.morse.ids(kind) if self.morse else ()))

    def names(self, kind: str) -> list[str]:
        """Ids and MORSE builder class names accepted as `type:`."""
        return sorted(set(self.ids(kind)) | set(self.aliases.get(kind, {})))

    def resolve(self, kind: str, name: str) -> str | None:
        if self.morse is not None:
            found = self._from_morse(kind, name)
            if found is not None:
                return found
        if name in self.by_kind.get(kind, {}):
            return name
        return self.aliases.get(kind, {}).get(name)

    def _from_morse(self, kind: str, name: str) -> str | None:
        """A name MORSE's data answers ($MORSE_ROOT): its file imported and its components put first."""
        assert self.morse is not None
        source = self.morse.source(kind, name)
        if source is None:
            return None
        for found_kind, cid, cls in self.morse.load(load_component, *source):
            if self.by_kind.setdefault(found_kind, {}).get(cid) is not cls:
                self.by_kind[found_kind][cid] = cls
                self._devices = None
        wanted = name.replace("\\", "/").removesuffix(".blend").removeprefix(f"{kind}/")
        return wanted if wanted in self.by_kind.get(kind, {}) else None

    # a component of `kind` is a subclass of KINDS[kind] (load_component checks it): typed as such
    @overload
    def get(self, kind: Literal["robots"], name: str) -> type[Robot]: ...
    @overload
    def get(self, kind: Literal["sensors"], name: str) -> type[Sensor]: ...
    @overload
    def get(self, kind: Literal["actuators"], name: str) -> type[Actuator]: ...
    @overload
    def get(self, kind: Literal["environments"], name: str) -> type[Environment]: ...
    @overload
    def get(self, kind: Literal["props"], name: str) -> type[Prop]: ...
    @overload
    def get(self, kind: str, name: str) -> type[Component]: ...

    def get(self, kind: str, name: str) -> type[Component]:
        resolved = self.resolve(kind, name)
        if resolved is None:
            label = kind[:-1]
            raise MorsecError(f"unknown {label} type {name!r}{did_you_mean(name, self.names(kind))}")
        return self.by_kind[kind][resolved]

    def add_classpath_component(self, cls: type[Device]) -> str:
        """Register a class named by its dotted path (a MORSE-API component): its id is the path."""
        kind = f"{cls.kind}s"
        if self.by_kind.setdefault(kind, {}).get(cls.id) is not cls:
            self.by_kind[kind][cls.id] = cls
            self._devices = None
        return cls.id

    def classpath(self, kinds: tuple[str, ...], text: str) -> str | None:
        """The id of the component at class path `text` (module.Class) in this catalogue's sources, imported
        now if it was not found when the catalogue was loaded; None if none of them has it."""
        for kind in kinds:
            if text in self.by_kind.get(kind, {}):
                return text
        for source in self.sources:
            cls = load_classpath(source, text)
            if cls is not None and f"{cls.kind}s" in kinds:
                return self.add_classpath_component(cls)
        return None

    def variant(self, name: str) -> dict | None:
        """The entry of `Prop.variants` that prop type `name` names (an object of a props file), or None."""
        found = self.variant_of.get(name)
        return self.by_kind["props"][found[0]].variants[found[1]] if found else None

    def prop_defaults(self, name: str) -> dict:
        """What an object of prop type `name` is unless its entry says otherwise: the named object's values
        (its parts left out) or the prop's `defaults`."""
        spec = self.variant(name)
        if spec is not None:
            return {k: v for k, v in spec.items() if k != "parts"}
        pid = self.resolve("props", name)
        return self.by_kind["props"][pid].defaults if pid else {}

    def devices(self) -> dict[str, type[Device]]:
        """Sensors and actuators by id (a catalogue does not change once loaded: computed once)."""
        if self._devices is None:
            self._devices = {**self.by_kind.get("sensors", {}), **self.by_kind.get("actuators", {})}
        return self._devices

    def all(self) -> list[type[Component]]:
        return [cls for kind in KINDS for _, cls in sorted(self.by_kind.get(kind, {}).items())]

    def applies_to(self, modifier: str) -> list[str]:
        """Ids of the sensors and actuators modifier `modifier` applies to (declared or inherited)."""
        return sorted(cid for cid, cls in self.devices().items() if modifier_class(modifier, cls) is not None)

    def modifiers(self) -> dict[str, dict[str, type[Modifier]]]:
        """{modifier name: {component id: the class it gives there}} for every name of the registry (what
        MORSE's MORSE_MODIFIER_DICT held), collected from the components' declarations."""
        devices = sorted(self.devices().items())
        return {name: {cid: impl for cid, cls in devices if (impl := modifier_class(name, cls)) is not None}
                for name in MODIFIERS}


def load_catalogue(start: Path | None = None) -> Catalogue:
    return _load(search_path(start), morse_data(), classpath_roots(start))


@lru_cache(maxsize=16)
def _load(roots: tuple[Path, ...], morse: Path | None = None, sources: tuple[Path, ...] = ()) -> Catalogue:
    cat = Catalogue(roots, sources=sources)
    if morse is not None:  # its imports are found by name (Catalogue.resolve), their templates under its root
        cat.morse = MorseData(morse)
        cat.roots = (*roots, cat.morse.root)
    for root in roots:
        for kind in KINDS:
            kind_dir = root / kind
            if not kind_dir.is_dir():
                continue
            for file in sorted(kind_dir.rglob("component.py")):
                folder = file.parent
                cid = folder.relative_to(kind_dir).as_posix()
                cls = load_component(folder, kind, cid)
                existing = cat.by_kind.setdefault(kind, {}).get(cid)
                if existing is not None:
                    raise MorsecError(f"component {cid!r} is defined twice: {existing.folder} and {folder}")
                cat.by_kind[kind][cid] = cls
                alias = cls.builder_name or camel_case(cid)
                cat.aliases.setdefault(kind, {})[alias] = cid
                for name in getattr(cls, "variants", {}):
                    taken = cat.variant_of.get(name) or (None, cat.aliases[kind].get(name))
                    if taken[1] is not None or name in cat.by_kind[kind]:
                        raise MorsecError(f"{folder / 'component.py'}: object {name!r} is already a prop type "
                                          f"({taken[0] or taken[1] or name})")
                    cat.aliases[kind][name] = cid
                    cat.variant_of[name] = (cid, name)
    for source in sources:
        for module in classpath_modules(source):
            for cls in classpath_components(source, module):
                cat.add_classpath_component(cls)
    return cat


# ---------------------------------------------------------------- components named by a dotted class path

def classpath_modules(source: Path) -> list[str]:
    """The modules of a MORSE simulation's `src/` that hold its components, as `morse create` and `morse add`
    lay them out: src/<sim>/sensors/*.py and src/<sim>/actuators/*.py."""
    found = []
    for package in sorted(p for p in source.iterdir() if (p / "__init__.py").is_file()):
        for kind in ("sensors", "actuators"):
            for file in sorted((package / kind).glob("*.py")):
                if file.stem != "__init__":
                    found.append(f"{package.name}.{kind}.{file.stem}")
    return found


def import_from(source: Path, module: str):
    """Import `module` from the folder `source` (put on sys.path, where it stays: its modules import one
    another while the simulation runs). A package of the same name loaded from elsewhere (another simulation's)
    is dropped first. An error is one line at the module's own line."""
    folder = use_source(source)
    try:
        return importlib.import_module(module)
    except MorsecError:
        raise
    except Exception as err:
        raise MorsecError(_import_failure(err, folder, module)) from None


def use_source(source: Path) -> str:
    """Put `source` first on sys.path (if it is not there), and drop the packages of the same names as its own
    that were loaded from elsewhere (another simulation's `mysim`): its own are imported instead."""
    folder = str(Path(source).resolve())
    if folder not in sys.path:
        sys.path.insert(0, folder)
    for top in (p.name for p in Path(folder).iterdir() if (p / "__init__.py").is_file()):
        loaded = sys.modules.get(top)
        where = getattr(loaded, "__file__", None) or next(iter(getattr(loaded, "__path__", None) or []), None)
        if loaded is not None and where and not str(Path(where).resolve()).startswith(folder + os.sep):
            for name in [m for m in sys.modules if m == top or m.startswith(top + ".")]:
                del sys.modules[name]
    return folder


def _import_failure(err: Exception, folder: str, module: str) -> str:
    frames = [f for f in traceback.extract_tb(err.__traceback__) if f.filename.startswith(folder + os.sep)]
    where = f"{frames[-1].filename}:{frames[-1].lineno}: " if frames else ""
    text = str(err).strip().splitlines()
    message = f"{where}{type(err).__name__}" + (f": {text[0]}" if text else "")
    missing = getattr(err, "name", None) if isinstance(err, ModuleNotFoundError) else None
    if missing and missing.split(".")[0] == "morse":
        message += (" (morsec emulates morse.core.sensor, actuator, services, status, exceptions, blenderapi, "
                    "mathutils, robot and morse.helpers.components, transformation, morse_math: see "
                    "docs/coming-from-morse.md)")
    elif missing and missing.split(".")[0] in ("bge", "bpy", "GameLogic"):
        message += " (Blender's modules do not exist in morsec: morse.core.blenderapi stands for what it emulates)"
    elif missing is None and not where:
        message += f" (importing {module})"
    return message


def classpath_components(source: Path, module: str) -> list[type[Device]]:
    """The sensor and actuator classes `module` defines (its levels' classes left out: they are their
    component's)."""
    loaded = import_from(source, module)
    classes = [c for c in vars(loaded).values() if isinstance(c, type) and c.__module__ == loaded.__name__
               and issubclass(c, (Sensor, Actuator)) and c not in (Sensor, Actuator)]
    levels = {lv.cls for c in classes for lv in c.levels if lv.cls}
    return [_as_classpath_component(c, source) for c in classes
            if c.__name__ not in levels and f"{c.__module__}.{c.__name__}" not in levels]


def _as_classpath_component(cls: type[Device], source: Path) -> type[Device]:
    classpath = f"{cls.__module__}.{cls.__qualname__}"
    if vars(cls).get("classpath") != classpath:
        cls.classpath = classpath
        cls.id = classpath
        cls.folder = Path(sys.modules[cls.__module__].__file__ or source).parent
        cls.import_root = Path(source).resolve()
        if "builder_name" not in vars(cls) or not cls.builder_name:
            cls.builder_name = cls.__name__
        check_properties(cls.Properties, Path(cls.folder))
    return cls


def load_classpath(source: Path, classpath: str) -> type[Device] | None:
    """The sensor or actuator class at `classpath` (module.Class) under `source`, or None if the module has no
    such class (an import error is the module's line)."""
    module, _, name = classpath.rpartition(".")
    if not module:
        return None
    try:
        loaded = import_from(source, module)
    except MorsecError as err:
        if f"No module named {module.split('.')[0]!r}" in str(err):
            return None  # not a module of this simulation
        raise
    cls = getattr(loaded, name, None)
    if not (isinstance(cls, type) and issubclass(cls, (Sensor, Actuator))):
        return None
    return _as_classpath_component(cls, source)


def _module_name(folder: Path, kind: str, cid: str) -> str:
    """A stable package name per component folder (two projects may both have a `thermal_cam`); its
    component.py is the module `<name>.component`."""
    digest = hashlib.sha1(str(folder.resolve()).encode()).hexdigest()[:8]
    return f"morsec_components.{kind}.{re.sub(r'[^0-9A-Za-z_]', '_', cid)}_{digest}"


def is_builtin(cls: type[Component]) -> bool:
    """Whether a component comes with morsec (rather than from a project or another package)."""
    try:
        Path(cls.folder).resolve().relative_to(data_dir("components").resolve())
        return True
    except ValueError:
        return False


def _package(folder: Path, name: str):
    """The folder as the package `name` (its `__init__.py` run, if it has one): modules beside component.py
    are its submodules. A package loaded before is dropped with its submodules: a folder loads afresh, whole."""
    for loaded in [m for m in sys.modules if m == name or m.startswith(name + ".")]:
        del sys.modules[loaded]
    parts = name.split(".")
    for i in range(1, len(parts)):  # morsec_components, morsec_components.<kind>: empty packages, for `import`
        parent = ".".join(parts[:i])
        if parent not in sys.modules:
            sys.modules[parent] = importlib.util.module_from_spec(importlib.machinery.ModuleSpec(parent, None,
                                                                                                is_package=True))
    init = folder / "__init__.py"
    if init.is_file():
        spec = importlib.util.spec_from_file_location(name, init, submodule_search_locations=[str(folder)])
    else:
        spec = importlib.machinery.ModuleSpec(name, None, is_package=True)
        spec.submodule_search_locations = [str(folder)]
    package = importlib.util.module_from_spec(spec)
    sys.modules[name] = package
    if spec.loader is not None:
        spec.loader.exec_module(package)
    return package


def load_component(folder: Path, kind: str, cid: str) -> type[Component]:
    package_name = _module_name(folder, kind, cid)
    module_name = f"{package_name}.component"
    try:
        package = _package(folder, package_name)
        spec = importlib.util.spec_from_file_location(module_name, folder / "component.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[module_name] = module
        spec.loader.exec_module(module)
        package.component = module
    except Exception as err:  # a broken user component must name its file
        raise MorsecError(f"{folder / 'component.py'}: cannot load component: {type(err).__name__}: {err}") from None
    cls = getattr(module, "COMPONENT", None)
    base = KINDS[kind]
    if not (isinstance(cls, type) and issubclass(cls, base)):
        raise MorsecError(f"{folder / 'component.py'}: must set COMPONENT to a subclass of "
                          f"morsec.component.{base.__name__}")
    cls.id = cid
    cls.folder = folder
    if cls.builder_name is None:
        cls.builder_name = camel_case(cid)
    check_properties(cls.Properties, folder)
    check_modifiers(cls, folder)
    check_data(cls, folder)
    return cls


class ComponentRefLike(Protocol):
    """Where a build found a component class: morsec.scene.manifest.ComponentRef (a layer above this one)."""

    @property
    def root(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def id(self) -> str: ...
    @property
    def name(self) -> str: ...


@overload
def load_class(ref: str, name: None = None) -> type[Modifier]: ...
@overload
def load_class(ref: ComponentRefLike, name: None = None) -> type[Component]: ...
@overload
def load_class(ref: ComponentRefLike, name: str) -> type[Device]: ...


def load_class(ref: str | ComponentRefLike, name: str | None = None) -> type:
    """A class a build recorded: a modifier's `"module:Class"`, or a component reference (root, kind, id,
    name: see morsec.scene.manifest.ComponentRef) whose folder is loaded if it is not yet; `name` picks
    another class of the same component.py (a level's, a sensor's or actuator's)."""
    if isinstance(ref, str):
        module_name, _, qualname = ref.partition(":")
        try:
            target: Any = importlib.import_module(module_name)
            for part in qualname.split("."):
                target = getattr(target, part)
        except (ImportError, AttributeError) as err:
            raise MorsecError(f"cannot load {ref}: {err}") from None
        if not (isinstance(target, type) and issubclass(target, Modifier)):
            raise MorsecError(f"cannot load {ref}: not a morsec.modifiers.base.Modifier subclass: rebuild the scene")
        return target
    module_path = getattr(ref, "module", None)
    if module_path:  # a class named by its dotted path (a MORSE-API component), importable from `root`
        target = name or ref.name
        if "." in target:
            module_path, _, target = target.rpartition(".")
        found = getattr(import_from(Path(ref.root), module_path), target, None)
        if not (isinstance(found, type) and issubclass(found, Device)):
            raise MorsecError(f"{module_path} has no component class {target}: rebuild the scene")
        return found
    root = data_dir("components") if ref.root == BUILTIN_ROOT else Path(ref.root)
    folder = root / ref.kind / ref.id
    if not (folder / "component.py").is_file():
        raise MorsecError(f"component {ref.kind}/{ref.id} is no longer at {folder}: rebuild the scene")
    module = sys.modules.get(_module_name(folder, ref.kind, ref.id))
    if getattr(getattr(module, "COMPONENT", None), "id", None) != ref.id:
        module = sys.modules[load_component(folder, ref.kind, ref.id).__module__]
    cls = getattr(module, name or ref.name, None)
    if not (isinstance(cls, type) and issubclass(cls, Device if name else Component)):
        raise MorsecError(f"{folder / 'component.py'} has no class {name or ref.name}: rebuild the scene")
    return cls


def type_lineage(cls) -> tuple[str, ...]:
    """A component's catalogue id, then those of the catalogue types it derives from (sick: laser_scanner)."""
    ids = [vars(k)["id"] for k in cls.__mro__ if isinstance(vars(k).get("id"), str) and vars(k)["id"]]
    return tuple(dict.fromkeys(ids))


def declaring_folder(cls, attribute: str) -> Path:
    """The folder of the class that declares `attribute` (a model file's name, `xacro`): a subclass in a
    folder of its own that keeps its parent's model (NavPR2 of BasePR2) finds the file in the parent's folder.
    The class's own folder when no catalogue class declares it (the contract's default)."""
    owner = next((k for k in cls.__mro__ if attribute in vars(k) and "folder" in vars(k)), cls)
    return Path(vars(owner).get("folder") or cls.folder)


def component_class(kind: str, cid: str, start: Path | None = None) -> type[Component]:
    """The class of component `cid` of `kind` ("sensors", ...) on the search path, for a component.py that
    extends another one (a preset: `LaserScanner = component_class("sensors", "laser_scanner")`). Reuses
    the module if already loaded; cannot go through load_catalogue, which is running when presets load."""
    for root in search_path(start):
        folder = root / kind / cid
        if (folder / "component.py").is_file():
            module = sys.modules.get(f"{_module_name(folder, kind, cid)}.component")
            loaded = getattr(module, "COMPONENT", None)
            return loaded if getattr(loaded, "id", None) == cid else load_component(folder, kind, cid)
    raise MorsecError(f"no {kind[:-1]} {cid!r} on the component search path")


def _basic(annotation) -> bool:
    if annotation in BASIC_TYPES:
        return True
    return get_origin(annotation) is Literal and all(isinstance(a, BASIC_TYPES) for a in get_args(annotation))


def check_properties(model: type[ComponentProperties], folder: Path) -> None:
    for name, info in model.model_fields.items():
        if not _basic(info.annotation):
            raise MorsecError(f"{folder / 'component.py'}: property {name!r} must be bool, int, float or str "
                              f"(got {info.annotation!r}), as MORSE's add_property")


def check_modifiers(cls: type[Component], folder: Path) -> None:
    declared = getattr(cls, "modifiers", {})
    if not isinstance(declared, dict):
        raise MorsecError(f"{folder / 'component.py'}: `modifiers` must be a mapping {{name: Modifier class}}")
    for name, impl in declared.items():
        if name not in MODIFIERS:
            raise MorsecError(f"{folder / 'component.py'}: unknown modifier {name!r} in `modifiers`"
                              f"{did_you_mean(str(name), MODIFIERS) or '; modifiers: ' + one_of(MODIFIERS)}")
        if not (isinstance(impl, type) and issubclass(impl, Modifier)):
            raise MorsecError(f"{folder / 'component.py'}: modifiers[{name!r}] must be a subclass of "
                              f"morsec.modifiers.base.Modifier (got {impl!r})")


def modifier_class(name: str, cls: type[Component]) -> type[Modifier] | None:
    """The modifier class `alter(name)` gives on a component class (declared by the class or inherited from
    its parents: a preset such as `sick` takes the modifiers of `laser_scanner`); None: it does not apply."""
    return getattr(cls, "modifiers", {}).get(name.lower())


def check_data(cls: type[Component], folder: Path) -> None:
    """Data fields are DataFields (their types were checked when they were made: see morsec.component.fields)."""
    message = getattr(cls, "message_fields", None) or ()
    extra = getattr(cls, "extra_field", None)
    for entry in (*getattr(cls, "data", ()), *message, *((extra,) if extra is not None else ())):
        if not isinstance(entry, DataField):
            raise MorsecError(f"{folder / 'component.py'}: data fields must be DataField(name, default, type, doc), "
                              f"got {entry!r}")


def level_class(cls: type[Device], level: str | None) -> type[Device]:
    """The class implementing `level` (add_level's classpath), defined in the same component.py."""
    for lv in cls.levels:
        if lv.name == level and lv.cls:
            module_name, _, name = lv.cls.rpartition(".")  # a class path: another module's class (MORSE's levels)
            module = importlib.import_module(module_name) if module_name else sys.modules[cls.__module__]
            return getattr(module, name)
    return cls
