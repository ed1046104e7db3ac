"""Dispatch service requests to components, MORSE's way.

A synchronous service answers at once with its return value. An asynchronous one answers when the
component calls `completed(status, result)`. A second asynchronous call on a busy component preempts the
running one if that service is interruptible, else fails. `id cancel` aborts a running one (PREEMPTED).
"""

from __future__ import annotations

import inspect
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from morsec.component.services import FAILED, PREEMPTED, SUCCESS, Request, ServiceInfo
from morsec.constants import MAX_PENDING_REQUESTS, PSEUDO_COMPONENTS

log = logging.getLogger("morsec.services")


@dataclass
class Exposed:
    obj: Any
    services: dict[str, ServiceInfo] = field(default_factory=dict)
    owners: dict[str, Any] = field(default_factory=dict)  # services another object adds (a middleware's)
    calls: dict[str, Call] = field(default_factory=dict)  # service -> its method, looked up once (see `call`)

    def owner(self, service: str) -> Any:
        return self.owners.get(service, self.obj)

    def call(self, service: str, info: ServiceInfo) -> Call:
        found = self.calls.get(service)
        if found is None:
            found = self.calls[service] = Call.of(getattr(self.owner(service), _attribute(self.owner(service), info)))
        return found


@dataclass(frozen=True)
class Call:
    """A service's bound method and how many positional arguments it takes: checking a request's count is
    a comparison; inspect's binding, which costs more than the rest of a request, only words the refusal."""

    method: Callable
    signature: inspect.Signature
    fewest: int
    most: float  # inf: *args

    @classmethod
    def of(cls, method: Callable) -> Call:
        signature = inspect.signature(method)
        fewest, most = 0, 0.0
        for parameter in signature.parameters.values():
            if parameter.kind in (parameter.POSITIONAL_ONLY, parameter.POSITIONAL_OR_KEYWORD):
                most += 1
                fewest += parameter.default is parameter.empty
            elif parameter.kind is parameter.VAR_POSITIONAL:
                most = float("inf")
            elif parameter.kind is parameter.KEYWORD_ONLY and parameter.default is parameter.empty:
                fewest, most = 1, 0.0  # no positional call binds: every request gets bind's refusal
        return cls(method, signature, fewest, most)

    def takes(self, args: list) -> bool:
        return self.fewest <= len(args) <= self.most


