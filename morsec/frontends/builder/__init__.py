"""MORSE's builder API, recording a morsec scene: `from morsec.frontends.builder import *`.

`from morse.builder import *` (the `morse` package shipped beside morsec, an edge that morsec never
imports) gives the same names, through `morsec.builder`. Besides the fixed classes below, every robot,
sensor, actuator and prop of the catalogue is a class named by its `builder_name` (ATRV, Pose,
MotionVW, ...): a project's own components appear here as soon as their folder exists.

MORSE's `morse/builder/__init__.py` star-imports modules that themselves import `math`, `os`, `sys`,
`json`, `logging`, `pprint` and `bpymorse`, so `from morse.builder import *` handed those to scripts,
which use them without importing them (`math.pi`, `bpymorse.get_object('Ground')`): they are here too
(`MORSE_MODULE_NAMES`). The import hook and the `morse.builder` façade resolve `morse.builder.<module>.<X>`
through `builder_attribute(module, X)`, which names an unknown class with its close matches.
"""

from __future__ import annotations

import json
import logging
import math
import os
import pprint
import sys
from functools import lru_cache

from morsec.component.catalogue import Catalogue
from morsec.errors import did_you_mean
from morsec.frontends.builder import bpymorse
from morsec.frontends.builder.components import (
    AbstractComponent,
    Actuator,
    ActuatorCreator,
    CatalogueProp,
    CatalogueRobot,
    Component,
    ComponentCreator,
    Cone,
    Cube,
    Cylinder,
    FakeRobot,
    GroundRobot,
    IcoSphere,
    Mesh,
    PassiveObject,
    Plane,
    Robot,
    Sensor,
    SensorCreator,
    Sphere,
    Torus,
    WheeledRobot,
    Zone,
)
from morsec.frontends.builder.environment import Environment, TimeStrategies
from morsec.frontends.builder.session import BuilderError, current, current_catalogue

MorseBuilderError = BuilderError
logger = logging.getLogger("morsebuilder")

FIXED = (
    "AbstractComponent", "Component", "Robot", "GroundRobot", "WheeledRobot", "FakeRobot", "Sensor", "Actuator",
    "ComponentCreator", "SensorCreator", "ActuatorCreator", "PassiveObject", "Zone", "Mesh", "Cube", "Cylinder",
    "Sphere", "IcoSphere", "Cone", "Torus", "Plane", "Environment", "TimeStrategies", "MorseBuilderError",
)
# the modules (and logger) MORSE's `from morse.builder import *` handed to scripts besides its classes
MORSE_MODULE_NAMES = ("math", "os", "sys", "json", "logging", "pprint", "logger", "bpymorse")
_MODULES = {"math": math, "os": os, "sys": sys, "json": json, "logging": logging, "pprint": pprint,
            "logger": logger, "bpymorse": bpymorse}
# MORSE's builder modules (`morse.builder.<name>`), each a view of this namespace but `bpymorse`
MORSE_BUILDER_MODULES = ("abstractcomponent", "actuators", "blenderobjects", "bpymorse", "creator", "data",
                         "environment", "morsebuilder", "robots", "sensors")


# other names MORSE's builder gave classes: {alias: the class's name}
MORSE_ALIASES = {"VelodyneZB": "Velodyne",  # MORSE 1.1's name, kept by MORSE's sensors.py
                 "LaserSensorWithArc": "LaserScanner"}  # the base of MORSE's laser scanner classes


