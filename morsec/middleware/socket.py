"""MORSE's socket middleware: a TCP server per stream (JSON lines), the service port (`id component service
[args]`), the optional lockstep port, and the `simulation` services that tell clients the stream ports."""

from __future__ import annotations

from collections.abc import Callable
from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field

from morsec.component.services import service
from morsec.constants import MAX_PORT, SERVICE_PORT, SERVICE_PORT_ATTEMPTS, STREAM_PORT_BASE
from morsec.errors import MorsecError
from morsec.middleware.base import Lockstep, Middleware, StreamRequest
from morsec.middleware.socket_services import ServiceServer
from morsec.middleware.socket_streams import SocketStream
from morsec.middleware.sync import SyncServer


class Socket(Middleware):
    name = "socket"
    description = "MORSE's socket protocol: JSON lines on a TCP port per stream, services on port 4000"

    class Options(BaseModel):
        model_config = ConfigDict(defer_build=True)  # read by a build, not by a run
        port: Annotated[int, Field(ge=1, le=65535)] | None = Field(
            None, description="socket: TCP port (default: allocated from 60000 in alphabetical order of names)")

    carries_services = True
    always_serves = True  # MORSE: the socket service port is always open

    @classmethod
    def assign(cls, streams: list[StreamRequest]) -> list[dict[str, Any]]:
        """Ports from 60000 in the order of the streams (alphabetical by component), skipping ports the scene
        gave explicitly."""
        explicit = {s.options["port"] for s in streams if s.options.get("port")}
        next_port = STREAM_PORT_BASE
        endpoints = []
        for stream in streams:
            if stream.options.get("port"):
                endpoints.append({"port": stream.options["port"], "explicit_port": True})
                continue
            while next_port in explicit:
                next_port += 1
            endpoints.append({"port": next_port, "explicit_port": False})
            next_port += 1
        return endpoints

    @classmethod
    def services_endpoint(cls) -> dict[str, Any]:
        return {"port": SERVICE_PORT}

    def __init__(self, context, settings):
        super().__init__(context, settings)
        self.streams: dict[str, list[SocketStream]] = {}
        self.server: ServiceServer | None = None
        self.sync: SyncServer | None = None
        if settings.get("time_sync"):
            # --port-base 0: every server on a port the OS picks, the lockstep port too (runs side by side)
            port = 0 if context.port_base == 0 else settings["sync_port"]
            self.sync = SyncServer(context.poller, context.bind, port)

    def open_stream(self, component: str, direction: str, endpoint: dict[str, Any]) -> SocketStream:
        port, base = endpoint["port"], self.context.port_base
        if base == 0:  # every stream on a port the OS picks (tests, throwaway runs)
            port = 0
        elif base is not None and not endpoint["explicit_port"]:
            port = base + (port - STREAM_PORT_BASE)
            if port > MAX_PORT:
                raise MorsecError(f"--port-base {base} puts the stream of {component} on port {port}, beyond "
                                  f"{MAX_PORT}: choose a lower --port-base")
        stream = SocketStream(self.context.poller, component, direction, self.context.bind, port, hint_only=True,
                              context=self.context)
        self.streams.setdefault(component, []).append(stream)
        return stream

    def open_services(self, endpoint: dict[str, Any]) -> None:
        chosen = self.context.service_port
        port = chosen if chosen is not None else endpoint["port"]
        attempts = 1 if chosen is not None else SERVICE_PORT_ATTEMPTS + 1
        self.server = ServiceServer(self.context.poller, self.context.requests, self.context.bind, port, attempts)

    def services(self) -> dict[str, Any]:
        return {"simulation": StreamPorts(self)}

    def lockstep(self) -> Lockstep | None:
        return self.sync

    def flush(self) -> None:
        if self.server is not None:
            self.server.flush()

    def flushes(self) -> list[Callable[[], None]]:
        # the service server's own flush, not `flush` (a subclass overriding `flush` overrides this too)
        return [self.server.flush] if self.server is not None else []

    def answer_anytime(self) -> None:
        if self.server is not None:
            self.server.answer_anytime()

    def describe(self) -> list[tuple[str, str, str]]:
        bind = self.context.bind
        rows = []
        if self.server is not None:
            rows.append(("services", "", f"{bind}:{self.server.port}"))
        if self.sync is not None:
            rows.append(("lockstep", "", f"{bind}:{self.sync.port}"))
        for component, streams in sorted(self.streams.items()):
            rows += [(component, s.direction, f"{bind}:{s.port}") for s in streams]
        return rows

    def ports(self) -> dict[str, int]:
        """The port of each component's (first) stream, as the `simulation` services report them."""
        return {component: streams[0].port for component, streams in sorted(self.streams.items())}

    def close(self) -> None:
        for streams in self.streams.values():
            for stream in streams:
                stream.close()
        self.streams = {}
        for server in (self.server, self.sync):
            if server is not None:
                server.close()
        self.server = self.sync = None


class StreamPorts:
    """MORSE's socket services of the `simulation` component (its SocketDatastreamManager's)."""

    def __init__(self, socket: Socket):
        self.socket = socket

    @service(anytime=True)
    def list_streams(self) -> list[str]:
        return sorted(self.socket.ports())

    @service(anytime=True)
    def get_stream_port(self, name: str) -> int:
        ports = self.socket.ports()
        if name not in ports:
            raise ValueError(f"Stream unavailable for component {name}")
        return ports[name]

    @service(anytime=True)
    def get_all_stream_ports(self) -> dict:
        return self.socket.ports()
