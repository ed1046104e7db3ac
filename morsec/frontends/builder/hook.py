"""`from morse.builder import *` inside a script that morsec runs: an import hook on sys.meta_path,
installed only while the script executes, that answers `morse`, `morse.builder` and every
`morse.builder.<module>` (sensors, actuators, robots, creator, ...) with views of `morsec.frontends.builder`.
No `morse` package is installed in the user's environment.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import types
from contextlib import contextmanager

ROOT = "morse"
BUILDER = "morse.builder"


def _view(name: str) -> types.ModuleType:
    """A module whose attributes (and `__all__`) are those of morsec.frontends.builder."""
    import morsec.frontends.builder as target

    module = types.ModuleType(name, f"morsec's view of MORSE's {name} (see morsec.frontends.builder)")

    def __getattr__(attr: str):
        if attr == "__all__":
            return list(target.__all__)
        try:
            return getattr(target, attr)
        except AttributeError:
            raise AttributeError(f"module {name!r} has no attribute {attr!r} (morsec's builder has no such "
                                 "class; see docs/coming-from-morse.md)") from None

    module.__getattr__ = __getattr__
    module.__dir__ = lambda: sorted(target.__all__)
    return module


class MorseBuilderFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    def find_spec(self, fullname, path=None, target=None):
        if fullname == ROOT or fullname == BUILDER or fullname.startswith(BUILDER + "."):
            return importlib.machinery.ModuleSpec(fullname, self, is_package=True)
        return None

    def create_module(self, spec):
        if spec.name == ROOT:
            module = types.ModuleType(ROOT, "morsec's stand-in for MORSE: only morse.builder is provided")
            return module
        return _view(spec.name)

    def exec_module(self, module):
        if module.__name__ == ROOT:
            module.__path__ = []
        else:
            module.__path__ = []


def _ours(name: str) -> bool:
    return name == ROOT or name.startswith(ROOT + ".")


@contextmanager
def morse_import_hook():
    """While active, `import morse.builder` gives morsec's builder; afterwards everything is as before."""
    saved = {name: mod for name, mod in sys.modules.items() if _ours(name)}
    for name in saved:
        del sys.modules[name]
    finder = MorseBuilderFinder()
    sys.meta_path.insert(0, finder)
    try:
        yield finder
    finally:
        if finder in sys.meta_path:
            sys.meta_path.remove(finder)
        for name in [n for n in sys.modules if _ours(n)]:
            del sys.modules[name]
        sys.modules.update(saved)
