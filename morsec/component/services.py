"""Services, as components declare them and middlewares carry them: the decorators, the request a
middleware hands to the runtime, and MORSE's answer statuses."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

SUCCESS, FAILED, PREEMPTED = "SUCCESS", "FAILED", "PREEMPTED"


@dataclass(eq=False)  # compared and hashed by identity: a key of the manager's tables
class Request:
    id: str
    component: str
    service: str
    args: list
    reply: Callable[[str, str, Any], None]  # (id, status, result)
    client: Any = None  # the connection it came on, for `cancel`
    info: ServiceInfo | None = None


class RequestHandler(Protocol):
    """What a middleware hands requests to (the runtime's RequestManager)."""

    def handle(self, request: Request) -> None: ...
    def anytime(self, component: str, service: str) -> bool: ...
    def cancel(self, client: Any, request_id: str) -> None: ...
    def drop_client(self, client: Any) -> None: ...


@dataclass(frozen=True)
class ServiceInfo:
    name: str
    asynchronous: bool
    interruptible: bool | None  # None: no policy, a second call fails
    anytime: bool = False  # may be answered while a frame's physics runs (see `service`)


def service(fn: Callable | None = None, *, name: str | None = None, anytime: bool = False):
    """A synchronous service: its return value is the answer. `anytime`: it reads nothing a frame changes
    (MjData, the components' data) and changes nothing, so it may be answered between two physics
    sub-steps of a frame (`time now`, `simulation list_robots`), not only between frames."""
    def mark(f):
        f._morsec_service = ServiceInfo(name or f.__name__, False, None, anytime)
        return f
    return mark(fn) if fn else mark


def async_service(fn: Callable | None = None, *, name: str | None = None, interruptible: bool | None = None):
    """An asynchronous service: it starts work and later calls `self.completed(status, result)`."""
    def mark(f):
        f._morsec_service = ServiceInfo(name or f.__name__, True, interruptible)
        return f
    return mark(fn) if fn else mark
