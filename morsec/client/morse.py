"""pymorse's API over `transport`: `Morse`, robots and components as attributes, streams, services as
futures, and the exceptions. See `morsec.client` for the overview."""

from __future__ import annotations

import json
import logging
import re
import threading
import time as _time
from collections import deque
from collections.abc import Callable, Mapping
from concurrent.futures import Future
from typing import Any

from .transport import Connection, Dispatcher, Loop

logger = logging.getLogger("morsec.client")

DETAILS_TIMEOUT = 15.0  # seconds to wait for `simulation details` (pymorse's value)
FLUSH_TIMEOUT = 5.0  # seconds close() waits for actuator messages still being sent
CANCEL_TIMEOUT = 2.0  # seconds close(cancel_async_services=True) waits for the PREEMPTED answers
KEPT_MESSAGES = 100  # messages each stream keeps for last(n), as pymorse
STREAM_METHODS = {"get": "OUT", "last": "OUT", "subscribe": "OUT", "unsubscribe": "OUT", "publish": "IN"}
QUIT_SERVICES = {("simulation", "quit"), ("simulation", "terminate")}

SUCCESS, FAILURE, PREEMPTED = "SUCCESS", "FAILED", "PREEMPTED"


# ------------------------------------------------------------------------------------------ errors
class MorseServerError(Exception):
    """Base of every error this client raises about the simulation: a service's answer, a connection
    that closed, an answer that did not come in time."""


class MorseServiceError(MorseServerError):
    """A service did not succeed. Its subclasses say how; raised as such for an unknown status.

    `component`, `service` and `request_id` name the request (None when unknown); `str(error)` is the
    simulator's message, unchanged."""

    def __init__(self, *args, component: str | None = None, service: str | None = None,
                 request_id: str | None = None):
        super().__init__(*args)
        self.component, self.service, self.request_id = component, service, request_id


class MorseServiceFailed(MorseServiceError):
    """The simulator answered FAILED: `str(error)` is its message."""


class MorseWrongArguments(MorseServiceFailed, TypeError):
    """FAILED with "wrong # of parameters": a TypeError, as in pymorse, and a MorseServiceFailed."""


class MorseServicePreempted(MorseServiceError):
    """The simulator answered PREEMPTED: the request was cancelled, or replaced by a newer one."""


class MorseConnectionError(MorseServerError, ConnectionError):
    """The connection to the simulation closed (it quit, or the client was closed) before an answer."""


class MorseTimeoutError(MorseServerError, TimeoutError):
    """No answer within the time asked for (`rpc_t`, the `simulation details` of start-up)."""


def _error_for(status: str, result: Any, request: _Request) -> MorseServerError:
    names = {"component": request.component, "service": request.service, "request_id": request.id}
    if status == FAILURE:
        message = result if isinstance(result, str) else json.dumps(result)
        if "wrong # of parameters" in message:
            return MorseWrongArguments(message, **names)
        return MorseServiceFailed(message, **names)
    if status == PREEMPTED:
        return MorseServicePreempted(f"{request} preempted" if result is None else result, **names)
    return MorseServiceError(f"unknown status {status!r} in the answer to {request}: {result!r}", **names)


# ------------------------------------------------------------------------------------------ futures
class _Request:
    __slots__ = ("id", "component", "service", "future")

    def __init__(self, request_id: str, component: str, service: str):
        self.id, self.component, self.service = request_id, component, service
        self.future: Future = Future()
        self.future.set_running_or_notify_cancel()  # sent: running until its answer

    def __str__(self) -> str:
        return f"request {self.id} ({self.component} {self.service})"


