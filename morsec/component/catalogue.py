"""Component discovery: one folder per component, found on a search path.

Built-in components, a project's own `components/` folders and folders registered by other packages
(entry point group `morsec.components`) go through this same mechanism; nothing about built-ins is special.
A folder is a component when it holds `component.py` defining `COMPONENT = <class>`.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import re
import sys
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from importlib.metadata import entry_points
from pathlib import Path
from typing import Literal, get_args, get_origin

from morsec.component.contract import KINDS, Component, ComponentProperties, DataField, Device
from morsec.errors import MorsecError, did_you_mean
from morsec.resources import data_dir

PROJECT_FILE = "morsec.toml"
ENV_VAR = "MORSEC_COMPONENTS"
ENTRY_POINT_GROUP = "morsec.components"
BASIC_TYPES = (bool, int, float, str)


def camel_case(identifier: str) -> str:
    return "".join(part[:1].upper() + part[1:] for part in re.split(r"[_\-/]+", identifier) if part)


@dataclass(eq=False)  # identity hash: generated scene models are cached per catalogue
class Catalogue:
    roots: tuple[Path, ...]
    by_kind: dict[str, dict[str, type[Component]]] = field(default_factory=dict)
    aliases: dict[str, dict[str, str]] = field(default_factory=dict)  # kind -> builder name -> id
    _devices: dict | None = field(default=None, repr=False)

    def ids(self, kind: str) -> list[str]:
        return sorted(self.by_kind.get(kind, {}))

    def names(self, kind: str) -> list[str]:
        """Ids and MORSE builder class names accepted as `type:`."""
        return sorted(set(self.by_kind.get(kind, {})) | set(self.aliases.get(kind, {})))

    def resolve(self, kind: str, name: str) -> str | None:
        if name in self.by_kind.get(kind, {}):
            return name
        return self.aliases.get(kind, {}).get(name)

    def get(self, kind: str, name: str) -> type[Component]:
        resolved = self.resolve(kind, name)
        if resolved is None:
            label = kind[:-1]
            raise MorsecError(f"unknown {label} type {name!r}{did_you_mean(name, self.names(kind))}")
        return self.by_kind[kind][resolved]

    def devices(self) -> dict[str, type[Device]]:
        """Sensors and actuators by id (a catalogue does not change once loaded: computed once)."""
        if self._devices is None:
            self._devices = {**self.by_kind.get("sensors", {}), **self.by_kind.get("actuators", {})}
        return self._devices

    def all(self) -> list[type[Component]]:
        return [cls for kind in KINDS for _, cls in sorted(self.by_kind.get(kind, {}).items())]


def project_root(start: Path) -> Path | None:
    """The nearest folder at or above `start` holding a `morsec.toml` project file."""
    start = start.resolve()
    for folder in (start, *start.parents):
        if (folder / PROJECT_FILE).is_file():
            return folder
    return None


def project_component_dirs(root: Path) -> list[Path]:
    with open(root / PROJECT_FILE, "rb") as f:
        try:
            config = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise MorsecError(f"{root / PROJECT_FILE}: {err}") from None
    dirs = config.get("project", {}).get("components", ["components"])
    return [(root / d) for d in dirs]


def search_path(start: Path | None = None) -> tuple[Path, ...]:
    """Built-ins, then entry points, then $MORSEC_COMPONENTS, then the project's folders (from `start` up)."""
    paths = [data_dir("components")]
    for ep in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name):
        target = ep.load()
        paths.append(Path(target() if callable(target) else target))
    for item in os.environ.get(ENV_VAR, "").split(os.pathsep):
        if item:
            paths.append(Path(item))
    root = project_root(start if start is not None else Path.cwd())
    if root is not None:
        paths.extend(project_component_dirs(root))
    unique: list[Path] = []
    for p in paths:
        p = p.resolve()
        if p not in unique and p.is_dir():
            unique.append(p)
    return tuple(unique)


def load_catalogue(start: Path | None = None) -> Catalogue:
    return _load(search_path(start))


@lru_cache(maxsize=16)
def _load(roots: tuple[Path, ...]) -> Catalogue:
    cat = Catalogue(roots)
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
    return cat


def _module_name(folder: Path, kind: str, cid: str) -> str:
    """A stable module name per component folder (two projects may both have a `thermal_cam`)."""
    digest = hashlib.sha1(str(folder.resolve()).encode()).hexdigest()[:8]
    return f"morsec_components.{kind}.{re.sub(r'[^0-9A-Za-z_]', '_', cid)}_{digest}"


def is_builtin(cls: type[Component]) -> bool:
    """Whether a component comes with morsec (rather than from a project or another package)."""
    try:
        Path(cls.folder).resolve().relative_to(data_dir("components").resolve())
        return True
    except ValueError:
        return False


def load_component(folder: Path, kind: str, cid: str) -> type[Component]:
    module_name = _module_name(folder, kind, cid)
    spec = importlib.util.spec_from_file_location(module_name, folder / "component.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except Exception as err:  # a broken user component must name its file
        raise MorsecError(f"{folder / 'component.py'}: cannot load component: {type(err).__name__}: {err}") from None
    cls = getattr(module, "COMPONENT", None)
    base = KINDS[kind]
    if not (isinstance(cls, type) and issubclass(cls, base)):
        raise MorsecError(f"{folder / 'component.py'}: must set COMPONENT to a subclass of morsec.component.{base.__name__}")
    cls.id = cid
    cls.folder = folder
    if cls.builder_name is None:
        cls.builder_name = camel_case(cid)
    check_properties(cls.Properties, folder)
    check_data(cls, folder)
    return cls


def component_class(kind: str, cid: str, start: Path | None = None) -> type[Component]:
    """The class of component `cid` of `kind` ("sensors", ...) on the search path, for a component.py that
    extends another one (a preset: `LaserScanner = component_class("sensors", "laser_scanner")`). Reuses
    the module if already loaded; cannot go through load_catalogue, which is running when presets load."""
    for root in search_path(start):
        folder = root / kind / cid
        if (folder / "component.py").is_file():
            module = sys.modules.get(_module_name(folder, kind, cid))
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
            module = sys.modules[cls.__module__]
            return getattr(module, lv.cls)
    return cls
