"""A fix for pymorse 1.4 (PyPI) on Python 3: `Morse.close()` raises at the end of every session.

pymorse 1.4's `Morse.close()` — called by `with Morse() as sim:` on exit and by `sim.quit()` — first
waits for the output queues of the components that can publish, found by
`Morse.get_publisher_streams`. That method tests `'publish' in dir(component)`; `dir()` reads the
component's `__class__` through `Component.__getattribute__`, which calls `lazy_init` on anything that
has one — here the `Component` class itself — so Python 3 raises

    TypeError: Component.lazy_init() missing 1 required positional argument: 'self'

whatever the simulator does, and `close()` stops before shutting down pymorse's executor and polling
thread (the client process then hangs until the server goes away). This is a defect of the client, not
of the wire protocol; morsec's server cannot avoid it.

    from morsec.pymorse_compat import patch_pymorse
    patch_pymorse()            # once, before or after importing pymorse; harmless if repeated
    from pymorse import Morse
    with Morse() as sim:       # now closes cleanly
        ...

`patch_pymorse()` replaces `pymorse.Morse.get_publisher_streams` with an implementation that behaves
the same (it yields the `StreamJSON` of every component that can publish, i.e. whose input stream has
been opened) but reads the components' attributes with `object.__getattribute__`, which does not call
`lazy_init`. It also visits sub-components (`robot.arm.gripper`), which the original never reached.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

_MARK = "_morsec_patched"


def _publisher_streams(morse: Any) -> Iterator[Any]:
    """The StreamJSON of every opened component stream that can publish (actuator input)."""
    from pymorse.pymorse import Component

    def walk(component: Any) -> Iterator[Any]:
        attributes = object.__getattribute__(component, "__dict__")
        if "publish" in attributes and attributes.get("stream") is not None:
            yield attributes["stream"]
        for value in list(attributes.values()):
            if type(value) is Component:  # sub-components are attributes of their parent component
                yield from walk(value)

    for name in list(getattr(morse, "robots", [])):
        # pymorse's loop-robot lists (robot, robot_001 -> morse.robots) can replace the name list itself
        robot = name if isinstance(name, dict) else object.__getattribute__(morse, name)
        for element in list(dict.values(robot)):
            if type(element) is Component:
                yield from walk(element)


def patch_pymorse() -> bool:
    """Replace `pymorse.Morse.get_publisher_streams` with a working one. Idempotent.

    Returns True when this call patched pymorse, False when it was patched already. Raises ImportError
    when pymorse is not installed."""
    import pymorse.pymorse as module

    if getattr(module.Morse.get_publisher_streams, _MARK, False):
        return False

    def get_publisher_streams(self) -> Iterator[Any]:
        return _publisher_streams(self)

    get_publisher_streams.__doc__ = _publisher_streams.__doc__
    get_publisher_streams.__qualname__ = "Morse.get_publisher_streams"
    setattr(get_publisher_streams, _MARK, True)
    module.Morse.get_publisher_streams = get_publisher_streams
    return True