class MorseFuture:
    """The answer to a service request, to come: `concurrent.futures.Future`'s reading side.

    `result(timeout)` waits and returns the service's value or raises its error; `cancel()` asks the
    simulator to abort the request (`<id> cancel`); the answer, PREEMPTED, then makes `result()` raise
    `MorseServicePreempted`. As in pymorse, comparing, printing (`repr`) or testing the truth of a
    future waits for its result: `motion.get_status() == "Arrived"` works."""

    def __init__(self, morse: Morse, request: _Request):
        self._morse = morse
        self._request = request
        self._future = request.future

    @property
    def request_id(self) -> str:
        return self._request.id

    rqst_id = request_id  # pymorse's name

    def result(self, timeout: float | None = None) -> Any:
        return self._future.result(timeout)

    def exception(self, timeout: float | None = None) -> BaseException | None:
        return self._future.exception(timeout)

    def done(self) -> bool:
        return self._future.done()

    def running(self) -> bool:
        return not self._future.done()

    def cancelled(self) -> bool:
        """True once the simulator preempted the request."""
        return self._future.done() and isinstance(self._future.exception(), MorseServicePreempted)

    def cancel(self) -> bool:
        """Send `<id> cancel`. False (and nothing sent) when the answer is already there."""
        if self._future.done():
            return False
        self._morse.cancel(self._request.id)
        return True

    def add_done_callback(self, fn: Callable[[MorseFuture], Any]) -> None:
        """`fn(future)` once the answer is there, on the client's callback thread (at once, on that
        thread, if it is there already)."""
        dispatcher = self._morse._dispatcher
        self._future.add_done_callback(lambda _: dispatcher.post(fn, self))

    def __eq__(self, other):
        return self.result() == other

    def __ne__(self, other):
        return self.result() != other

    def __lt__(self, other):
        return self.result() < other

    def __le__(self, other):
        return self.result() <= other

    def __gt__(self, other):
        return self.result() > other

    def __ge__(self, other):
        return self.result() >= other

    def __bool__(self) -> bool:
        return bool(self.result())

    def __repr__(self) -> str:
        return repr(self.result())

    __hash__ = object.__hash__


# ------------------------------------------------------------------------------------------ streams
class Stream:
    """A component's socket stream: JSON lines in (a sensor) or out (an actuator). Connected on first use."""

    def __init__(self, morse: Morse, fqn: str, port: int, directions: frozenset[str]):
        self._morse = morse
        self.fqn = fqn
        self.port = port
        self.directions = directions
        self._connection: Connection | None = None
        self._open_lock = threading.Lock()
        self._messages: deque[bytes] = deque(maxlen=KEPT_MESSAGES)
        self._count = 0
        self._new = threading.Condition()
        self._callbacks: list[Callable[[Any], Any]] = []
        self._closed_reason: str | None = None

    def open(self) -> None:
        with self._open_lock:
            if self._connection is None:
                self._connection = self._morse._loop.open(self._morse.host, self.port, self.fqn,
                                                          self._on_line, self._on_close)

    @property
    def connection(self) -> Connection | None:
        return self._connection

    def _on_line(self, raw: bytes) -> None:  # I/O thread
        if not raw.strip():
            return
        with self._new:
            self._messages.append(raw)
            self._count += 1
            self._new.notify_all()
        if self._callbacks:
            self._morse._dispatcher.post(self._deliver, raw)

    def _on_close(self, reason: str) -> None:  # I/O thread
        with self._new:
            self._closed_reason = reason
            self._new.notify_all()

    def _deliver(self, raw: bytes) -> None:  # callback thread
        message = None
        for callback in list(self._callbacks):
            if callback not in self._callbacks:  # unsubscribed meanwhile
                continue
            if message is None:
                message = json.loads(raw)
            callback(message)

    # ---- a sensor's
    def get(self, timeout: float | None = None) -> Any:
        """The next message (the first one received after this call), or None after `timeout` seconds."""
        self.open()
        with self._new:
            seen = self._count
            if not self._new.wait_for(lambda: self._count > seen or self._closed_reason is not None, timeout):
                return None
            if self._count > seen:
                return json.loads(self._messages[-1])
            raise MorseConnectionError(f"{self.fqn}: stream closed ({self._closed_reason})")

    def last(self, n: int = 1) -> Any:
        """The last message received (None if none yet); with n > 1, a list of the last n (fewer if fewer
        came). The first call of any stream method connects: messages before it are not seen."""
        self.open()
        with self._new:
            if n > 1:
                kept = list(self._messages)[-n:]
            else:
                kept = [self._messages[-1]] if self._messages else []
        if n > 1:
            return [json.loads(raw) for raw in kept]
        return json.loads(kept[0]) if kept else None

    def subscribe(self, callback: Callable[[Any], Any]) -> None:
        """`callback(message)` for every message from now on, on the client's callback thread."""
        self.open()
        self._callbacks.append(callback)

    def unsubscribe(self, callback: Callable[[Any], Any]) -> None:
        """Stop calling `callback` (ValueError if it was not subscribed, as list.remove)."""
        self._callbacks.remove(callback)

    # ---- an actuator's
    def publish(self, message: Mapping[str, Any]) -> None:
        """Send one message: a dict of the actuator's data fields (those left out take their defaults)."""
        if not isinstance(message, Mapping):
            raise TypeError(f"{self.fqn}: publish takes a dict of the actuator's fields, got {type(message).__name__}")
        line = json.dumps(dict(message), allow_nan=False) + "\n"
        self.open()
        assert self._connection is not None
        try:
            self._connection.send(line.encode("utf-8"))
        except ConnectionError as err:
            raise MorseConnectionError(str(err)) from None

    def close(self) -> None:
        if self._connection is not None:
            self._connection.close("closed by the client")


