"""`morsec replay run.mcap`: a recording's sensor streams served again on MORSE's socket protocol, for clients to
be tested against a fixed input.

The recording says what the scene was (`morsec` metadata: `simulation details`, the build's streams): each
recorded sensor stream is served on a socket stream, on the port the scene's socket stream had (others on
free ports from 60000), its JSON messages sent in simulated-time order at the recorded pace times `rate`; the
actuator streams the scene had on sockets accept clients and ignore what they send. The service port answers
what a client asks on connecting and while it reads: `simulation details`, the stream ports, `quit`,
`terminate`, `time now` and `time sleep` (in the recording's time). A client written for the simulation
(pymorse, morsec.client) connects unchanged and reads what was recorded; the components' own services are
not served (nothing runs)."""

from __future__ import annotations

import heapq
import json
import time
from dataclasses import dataclass
from itertools import count
from pathlib import Path
from typing import Any

from morsec.component.services import SUCCESS, async_service, service
from morsec.constants import DEFAULT_BIND, SERVICE_PORT, STREAM_PORT_BASE
from morsec.errors import MorsecError, RuntimeFailure
from morsec.middleware.base import RunContext
from morsec.middleware.poller import Poller
from morsec.middleware.socket import Socket
from morsec.runtime.requests import RequestManager, concurrent, services_of

POLL = 0.05  # s: the longest wait between two looks at the sockets


@dataclass
class ReplayOptions:
    rate: float = 1.0  # recorded (simulated) seconds per wall-clock second
    bind: str = DEFAULT_BIND
    service_port: int | None = None
    port_base: int | None = None
    wait_for_client: bool = False  # start with the first client's request or stream connection


@dataclass
class Recorded:
    """What a recording says of its scene."""

    details: dict[str, Any]  # `simulation details` as the simulation answered it
    streams: list[dict[str, Any]]  # the build's streams: component, direction, middleware, endpoint
    sensors: list[str]  # the components whose messages the file holds (JSON channels of sensor streams)
    start: int  # ns, the first message's log time
    end: int
    count: int  # messages to replay


def read_recording(path: Path) -> Recorded:
    """The scene a recording was made of; MorsecError (one line) for a file that is not a morsec recording."""
    from mcap.exceptions import McapError
    from mcap.reader import make_reader
    try:
        with open(path, "rb") as f:
            reader = make_reader(f)
            summary = reader.get_summary()
            metadata = next((m.metadata for m in reader.iter_metadata() if m.name == "morsec"), None)
    except OSError as err:
        raise MorsecError(f"{path}: {err.strerror or err}") from None
    except (McapError, ValueError, EOFError) as err:
        raise MorsecError(f"{path}: not a readable MCAP file ({err})") from None
    if metadata is None or summary is None:
        raise MorsecError(f"{path}: not a recording made by `morsec run --record` (no morsec metadata)")
    streams = json.loads(metadata["streams"])
    directions = {(s["component"], s["direction"]) for s in streams}
    sensors = sorted({c.topic for c in summary.channels.values() if c.message_encoding == "json"
                      and (c.topic, "OUT") in directions})
    counts = summary.statistics.channel_message_counts if summary.statistics else {}
    number = sum(n for cid, n in counts.items() if summary.channels[cid].topic in sensors)
    stats = summary.statistics
    return Recorded(json.loads(metadata["details"]), streams, sensors, stats.message_start_time if stats else 0,
                    stats.message_end_time if stats else 0, number)


