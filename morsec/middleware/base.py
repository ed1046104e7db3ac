"""What a middleware is. One class per middleware, registered by name like a component (built-ins and other
packages through the `morsec.middlewares` entry points): it declares the stream options it reads, assigns
every stream's endpoint when the scene is built, and opens them when the build runs.

    build:  Middleware.assign(streams) -> one endpoint per stream (a port, a file ...), written in the manifest
    run:    Middleware(context, settings) -> open_stream(...) per stream, open_services(...), close()
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Protocol

from pydantic import BaseModel

from morsec.component.services import RequestHandler
from morsec.middleware.poller import Poller


@dataclass(frozen=True)
class StreamRequest:
    """A stream as the scene asks for it: the component, the direction, the options the scene gave (topic,
    frame_id, a full binding's classpath and method, and this middleware's own)."""

    component: str
    direction: str  # IN (actuator input) or OUT (sensor output)
    options: dict[str, Any]
    types: tuple[str, ...] = ()  # the component's catalogue id, then those of the types it derives from
    properties: dict[str, Any] = field(default_factory=dict)  # its resolved properties
    # where it is on its robot, as the scene placed it (nesting composed): ([x, y, z] m, [roll, pitch, yaw] rad)
    placement: tuple[list[float], list[float]] = ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0])


@dataclass
class RunContext:
    """What the runtime hands a middleware when the simulation starts."""

    poller: Poller  # every socket is polled on the loop's thread
    requests: RequestHandler  # where service requests go
    bind: str  # the address servers listen on
    output_dir: Path  # where file outputs go
    port_base: int | None = None  # --port-base
    service_port: int | None = None  # --service-port
    now: Callable[[], float] = field(default=lambda: 0.0)  # the simulated time messages are stamped with, s
    # fixed_step's loop waits, briefly, for what a client sends right after its `time sleep` ended and for
    # the first message of a client that has just connected to an actuator stream: the middleware tells
    # it of actuator stream connections (the connection object) opening, sending a message, and closing
    stream_opened: Callable[[Any], None] = field(default=lambda connection: None)
    stream_heard: Callable[[Any], None] = field(default=lambda connection: None)
    stream_closed: Callable[[Any], None] = field(default=lambda connection: None)
    # a client connected to a sensor stream: the answers to sleeps wait for its polling thread to see it
    reader_opened: Callable[[], None] = field(default=lambda: None)
    # how many frames the loop has run: actuator streams stamp their messages with it (MORSE's frame order)
    frames: Callable[[], int] = field(default=lambda: 0)


class OutStream(Protocol):
    @property
    def listening(self) -> bool: ...  # whether anyone reads: the sensor's message is built only then
    def publish(self, message: dict) -> None: ...
    def close(self) -> None: ...


class InStream(Protocol):
    def take(self, frames: int) -> dict | None: ...  # the last message to apply at the frame after `frames`
    def close(self) -> None: ...


class Lockstep(Protocol):
    """A middleware that can hold the loop: while engaged, a frame runs only when `take()` allows it."""

    @property
    def engaged(self) -> bool: ...
    def take(self) -> bool: ...


class Middleware:
    name: ClassVar[str]
    description: ClassVar[str] = ""
    # the stream options this middleware reads, beyond those every stream has (direction, topic ...): they
    # become fields of the scene's StreamSpec (with their descriptions); another middleware's are refused
    Options: ClassVar[type[BaseModel]] = BaseModel
    carries_services: ClassVar[bool] = False  # add_service(name) / add_interface(name) expose services on it
    # serves the simulation's own services (simulation, time, communication) whatever the scene says
    always_serves: ClassVar[bool] = False

    # ---- build time
    @classmethod
    def unavailable(cls) -> str | None:
        """Why this middleware cannot work on this machine (what to install), or None."""
        return None

    @classmethod
    def check_stream(cls, request: StreamRequest) -> str | None:
        """Why this middleware cannot carry this stream (no serialiser for the component ...), or None."""
        return None

    @classmethod
    def overlay_class(cls, overlay: str, types: tuple[str, ...]) -> str:
        """The importable class (module:Class) of an overlay the scene names (MORSE's class path) for a
        component of `types`; ValueError saying why when there is none."""
        raise ValueError(f"the {cls.name} middleware has no overlays")

    @classmethod
    def assign(cls, streams: list[StreamRequest]) -> list[dict[str, Any]]:
        """The endpoint of each stream (same order), recorded in the manifest; streams come sorted by component."""
        return [{} for _ in streams]

    @classmethod
    def services_endpoint(cls) -> dict[str, Any]:
        """Where services are served (only for a middleware that carries services)."""
        return {}

    # ---- run time
    def __init__(self, context: RunContext, settings: dict[str, Any]):
        """`settings`: configure_stream_manager's options for this middleware (the scene's stream_managers)."""
        self.context = context
        self.settings = settings

    def open_stream(self, component: str, direction: str, endpoint: dict[str, Any]) -> InStream | OutStream:
        raise NotImplementedError(f"middleware {self.name!r} has no streams")

    def open_services(self, endpoint: dict[str, Any]) -> None:
        raise NotImplementedError(f"middleware {self.name!r} carries no services")

    def open_overlay(self, component: str, instance: Any, overlay: str, params: dict[str, Any]) -> None:
        """Serve a component's services adapted by an overlay (`overlay`: module:Class, from overlay_class);
        `instance` is the component, for what the overlay reads of it on the loop's thread."""
        raise NotImplementedError(f"middleware {self.name!r} has no overlays")

    def services(self) -> dict[str, Any]:
        """Objects whose @service methods this middleware adds to pseudo-components ({"simulation": obj})."""
        return {}

    def lockstep(self) -> Lockstep | None:
        return None

    def flush(self) -> None:
        """Send what is queued (called every frame)."""

    def flushes(self) -> list[Callable[[], None]]:
        """What the loop calls at each of its flushes (at the end of a frame, again after its answers, and while it
        waits), asked once the endpoints are open: `flush`, or the flushes of the middleware's own servers, which
        saves a call at every flush (the socket middleware's service server; none when it serves nothing)."""
        return [self.flush]

    def answer_anytime(self) -> None:
        """Between two physics sub-steps of a frame, while a client converses: answer the requests that
        `anytime` services may answer mid-frame (ServiceInfo.anytime), on the loop's thread; nothing else."""

    def describe(self) -> list[tuple[str, str, str]]:
        """(what, direction, where) per endpoint, for the table printed at SCENE INITIALIZED."""
        return []

    def close(self) -> None:
        """Close every endpoint."""