# ------------------------------------------------------------------------------------------ components
def normalize_name(name: str) -> str:
    """A MORSE name as a Python identifier, as pymorse makes it: `.`, `-` and `~` become `_`."""
    for illegal in ".-~":
        name = name.replace(illegal, "_")
    return name


def _by_name(mapping: Mapping[str, Any], name: str) -> Any:
    if name in mapping:
        return mapping[name]
    for key, value in mapping.items():
        if normalize_name(key) == name:
            return value
    return None


class Component:
    """A component: `fqn`, `name`; its services as methods returning `MorseFuture`s; its sub-components
    as attributes; a sensor's `get`, `last`, `subscribe`, `unsubscribe`, an actuator's `publish`."""

    def __init__(self, morse: Morse, name: str, fqn: str, stream: Stream | None = None,
                 services: list[str] | tuple[str, ...] = ()):
        self._morse = morse
        self.name = name
        self.fqn = fqn
        self._stream = stream
        self._services = list(services)
        self._service_methods: dict[str, Callable[..., MorseFuture]] = {}
        self._children: dict[str, Component] = {}

    def _add_child(self, name: str, child: Component) -> None:
        self._children.setdefault(name, child)

    def _child(self, name: str) -> Component | None:
        """A sub-component by its name, or by its name made an identifier (`my-arm` as `my_arm`)."""
        return _by_name(self._children, name)

    def _stream_method(self, method: str) -> Callable:
        stream = self._stream
        if stream is None or STREAM_METHODS[method] not in stream.directions:
            raise AttributeError(method)  # then __getattr__ explains
        return getattr(stream, method)

    get = property(lambda self: self._stream_method("get"), doc="a sensor's: the next message")
    last = property(lambda self: self._stream_method("last"), doc="a sensor's: the last message")
    subscribe = property(lambda self: self._stream_method("subscribe"), doc="a sensor's: a callback per message")
    unsubscribe = property(lambda self: self._stream_method("unsubscribe"), doc="a sensor's")
    publish = property(lambda self: self._stream_method("publish"), doc="an actuator's: send a message")

    @property
    def stream(self) -> Stream | None:
        return self._stream

    def _service(self, name: str) -> Callable[..., MorseFuture]:
        method = self._service_methods.get(name)
        if method is None:
            morse, fqn = self._morse, self.fqn

            def method(*args):
                return morse.rpc_async(fqn, name, *args)

            method.__name__ = method.__qualname__ = name
            method.__doc__ = f"The MORSE service {fqn}.{name}: returns a MorseFuture."
            self._service_methods[name] = method
        return method

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__") or "_children" not in self.__dict__:
            raise AttributeError(name)
        child = self._child(name)
        if child is not None:
            return child
        if name in self._services:
            return self._service(name)
        if name in STREAM_METHODS:
            if self._stream is None:
                why = "no socket stream"
            elif STREAM_METHODS[name] == "OUT":
                why = "no outgoing data (an actuator: use publish)"
            else:
                why = "no incoming data (a sensor: use get, last or subscribe)"
            raise AttributeError(f"component {self.fqn} has {why}")
        raise AttributeError(f"component {self.fqn} has no service or sub-component {name!r} (services: "
                             f"{', '.join(self._services) or 'none'}; sub-components: "
                             f"{', '.join(sorted(set(self._children))) or 'none'})")

    def __dir__(self) -> list[str]:
        names = set(super().__dir__()) | {normalize_name(n) for n in self._children} | set(self._services)
        for method, direction in STREAM_METHODS.items():
            if self._stream is None or direction not in self._stream.directions:
                names.discard(method)
        return sorted(names)

    def close(self) -> None:
        if self._stream is not None:
            self._stream.close()

    def __repr__(self) -> str:
        return f"<component {self.fqn}>"