def describe_recording(path: Path) -> str:
    """What `morsec replay --info` prints: the time span, and each channel with its schema and message count."""
    from mcap.reader import make_reader
    recorded = read_recording(path)  # a file that is not a recording: one line
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        metadata = next(m.metadata for m in reader.iter_metadata() if m.name == "morsec")
    assert summary is not None and summary.statistics is not None
    counts = summary.statistics.channel_message_counts
    origin = ("since the start" if metadata.get("time_origin") == "start" else
              "since the Unix epoch, the clock starting at the wall-clock time of the start")
    lines = [f"{path}: {summary.statistics.message_count} messages over {(recorded.end - recorded.start) / 1e9:.3f} "
             f"simulated s, recorded by morsec {metadata['version']} (log times: simulated time {origin})"]
    width = max(len(c.topic) for c in summary.channels.values())
    for channel in sorted(summary.channels.values(), key=lambda c: c.topic):
        schema = summary.schemas[channel.schema_id]
        lines.append(f"  {channel.topic:<{width}}  {counts.get(channel.id, 0):>7}  {channel.message_encoding:<4}  "
                     f"{schema.name} ({schema.encoding})")
    return "\n".join(lines)


class Replay:
    def __init__(self, path: Path, options: ReplayOptions | None = None):
        self.path = Path(path)
        self.options = options or ReplayOptions()
        if not self.options.rate > 0:
            raise MorsecError(f"--rate must be a positive number, got {self.options.rate}")
        self.recorded = read_recording(self.path)
        self.now = self.recorded.start / 1e9  # the recording's time: where the replay is
        self.quitting = False
        self.client_came = not self.options.wait_for_client
        self.poller = Poller()
        self.requests = RequestManager()
        self.requests.on_request.append(self._client_request)
        opts = self.options
        context = RunContext(self.poller, self.requests, opts.bind, Path.cwd(), opts.port_base, opts.service_port,
                             now=lambda: self.now, stream_opened=self._client_stream,
                             reader_opened=lambda: self._client_stream(None))
        self.socket = Socket(context, {})
        self.time = ReplayTime(self)
        try:
            self.streams = self._open_streams()
            self.socket.open_services({"port": SERVICE_PORT})
        except OSError as err:
            self.close()
            raise RuntimeFailure(f"cannot open the replay's sockets on {opts.bind}: {err.strerror or err}") from None
        except MorsecError:
            self.close()
            raise
        for name, obj in (("simulation", ReplaySupervision(self)), ("time", self.time)):
            self.requests.expose(name, obj, services_of(obj))
        for name, obj in self.socket.services().items():
            self.requests.expose_more(name, obj, services_of(obj))

    def _open_streams(self) -> dict[str, list]:
        """A socket stream per recorded sensor stream and per socket actuator stream of the scene."""
        socket = [s for s in self.recorded.streams if s["middleware"] == "socket"]
        wanted = {(s["component"], s["direction"]): s["endpoint"] for s in socket
                  if s["direction"] == "IN" or s["component"] in self.recorded.sensors}
        used = {e["port"] for e in wanted.values()}
        free = (port for port in count(STREAM_PORT_BASE) if port not in used)
        for component in self.recorded.sensors:
            if (component, "OUT") not in wanted:  # recorded from a ROS or text stream: a port of its own
                wanted[(component, "OUT")] = {"port": next(free), "explicit_port": False}
        streams: dict[str, list] = {}
        for (component, direction), endpoint in sorted(wanted.items()):
            streams.setdefault(component, []).append(self.socket.open_stream(component, direction, endpoint))
        return streams

    def details(self) -> dict[str, Any]:
        """The recorded scene's structure, as served here: the socket streams, no component services."""
        directions: dict[str, list[str]] = {}
        for component, streams in self.streams.items():
            directions[component] = [s.direction for s in streams]
        robots = []
        for robot in self.recorded.details.get("robots", []):
            components = {}
            for fqn, entry in robot.get("components", {}).items():
                served = {"type": entry.get("type", "")}
                if fqn in directions:
                    served["stream_interfaces"] = [["morsec.middleware.socket", d] for d in directions[fqn]]
                components[fqn] = served
            robots.append({"name": robot["name"], "type": robot.get("type", ""), "components": components})
        return {"robots": robots, "environment": self.recorded.details.get("environment", "")}

    # ---- clients
    def _client_request(self, request) -> None:
        self.client_came = True

    def _client_stream(self, connection) -> None:
        self.client_came = True

    # ---- the replay
    def announce(self, out) -> None:
        r = self.recorded
        lines = [f"REPLAYING {self.path}: {r.count} messages of {len(r.sensors)} sensor streams, "
                 f"{(r.end - r.start) / 1e9:.3f} simulated s at {self.options.rate:g}x", "SCENE INITIALIZED"]
        bind = self.options.bind
        rows = self.socket.describe()
        lines += [f"  {what:<14} {where}" for what, direction, where in rows if not direction]
        width = max([len(what) for what, direction, _ in rows if direction] + [10])
        lines += [f"  {what:<{width}}  {direction:<3}  socket  {where}" for what, direction, where in rows if direction]
        if not self.client_came:
            lines.append(f"  waiting for a client on {bind}")
        out.write("\n".join(lines) + "\n")
        out.flush()

    def run(self) -> tuple[int, int]:
        """Replay the whole recording (or until `simulation quit`); (messages replayed, messages sent to clients)."""
        from mcap.reader import make_reader
        try:
            while not self.client_came and not self.quitting:
                self._poll(POLL)
            replayed = sent = 0
            start_wall = time.perf_counter()
            with open(self.path, "rb") as f:
                for _, channel, message in make_reader(f).iter_messages(topics=self.recorded.sensors,
                                                                        log_time_order=True):
                    due = start_wall + (message.log_time - self.recorded.start) / 1e9 / self.options.rate
                    while not self.quitting and (left := due - time.perf_counter()) > 0:
                        self._poll(min(left, POLL))
                    if self.quitting:
                        break
                    self.now = message.log_time / 1e9
                    replayed += 1
                    self.time.wake()
                    for stream in self.streams.get(channel.topic, ()):
                        if stream.direction == "OUT" and stream.listening:
                            stream.publish(json.loads(message.data))
                            sent += 1
                    self.socket.flush()
            self.now = self.recorded.end / 1e9
            self.time.wake(every=True)
            self._poll(0.0)
            return replayed, sent
        finally:
            self.close()

    def _poll(self, timeout: float) -> None:
        self.poller.poll(timeout)
        self.socket.flush()

    def close(self) -> None:
        self.socket.close()
        self.poller.close()


