"""MORSE's builder API, recording a morsec scene: `from morsec.frontends.builder import *`.

`from morse.builder import *` (the `morse` package shipped beside morsec, an edge that morsec never
imports) gives the same names, through `morsec.builder`. Besides the fixed classes below, every robot,
sensor, actuator and prop of the catalogue is a class named by its `builder_name` (ATRV, Pose,
MotionVW, ...): a project's own components appear here as soon as their folder exists.
"""

from __future__ import annotations

from functools import lru_cache

from morsec.component.catalogue import Catalogue
from morsec.frontends.builder.components import (
    AbstractComponent,
    Actuator,
    ActuatorCreator,
    CatalogueProp,
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
from morsec.frontends.builder.session import BuilderError, current_catalogue

MorseBuilderError = BuilderError

FIXED = (
    "AbstractComponent", "Component", "Robot", "GroundRobot", "WheeledRobot", "FakeRobot", "Sensor", "Actuator",
    "ComponentCreator", "SensorCreator", "ActuatorCreator", "PassiveObject", "Zone", "Mesh", "Cube", "Cylinder",
    "Sphere", "IcoSphere", "Cone", "Torus", "Plane", "Environment", "TimeStrategies", "MorseBuilderError",
)


@lru_cache(maxsize=16)
def catalogue_classes(cat: Catalogue) -> dict[str, type]:
    """One builder class per catalogue robot, sensor, actuator and prop, named by its builder_name."""
    classes: dict[str, type] = {}
    bases = {"robots": Robot, "sensors": SensorCreator, "actuators": ActuatorCreator, "props": CatalogueProp}
    for kind, base in bases.items():
        for cid, comp in sorted(cat.by_kind.get(kind, {}).items()):
            name = comp.builder_name or cid
            if not name.isidentifier() or name in FIXED or name in classes:
                continue
            namespace = {"_type": cid, "_classpath": f"{kind}/{cid}:{comp.__name__}", "__module__": __name__,
                         "__doc__": comp.doc() or comp.short_descr or None, "__qualname__": name}
            if kind == "robots":
                namespace["__init__"] = _robot_init
            elif kind in ("sensors", "actuators"):
                namespace["__init__"] = _device_init(base)
            classes[name] = type(name, (base,), namespace)
    return classes


def _robot_init(self, name=None, debug=True):
    Robot.__init__(self, "", name)


def _device_init(base):
    def __init__(self, name=None):
        base.__init__(self, name)
    return __init__


def builder_names() -> list[str]:
    return sorted(set(FIXED) | set(catalogue_classes(current_catalogue())))


def __getattr__(name: str):
    if name == "__all__":
        return builder_names()
    if name[:1].isupper():
        classes = catalogue_classes(current_catalogue())
        if name in classes:
            return classes[name]
    raise AttributeError(f"module 'morsec.builder' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(builder_names()))