class Robot(dict):
    """A robot: a dict of its components by name (as in pymorse), which are also its attributes; its own
    services as methods."""

    def __init__(self, morse: Morse, name: str, services: list[str] | tuple[str, ...] = ()):
        super().__init__()
        self._component = Component(morse, name, name, None, services)
        self.name = name
        self.fqn = name

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        found = _by_name(self, name)
        if found is not None:
            return found
        component = self.__dict__.get("_component")
        if component is not None and name in component._services:
            return component._service(name)
        raise AttributeError(f"robot {self.__dict__.get('fqn')} has no component or service {name!r} "
                             f"(components: {', '.join(sorted(self)) or 'none'})")

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | {normalize_name(n) for n in self} | set(self._component._services))

    def __repr__(self) -> str:
        return f"<robot {self.fqn}: {', '.join(sorted(self))}>"

    __hash__ = object.__hash__  # type: ignore[assignment]  # a robot is itself, not its contents

    def __eq__(self, other):
        return self is other


# ------------------------------------------------------------------------------------------ the client
class Morse:
    """A connection to a MORSE simulation (`morsec run`, or MORSE itself): `Morse(host, port)`.

    Asks the simulation for its structure (`simulation details`) and builds `sim.<robot>.<component>`
    from it; see `morsec.client` for the whole API. Use it as a context manager, or call `close()`."""

    def __init__(self, host: str = "localhost", port: int = 4000):
        self.host = host
        self.port = port
        self._lock = threading.Lock()
        self._next_id = 0
        self._pending: dict[str, _Request] = {}
        self._closed = False
        self._service_closed = threading.Event()
        self._streams: list[Stream] = []
        self._robots: dict[str, Robot] = {}
        self._dispatcher = Dispatcher()
        self._loop = Loop()
        try:
            self._service = self._loop.open(host, port, "services", self._on_answer, self._on_service_closed)
            self.initialize_api()
        except BaseException:
            self._shutdown()
            raise

    # ---- discovery
    def initialize_api(self) -> None:
        """Build the robots and components from `simulation details` (done by the constructor)."""
        details = self.rpc_t(DETAILS_TIMEOUT, "simulation", "details")
        if not details:
            raise MorseServerError("simulation details not available")
        robots = details.get("robots", [])
        ports = self._stream_ports(robots)
        self.robots: list = []
        for robot_detail in robots:
            name = robot_detail["name"]
            robot = Robot(self, name, robot_detail.get("services") or ())
            self._robots[name] = robot
            attribute = normalize_name(name)
            self.robots.append(attribute)
            if hasattr(type(self), attribute):
                logger.warning("robot %r is not an attribute (Morse has a method of that name): reach it "
                               "as sim[%r]", name, name)
            else:
                setattr(self, attribute, robot)
            components = robot_detail.get("components", {})
            for fqn in sorted(components):  # parents before their children
                self._add_component(robot, fqn, components[fqn], ports)
        self._group_loop_robots()

    def _stream_ports(self, robots: list[dict]) -> dict[str, int]:
        wanted = [fqn for robot in robots for fqn, detail in robot.get("components", {}).items()
                  if detail.get("stream_interfaces")]
        if not wanted:
            return {}
        try:
            return dict(self.rpc("simulation", "get_all_stream_ports") or {})
        except MorseServiceFailed:
            pass
        ports = {}
        for fqn in wanted:  # a simulator without get_all_stream_ports: one request each, as pymorse
            try:
                ports[fqn] = self.get_stream_port(fqn)
            except MorseServiceFailed:
                pass
        return ports

    def _add_component(self, robot: Robot, fqn: str, details: dict, ports: dict[str, int]) -> None:
        path = fqn.split(".")[1:]  # the first token is the robot's name
        if not path:
            logger.error("component %r of robot %r has an invalid name", fqn, robot.name)
            return
        stream = None
        interfaces = details.get("stream_interfaces") or []
        if interfaces:
            if fqn in ports:
                directions = frozenset(entry[1] for entry in interfaces if len(entry) > 1)
                stream = Stream(self, fqn, int(ports[fqn]), directions)
                self._streams.append(stream)
            else:
                logger.info("component %s has no socket stream: no data through this client", fqn)
        component = Component(self, path[-1], fqn, stream, details.get("services") or ())
        if len(path) == 1:
            robot.setdefault(path[0], component)
            return
        parent: Any = robot.get(path[0])
        if parent is None:  # a parent that is not a component of its own
            parent = Component(self, path[0], f"{robot.name}.{path[0]}")
            robot[path[0]] = parent
        for index, part in enumerate(path[1:-1], start=1):
            child = parent._child(part)
            if child is None:
                child = Component(self, part, ".".join([robot.name, *path[: index + 1]]))
                parent._add_child(part, child)
            parent = child
        if path[-1] in parent._services:
            logger.warning("sub-component %s hides the service %s of %s: call it with sim.rpc",
                           fqn, path[-1], parent.fqn)
        parent._add_child(path[-1], component)

    def _group_loop_robots(self) -> None:
        """Robots named `x`, `x_001`, `x_002`... also as the list `sim.xs`, as pymorse does (which
        replaces `sim.robots`, the list of names, when the robots are called `robot`...)."""
        names = sorted(self.robots)
        while names:
            name = names.pop(0)
            pattern = re.compile("^" + re.escape(name) + "_[0-9]{3}$")
            family = [other for other in names if pattern.match(other)]
            if family:
                for other in family:
                    names.remove(other)
                by_attribute = {normalize_name(n): robot for n, robot in self._robots.items()}
                setattr(self, name + "s", [by_attribute[n] for n in [name, *family]])

    def __getitem__(self, name: str) -> Robot:
        """A robot by its name (or the name made an identifier): `sim["robot"]`."""
        if name in self._robots:
            return self._robots[name]
        for robot_name, robot in self._robots.items():
            if normalize_name(robot_name) == name:
                return robot
        raise KeyError(name)

    # ---- services
    def rpc_async(self, component: str, service: str, *args) -> MorseFuture:
        """Send a request; its MorseFuture. What a component's service methods do."""
        params = json.dumps(list(args))
        with self._lock:
            request = _Request(str(self._next_id), component, service)
            self._next_id += 1
            if self._closed or self._service_closed.is_set():
                error = MorseConnectionError(f"cannot send {request}: the client is closed")
                request.future.set_exception(error)
                return MorseFuture(self, request)
            self._pending[request.id] = request
        try:
            self._service.send(f"{request.id} {component} {service} {params}\n".encode())
        except ConnectionError as err:
            with self._lock:
                self._pending.pop(request.id, None)
            request.future.set_exception(MorseConnectionError(f"cannot send {request}: {err}"))
        return MorseFuture(self, request)

    def rpc(self, component: str, service: str, *args) -> Any:
        """Call a service and wait for its result (or its error)."""
        return self.rpc_async(component, service, *args).result()

    def rpc_t(self, timeout: float | None, component: str, service: str, *args) -> Any:
        """`rpc` waiting at most `timeout` seconds: MorseTimeoutError after that."""
        future = self.rpc_async(component, service, *args)
        try:
            return future.result(timeout)
        except TimeoutError:
            if future.done():
                raise
            raise MorseTimeoutError(f"no answer to {component} {service} from {self.host}:{self.port} within "
                                    f"{timeout} s") from None

    def cancel(self, service_id: str | int) -> None:
        """Ask the simulation to abort a running request (`<id> cancel`); ignored if it is not running."""
        try:
            self._service.send(f"{service_id} cancel\n".encode())
        except ConnectionError:
            pass

    def _on_answer(self, raw: bytes) -> None:  # I/O thread
        text = raw.decode("utf-8", "replace").strip()
        if not text:
            return
        parts = text.split(" ", 2)
        if len(parts) < 2:
            logger.error("not an answer from the simulation: %r", text[:200])
            return
        request_id, status = parts[0], parts[1]
        result = None
        if len(parts) == 3:
            try:
                result = json.loads(parts[2])
            except ValueError:
                result = parts[2]
        with self._lock:
            request = self._pending.pop(request_id, None)
        if request is None:
            logger.debug("answer to no pending request: %r", text[:200])
            return
        if status == SUCCESS:
            request.future.set_result(result)
        else:
            request.future.set_exception(_error_for(status, result, request))

    def _on_service_closed(self, reason: str) -> None:  # I/O thread
        self._service_closed.set()
        with self._lock:
            pending, self._pending = self._pending, {}
        for request in pending.values():
            if (request.component, request.service) in QUIT_SERVICES:
                request.future.set_result(None)  # the simulation went away as asked
            else:
                request.future.set_exception(MorseConnectionError(
                    f"no answer to {request}: the connection to {self.host}:{self.port} closed ({reason})"))

    def is_up(self) -> bool:
        """True while the service connection is open."""
        return not self._service_closed.is_set()

    # ---- the simulation
    def sleep(self, seconds: float) -> None:
        """Wait `seconds` of simulated time (`time sleep`)."""
        return self.rpc("time", "sleep", seconds)

    def time(self) -> float:
        """The simulated time, seconds since the epoch (`time now`); 0.0 at the start of a relative-time run,
        whose answer, as MORSE's, leaves the falsy result out."""
        return self.rpc("time", "now") or 0.0

    def reset(self) -> Any:
        return self.rpc("simulation", "reset_objects")

    def streams(self) -> list[str]:
        return self.rpc("simulation", "list_streams")

    def get_stream_port(self, stream: str) -> int:
        return self.rpc("simulation", "get_stream_port", stream)

    def activate(self, component: str) -> Any:
        return self.rpc("simulation", "activate", component)

    def deactivate(self, component: str) -> Any:
        return self.rpc("simulation", "deactivate", component)

    def quit(self) -> None:
        """End the simulation (`simulation quit`), then close this client."""
        try:
            self.rpc("simulation", "quit")
        finally:
            self.close()

    def spin(self, timeout: float | None = None) -> bool:
        """Wait until the simulation closes the connection (True) or `timeout` seconds passed (False)."""
        return self._service_closed.wait(timeout)

    # ---- closing
    def close(self, cancel_async_services: bool = False, wait_publishers: bool = True) -> None:
        """Close the connections and end this client's threads; safe to call twice.

        As in pymorse it first waits until the messages published to actuators are sent
        (`wait_publishers`, up to 5 s) and then for the answers of the requests still running — or,
        with `cancel_async_services`, cancels them (the `with` block does so when it ends on an
        exception), waiting up to 2 s for their PREEMPTED."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
        try:
            if wait_publishers:
                deadline = _time.monotonic() + FLUSH_TIMEOUT
                for stream in self._streams:
                    if stream.connection is not None:
                        stream.connection.flush(max(0.0, deadline - _time.monotonic()))
            with self._lock:
                running = list(self._pending.values())
            if cancel_async_services:
                for request in running:
                    self.cancel(request.id)
                deadline = _time.monotonic() + CANCEL_TIMEOUT
                for request in running:
                    try:
                        request.future.exception(max(0.0, deadline - _time.monotonic()))
                    except TimeoutError:
                        pass
            else:
                for request in running:
                    request.future.exception()  # waits; a closing connection answers every request
        finally:
            self._shutdown()

    def _shutdown(self) -> None:
        self._closed = True
        self._loop.stop()
        with self._lock:
            pending, self._pending = self._pending, {}
        for request in pending.values():
            if not request.future.done():
                request.future.set_exception(MorseConnectionError(f"{request}: the client was closed"))
        self._dispatcher.stop()

    @property
    def threads(self) -> list[threading.Thread]:
        """This client's threads still alive (none after close())."""
        return [t for t in (self._loop.thread, self._dispatcher.thread) if t is not None and t.is_alive()]

    def __enter__(self) -> Morse:
        return self

    def __exit__(self, exc_type, exc_value, traceback) -> None:
        self.close(cancel_async_services=exc_type is not None)

    def __repr__(self) -> str:
        state = "closed" if self._closed else "open"
        return f"<Morse {self.host}:{self.port} {state}: robots {', '.join(self._robots) or 'none'}>"

