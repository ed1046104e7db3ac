"""MORSE's builder API for your own Python: `from morsec.builder import *`.

The public face of the builder front end (morsec.frontends.builder): the fixed builder classes plus one
class per catalogue robot, sensor, actuator and prop, named by its builder name (ATRV, Pose, MotionVW...).
A script run as plain Python (`python mysim.py [-- run ...]`) hands its scene to the `morsec` command line
at `Environment.create()`. To record builder calls from a notebook or a test: `with recording() as s: ...`.
"""

from __future__ import annotations

import morsec.frontends.builder as _namespace
from morsec.cli.standalone import standalone_main
from morsec.frontends.builder import session as _session
from morsec.frontends.builder.script import recording  # noqa: F401 (public: record builder calls in a notebook)

_session.on_standalone_create(standalone_main)


def __getattr__(name: str):
    if name == "__all__":
        return _namespace.builder_names()
    return getattr(_namespace, name)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_namespace.builder_names()))
