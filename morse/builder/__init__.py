"""`from morse.builder import *`: MORSE's builder API under its own name, in a builder script that
`morsec build/run` runs as in plain Python (`python mysim.py`, a MORSE test file's `setUpEnv`).

The names are those of `morsec.builder`: the fixed builder classes (`Environment`, `Robot`, `FakeRobot`,
`PassiveObject`, ...) and one class per catalogue robot, sensor, actuator and prop (`ATRV`, `Pose`,
`MotionVW`, ...). MORSE spread them over submodules; every `morse.builder.<module>` a script imports
(`sensors`, `actuators`, `robots`, `creator`, `morsebuilder`, `blenderobjects`, ...) gives the same names.

MORSE's star import also handed over the modules its builder imported (it had no `__all__`), and MORSE
scripts and test files use `math` from it without importing it: those come too (the builder namespace's
MORSE_MODULE_NAMES). An unknown class (`morse.builder.robots.Foo`) is one located line with close matches.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import types

import morsec.builder  # noqa: F401 (`python mysim.py` hands its scene to the command line at create())
from morsec.frontends.builder import MORSE_BUILDER_MODULES, builder_attribute, builder_names


def _delegate(name: str):
    """`__getattr__` and `__dir__` for a module named `name` whose attributes are the builder namespace's."""

    def __getattr__(attr: str):
        if attr == "__all__":
            return builder_names()
        if attr.startswith("__"):
            raise AttributeError(attr)
        return builder_attribute(name, attr)

    def __dir__() -> list[str]:
        return builder_names()

    return __getattr__, __dir__


__getattr__, __dir__ = _delegate(__name__)


class _Submodules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Answers `import morse.builder.<module>` for MORSE's builder modules (after the regular finders) with a
    view of the names; any other name under morse.builder is not a module (`from morse.builder.robots import
    BasePR2` then fails with the builder's one-line ImportError naming the missing class)."""

    def find_spec(self, fullname, path=None, target=None):
        parts = fullname.split(".")
        # MORSE's builder modules, and the modules inside them (morse.builder.robots.morserobots ...)
        if parts[:2] == __name__.split(".") and len(parts) > 2 and parts[2] in MORSE_BUILDER_MODULES \
                and parts[-1][:1].islower():
            return importlib.machinery.ModuleSpec(fullname, self, is_package=True)
        return None

    def create_module(self, spec):
        module = types.ModuleType(spec.name, f"MORSE's {spec.name}: the names of morsec.builder")
        module.__getattr__, module.__dir__ = _delegate(spec.name)
        return module

    def exec_module(self, module):
        pass


# last on sys.meta_path: a real file would win; once only, even if this module is reloaded
if not any(type(finder).__module__ == __name__ and type(finder).__name__ == "_Submodules" for finder in sys.meta_path):
    sys.meta_path.append(_Submodules())
