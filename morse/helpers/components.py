"""MORSE's `morse.helpers.components`: `add_data`, `add_property` and `add_level`, called in a component's class
body. As MORSE's, each writes a table into the class being defined (`_data_fields`, `_properties`, `_levels`);
`morse.core.object.Object` turns the tables into morsec's declarations (DataField, the Properties model, Level)
when the class is created."""

from __future__ import annotations

import sys
from collections import OrderedDict

__all__ = ["add_data", "add_level", "add_property"]

RESERVED_LEVELS = ("all", "default")


def _table(name: str) -> OrderedDict:
    namespace = sys._getframe(2).f_locals  # the class body calling add_*
    return namespace.setdefault(name, OrderedDict())


def add_level(name, classpath, doc="(no documentation available yet)", default=False):
    """A level of realism: its name, the class implementing it (a class path, or None: this class), a doc."""
    if name in RESERVED_LEVELS:
        raise NameError(f"{name} is a reserved level name. You can not use it.")
    _table("_levels")[name] = (classpath, doc, default)


def add_data(name, default_value, type="", doc="(no documentation available yet)", level="all"):
    """A field of `local_data`: exported by a sensor, read by an actuator. `level`: "all", a level or a list."""
    _table("_data_fields")[name] = (default_value, type, doc, level)


def add_property(python_name, default_value, name, type="", doc="(no documentation available yet)"):
    """A property the builder script sets (`properties(Name=value)`), given to the component as `python_name`."""
    _table("_properties")[name] = (default_value, type, doc, python_name)