class ReplaySupervision:
    """The `simulation` services a client asks while it reads a replay."""

    def __init__(self, replay: Replay):
        self.replay = replay

    @service
    def details(self) -> dict:
        return self.replay.details()

    @service
    def list_robots(self) -> list[str]:
        return [r["name"] for r in self.replay.details()["robots"]]

    @service
    def quit(self) -> None:
        self.replay.quitting = True

    @service
    def terminate(self) -> None:
        self.replay.quitting = True


class ReplayTime:
    """`time now` and `time sleep` in the recording's time: a sleep ends when the replay reaches its end."""

    def __init__(self, replay: Replay):
        self.replay = replay
        self.sleeping: list[tuple[float, int, Any]] = []  # (deadline, order, request)
        self.order = count()

    @service
    def now(self) -> float:
        return self.replay.now

    @async_service
    @concurrent
    def sleep(self, time: float) -> None:
        request = self.replay.requests.current
        heapq.heappush(self.sleeping, (self.replay.now + float(time), next(self.order), request))

    def wake(self, every: bool = False) -> None:
        while self.sleeping and (every or self.sleeping[0][0] <= self.replay.now + 1e-9):
            _, _, request = heapq.heappop(self.sleeping)
            self.replay.requests.complete("time", SUCCESS, None, request)

    def interrupt(self) -> None:
        """A sleep cancelled (`cancel`): the request manager answers it; it is forgotten at its deadline."""

    def abandoned(self, requests) -> None:
        gone = set(map(id, requests))
        self.sleeping = [entry for entry in self.sleeping if id(entry[2]) not in gone]
        heapq.heapify(self.sleeping)