class RequestManager:
    """Asynchronous requests in progress are kept twice, by component and by client, in insertion-ordered
    dicts: starting, finishing, cancelling one and dropping a client's are as cheap as the requests
    concerned, however many others are running."""

    def __init__(self):
        self.exposed: dict[str, Exposed] = {}
        self.running: dict[str, dict[Request, None]] = {}  # component -> async requests in progress
        self.by_client: dict[Any, dict[Request, None]] = {}  # client -> its async requests in progress
        self.current: Request | None = None  # the request being dispatched (for async services)
        self.on_request: list[Callable[[Request], None]] = []  # told of each request, before it is handled
        self.on_leave: list[Callable[[Any], None]] = []  # told of each client that went away
        self.on_complete: list[Callable[[Request], None]] = []  # told of each asynchronous request answered
        # MORSE's frame order (docs/running.md#time): a component's asynchronous service starts at the end of the
        # frame after the one it arrived after, and so acts from the next; `frames` (the loop's frame count) set,
        # such requests wait in `waiting` (frame count at arrival, request, the component, its method)
        self.frames: Callable[[], int] | None = None
        self.waiting: list[tuple[int, Request, Exposed, Any]] = []
        self.last_request = float("-inf")  # wall clock (perf_counter) of the last request handled

    def expose(self, name: str, obj: Any, services: dict[str, ServiceInfo]) -> None:
        self.exposed[name] = Exposed(obj, dict(services))

    def expose_more(self, name: str, obj: Any, services: dict[str, ServiceInfo]) -> None:
        """Services of `obj` added to the already exposed `name` (the socket middleware's stream ports on
        `simulation`, as MORSE's socket datastream manager added them)."""
        exposed = self.exposed[name]
        for service_name, info in services.items():
            exposed.services[service_name] = info
            exposed.owners[service_name] = obj
            exposed.calls.pop(service_name, None)

    def service_names(self, name: str) -> list[str]:
        exposed = self.exposed.get(name)
        return sorted(exposed.services) if exposed else []

    def anytime(self, component: str, service: str) -> bool:
        """Whether the service may be answered while a frame's physics runs (ServiceInfo.anytime)."""
        exposed = self.exposed.get(component)
        info = exposed.services.get(service) if exposed else None
        return info is not None and info.anytime

    def is_running(self, request: Request) -> bool:
        return request in self.running.get(request.component, ())

    def _pending_count(self, client: Any) -> int:
        """The client's asynchronous requests running or waiting to start."""
        waiting = sum(1 for entry in self.waiting if entry[1].client == client) if self.waiting else 0
        return len(self.by_client.get(client, ())) + waiting

    def pending(self, request: Request) -> bool:
        """Whether an asynchronous request is not answered yet (running, or waiting to start)."""
        return self.is_running(request) or any(entry[1] is request for entry in self.waiting)

    def handle(self, request: Request) -> None:
        self.last_request = time.perf_counter()
        for listener in self.on_request:
            listener(request)
        exposed = self.exposed.get(request.component)
        info = exposed.services.get(request.service) if exposed else None
        if exposed is None or info is None:
            request.reply(request.id, FAILED, f"The request {request.service!r} of component {request.component!r} "
                          "has not been registered in Socket service manager")
            return
        call = exposed.call(request.service, info)
        method = call.method
        try:
            if not call.takes(request.args):
                call.signature.bind(*request.args)  # raises, in inspect's words
        except TypeError as err:
            if not request.args:  # MORSE's words (pymorse raises MorseServiceFailed, not TypeError)
                request.reply(request.id, FAILED, f"Socket service manager: parameters expected for service "
                              f"{request.service}! {request.component}.{request.service}: {err}")
            else:
                request.reply(request.id, FAILED,
                              f"wrong # of parameters for {request.component}.{request.service}: {err}")
            return
        request.info = info
        if info.asynchronous:
            if request.client is not None and self._pending_count(request.client) >= MAX_PENDING_REQUESTS:
                request.reply(request.id, FAILED, "too many requests pending for this client "
                              f"({MAX_PENDING_REQUESTS}): wait for their answers or cancel some")
                return
            if self.frames is not None and request.component not in PSEUDO_COMPONENTS:
                self.waiting.append((self.frames(), request, exposed, method))
                return
            self._start_async(exposed, request, method)
            return
        try:
            result = method(*request.args)
        except Exception as err:  # a service's failure is the client's answer, not the simulation's end
            request.reply(request.id, FAILED, _message(err))
            return
        request.reply(request.id, SUCCESS, result)

    def start_waiting(self, frames: int) -> None:
        """At the end of a frame, `frames` frames run: start the asynchronous requests that arrived before
        that frame began (see `waiting`), in their order."""
        if not self.waiting or self.waiting[0][0] >= frames:
            return
        ready = [entry for entry in self.waiting if entry[0] < frames]
        self.waiting = [entry for entry in self.waiting if entry[0] >= frames]
        for _, request, exposed, method in ready:
            self._start_async(exposed, request, method)

    def _start_async(self, exposed: Exposed, request: Request, method) -> None:
        running = self.running.setdefault(request.component, {})
        concurrent = getattr(method, "_morsec_concurrent", False)
        if running and not concurrent:
            old = next(reversed(running))
            if old.info and old.info.interruptible:
                self._finish(old)
                exposed.obj.interrupt()
                old.reply(old.id, PREEMPTED, None)
            else:
                request.reply(request.id, FAILED, f"{request.component}: service {old.service!r} is already running "
                              "and cannot be interrupted")
                return
        running[request] = None
        self.by_client.setdefault(request.client, {})[request] = None
        self.current = request
        try:
            method(*request.args)
        except Exception as err:
            if request in running:
                self._finish(request)
            request.reply(request.id, FAILED, _message(err))
        finally:
            self.current = None

    def _finish(self, request: Request) -> None:
        """No longer in progress (answered, preempted, cancelled or abandoned)."""
        self.running.get(request.component, {}).pop(request, None)
        mine = self.by_client.get(request.client)
        if mine is not None:
            mine.pop(request, None)
            if not mine:
                del self.by_client[request.client]

    def complete(self, component: str, status: str, result: Any, request: Request | None = None) -> None:
        running = self.running.get(component) or {}
        if request is None:
            if self.current is not None and self.current.component == component:
                request = self.current
            elif running:
                request = next(reversed(running))
        if request is None or request not in running:
            return
        self._finish(request)
        request.reply(request.id, status, result)
        for listener in self.on_complete:
            listener(request)

    def cancel(self, client: Any, request_id: str) -> None:
        for entry in self.waiting:
            request = entry[1]
            if request.client == client and request.id == request_id:  # not started yet: nothing to interrupt
                self.waiting.remove(entry)
                request.reply(request.id, PREEMPTED, None)
                return
        for request in list(self.by_client.get(client, ())):
            if request.id == request_id:
                self._abandon([request])
                self.exposed[request.component].obj.interrupt()
                request.reply(request.id, PREEMPTED, None)
                return

    def drop_client(self, client: Any) -> None:
        """A client went away: its pending requests can no longer be answered."""
        self.waiting = [entry for entry in self.waiting if entry[1].client != client]
        self._abandon(list(self.by_client.get(client, ())))
        for listener in self.on_leave:
            listener(client)

    def _abandon(self, requests: list[Request]) -> None:
        """Finish requests nobody will complete; a component that keeps requests itself (time.sleep's
        queue) forgets them in its `abandoned(requests)`, once per component."""
        by_component: dict[str, list[Request]] = {}
        for request in requests:
            self._finish(request)
            by_component.setdefault(request.component, []).append(request)
        for component, mine in by_component.items():
            forget = getattr(self.exposed[component].obj, "abandoned", None)
            if forget is not None:
                forget(mine)


def concurrent(fn):
    """Mark an asynchronous service that may run several times at once (time.sleep)."""
    fn._morsec_concurrent = True
    return fn


def services_of(obj: Any) -> dict[str, ServiceInfo]:
    """The services an object's class (and its bases) declare, by name: what `expose` takes."""
    found = {}
    for klass in reversed(type(obj).__mro__):
        for value in vars(klass).values():
            info = getattr(value, "_morsec_service", None)
            if info is not None:
                found[info.name] = info
    return found


def _attribute(obj: Any, info: ServiceInfo) -> str:
    for klass in type(obj).__mro__:
        for attr, value in vars(klass).items():
            if getattr(value, "_morsec_service", None) is info:
                return attr
    return info.name


def _message(err: Exception) -> str:
    text = str(err) or type(err).__name__
    return text if isinstance(err, (ValueError, KeyError, LookupError)) else f"{type(err).__name__}: {text}"