@lru_cache(maxsize=16)
def catalogue_classes(cat: Catalogue) -> dict[str, type]:
    """One builder class per catalogue robot, sensor, actuator and prop, named by its builder_name."""
    classes: dict[str, type] = {}
    bases = {"robots": CatalogueRobot, "sensors": SensorCreator, "actuators": ActuatorCreator, "props": CatalogueProp}
    for kind, base in bases.items():
        for cid, comp in sorted(cat.by_kind.get(kind, {}).items()):
            if getattr(comp, "classpath", None):
                continue  # a MORSE-API class: its builder class is the simulation's own (src/<sim>/builder)
            name = comp.builder_name or cid
            if not name.isidentifier() or name in FIXED or name in classes:
                continue
            namespace = {"_type": cid, "_classpath": f"{kind}/{cid}:{comp.__name__}", "__module__": __name__,
                         "__doc__": comp.doc() or comp.short_descr or None, "__qualname__": name}
            # MORSE's builder class's own arguments and methods (Joystick(index=), NavPR2(with_keyboard=),
            # Sound.open), from the component
            mixin = getattr(comp, "builder_mixin", None)
            if kind in ("sensors", "actuators") and not (mixin and "__init__" in vars(mixin)):
                namespace["__init__"] = _device_init(base)
            classes[name] = type(name, (mixin, base) if mixin else (base,), namespace)
    for alias, name in MORSE_ALIASES.items():
        if name in classes and alias not in classes:
            classes[alias] = classes[name]
    return classes


def _device_init(base):
    def __init__(self, name=None):
        base.__init__(self, name)
    return __init__


def builder_names() -> list[str]:
    """What `from morse.builder import *` gives: the classes, and the modules MORSE's gave."""
    return sorted(set(FIXED) | set(catalogue_classes(current_catalogue())) | set(MORSE_MODULE_NAMES))


class UnknownBuilderName(BuilderError, ImportError):
    """`morse.builder.robots.Foo` or `from morse.builder.robots import Foo` with no such class in morsec's
    catalogue: one line at the script's line, with the close matches. An ImportError too, so that
    `try: from morse.builder.robots import Foo / except ImportError:` still works."""


_KINDS = {"robots": ("robots", "robot"), "sensors": ("sensors", "sensor"), "actuators": ("actuators", "actuator")}


def builder_attribute(module: str, attr: str):
    """`attr` of MORSE's builder module `module` ('morse.builder', 'morse.builder.robots',
    'morse.builder.bpymorse', ...): what the import hook and the `morse.builder` façade return for
    `module.attr` and `from module import attr`.

    A builder class or module of this namespace is returned whatever the module (MORSE's modules
    import each other's names); `morse.builder.bpymorse.X` is morsec's bpymorse stand-in's X. An unknown
    name that is not a class name (lower case, private, dunder) raises AttributeError: the import system
    probes those, and falls back to a submodule (`from morse.builder import robots`). An unknown class
    name raises UnknownBuilderName: "no robot 'Foo' in morsec's catalogue; did you mean ...?",
    located at the script line when a script is being recorded."""
    short = module.split(".")[-1] if module.startswith("morse.builder.") else ""
    if short == "bpymorse":
        return getattr(bpymorse, attr)
    if attr in _MODULES:
        return _MODULES[attr]
    if attr == "__all__":
        return builder_names()
    if attr in FIXED:
        return globals()[attr]
    classes = catalogue_classes(current_catalogue())
    if attr in classes:
        return classes[attr]
    if attr in globals() and not isinstance(globals()[attr], type(sys)):
        return globals()[attr]
    if not attr[:1].isupper():  # a module probe, a submodule (morse.builder.robots): not a class name
        raise AttributeError(f"module {module!r} has no attribute {attr!r}")
    raise _unknown(module, short, attr)


def _unknown(module: str, short: str, attr: str) -> UnknownBuilderName:
    cat = current_catalogue()
    if short in _KINDS:
        kind, word = _KINDS[short]
        names = sorted({cls.builder_name or cid for cid, cls in cat.by_kind.get(kind, {}).items()})
        what, known = f"no {word} {attr!r} in morsec's catalogue", f"{word}s: {', '.join(names)}"
    else:
        names = builder_names()
        what, known = f"no builder class {attr!r} in morsec", "`morsec components` lists the catalogue"
    hint = did_you_mean(attr, names)
    message = f"{what} (from {module}){hint}" if hint else f"{what} (from {module}; {known})"
    session = current(create=False)
    if session is not None:
        return UnknownBuilderName(message, *session.position())
    return UnknownBuilderName(message)


def __getattr__(name: str):
    if name == "__all__":
        return builder_names()
    if name[:1].isupper():
        return builder_attribute("morse.builder", name)
    raise AttributeError(f"module 'morsec.builder' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(builder_names()))
