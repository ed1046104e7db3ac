"""The middlewares morsec knows: every class registered under the `morsec.middlewares` entry points, the
built-in socket and text included (see pyproject.toml). A package adds one the same way."""

from __future__ import annotations

from functools import cache, lru_cache

from morsec.errors import MorsecError, did_you_mean
from morsec.middleware.base import Middleware
from morsec.resources import entry_points_of

ENTRY_POINT_GROUP = "morsec.middlewares"


@lru_cache(maxsize=1)
def middlewares() -> dict[str, type[Middleware]]:
    return {name: _load(ep) for name, ep in _registered().items()}


@cache
def middleware(name: str) -> type[Middleware]:
    """The middleware registered as `name`, its module alone imported: a run imports the middlewares its scene
    uses, not every one installed."""
    registered = _registered()
    if name not in registered:
        raise MorsecError(f"unknown middleware {name!r}{did_you_mean(name, registered)}")
    return _load(registered[name])


@lru_cache(maxsize=1)
def _registered() -> dict:
    found = {ep.name: ep for ep in entry_points_of(ENTRY_POINT_GROUP)}
    if not found:
        raise MorsecError("no middleware is registered: morsec is not installed (pip install -e . in its folder)")
    return found


def _load(ep) -> type[Middleware]:
    cls = ep.load()
    if not (isinstance(cls, type) and issubclass(cls, Middleware)) or cls.name != ep.name:
        raise MorsecError(f"entry point {ep.name} = {ep.value}: must name a morsec.middleware.base.Middleware "
                          f"subclass whose name is {ep.name!r}")
    return cls


def service_middlewares() -> tuple[str, ...]:
    return tuple(name for name, cls in middlewares().items() if cls.carries_services)
