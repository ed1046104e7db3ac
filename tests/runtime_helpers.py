"""Shared helpers for the runtime tests: run `morsec run` as a user would (a subprocess), on ports that
are free, and talk to it over raw sockets.

    with Morsec(scene_file(tmp_path, scene(robot())), tmp_path) as sim:   # waits for SCENE INITIALIZED
        client = sim.client()
        assert client.call("simulation", "list_robots") == ("SUCCESS", ["robot"])
        sim.stream("robot.pose").line()                              # one JSON line of the pose stream

Every process is stopped (SIGTERM, then SIGKILL) when the block ends, whatever happens in it.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import queue
import random
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import yaml

from morsec.kits.ground_friction import ground_friction, slide

MORSEC = Path(sys.executable).with_name("morsec")
READY = "SCENE INITIALIZED"
HOST = "127.0.0.1"
START_TIMEOUT = 90.0  # building and starting a scene on a loaded machine

# ------------------------------------------------------------------------------------------- ports
# Listening ports are picked below the Linux ephemeral range (32768+), where client sockets of other
# processes live, and checked free by binding them.
_PORT_LOW, _PORT_HIGH = 20000, 32000
_taken: set[int] = set()  # handed out by this process already
_rng = random.Random(os.getpid() ^ int(time.time() * 1000))


def port_free(port: int, host: str = HOST) -> bool:
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        sock.bind((host, port))
    except OSError:
        return False
    finally:
        sock.close()
    return True


def free_ports(count: int = 1) -> int:
    """The first of `count` consecutive free ports, none handed out before by this process."""
    for _ in range(2000):
        base = _rng.randrange(_PORT_LOW, _PORT_HIGH - count)
        block = range(base, base + count)
        if any(p in _taken for p in block):
            continue
        if all(port_free(p) for p in block):
            _taken.update(block)
            return base
    raise RuntimeError("no block of free ports found")


def free_port() -> int:
    return free_ports(1)


def occupy(port: int, host: str = HOST) -> socket.socket:
    """A listening socket holding `port` (close it to free the port)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.bind((host, port))
    sock.listen(1)
    return sock


# ------------------------------------------------------------------------------------------- scenes
def pose_sensor(name: str = "pose", **extra) -> dict:
    """A pose sensor at ground level on an ATRV (its origin is 0.1 m up), with a socket stream."""
    return {"name": name, "type": "pose", "translate": [0.0, 0.0, -0.1], "streams": ["socket"], **extra}


def robot(name: str = "robot", *components: dict, **extra) -> dict:
    """An ATRV with pose and motion_vw (socket stream and services) unless components are given."""
    if not components:
        components = (pose_sensor(), {"name": "motion", "type": "motion_vw", "streams": ["socket"],
                                      "services": ["socket"]})
    return {"name": name, "type": "atrv", "components": list(components), **extra}


def scene(*robots: dict, strategy: str = "fixed_step", frequency: float = 60.0, objects: list | None = None,
          environment: dict | None = None) -> dict:
    env = {"name": "empty", "time": {"strategy": strategy, "frequency": frequency}}
    for key, value in (environment or {}).items():
        if key == "time":
            env["time"].update(value)
        else:
            env[key] = value
    out: dict[str, Any] = {"environment": env, "robots": list(robots) or [robot()]}
    if objects:
        out["objects"] = objects
    return out


def scene_file(folder: Path, content: dict | None = None, name: str = "scene") -> Path:
    path = Path(folder) / f"{name}.yaml"
    path.write_text(yaml.safe_dump(content if content is not None else scene(), sort_keys=False))
    return path


def build_folder(scene_path: Path, out: Path) -> Path:
    """`morsec build scene_path -o out`, in this process."""
    from morsec.app.project import build_scene
    return build_scene(Path(scene_path), Path(out))


# ------------------------------------------------------------------------------------------- clients
class LineSocket:
    """A blocking TCP client reading newline-terminated lines with a timeout."""

    def __init__(self, port: int, host: str = HOST, timeout: float = 10.0):
        self.sock = socket.create_connection((host, port), timeout=timeout)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.timeout = timeout
        self.buffer = b""

    def send(self, data: bytes | str) -> None:
        self.sock.sendall(data.encode() if isinstance(data, str) else data)

    def raw_line(self, timeout: float | None = None) -> bytes:
        """The next line, with its newline."""
        deadline = time.monotonic() + (timeout if timeout is not None else self.timeout)
        while b"\n" not in self.buffer:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError(f"no complete line within the timeout (have {self.buffer[:200]!r})")
            self.sock.settimeout(remaining)
            try:
                chunk = self.sock.recv(65536)
            except TimeoutError:
                continue
            if not chunk:
                raise ConnectionError(f"connection closed by the server (have {self.buffer[:200]!r})")
            self.buffer += chunk
        line, _, self.buffer = self.buffer.partition(b"\n")
        return line + b"\n"

    def line(self, timeout: float | None = None) -> str:
        return self.raw_line(timeout).decode("utf-8").rstrip("\n")

    def json(self, timeout: float | None = None) -> Any:
        return json.loads(self.raw_line(timeout))

    def drain(self) -> None:
        """Forget what is buffered or waiting on the socket now."""
        self.buffer = b""
        self.sock.setblocking(False)
        try:
            while self.sock.recv(65536):
                pass
        except (BlockingIOError, InterruptedError):
            pass
        finally:
            self.sock.setblocking(True)
            self.sock.settimeout(self.timeout)

    def close(self) -> None:
        with contextlib.suppress(OSError):
            self.sock.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class ServiceClient(LineSocket):
    """The socket service protocol: `id component service [json]` -> `id STATUS[ json]`."""

    def __init__(self, port: int, host: str = HOST, timeout: float = 15.0):
        super().__init__(port, host, timeout)
        self.next_id = 0

    def new_id(self) -> str:
        self.next_id += 1
        return f"r{self.next_id}"

    def send_request(self, component: str, service: str, *args, request_id: str | None = None) -> str:
        request_id = request_id or self.new_id()
        params = f" {json.dumps(list(args))}" if args else ""
        self.send(f"{request_id} {component} {service}{params}\n")
        return request_id

    def response(self, request_id: str | None = None, timeout: float | None = None) -> tuple[str, str, Any]:
        """(id, status, result) of the next response (of `request_id`: others are skipped)."""
        while True:
            line = self.line(timeout)
            rid, status, result = parse_response(line)
            if request_id is None or rid == request_id:
                return rid, status, result

    def call(self, component: str, service: str, *args, timeout: float | None = None) -> tuple[str, Any]:
        """(status, result) of a request, waiting for its answer."""
        request_id = self.send_request(component, service, *args)
        _, status, result = self.response(request_id, timeout)
        return status, result

    def ok(self, component: str, service: str, *args, timeout: float | None = None) -> Any:
        status, result = self.call(component, service, *args, timeout=timeout)
        assert status == "SUCCESS", f"{component} {service} {list(args)}: {status} {result!r}"
        return result


def parse_response(line: str) -> tuple[str, str, Any]:
    parts = line.split(" ", 2)
    assert len(parts) >= 2, f"not a response line: {line!r}"
    result = json.loads(parts[2]) if len(parts) == 3 else None
    return parts[0], parts[1], result


# ------------------------------------------------------------------------------------------- process
class Morsec:
    """A `morsec run` subprocess on free ports (a given service port and stream port base)."""

    def __init__(self, scene_path: Path, workdir: Path, *, args: tuple | list = (), service_port: int | str | None = None,
                 port_base: int | None = None, strategy: str | None = None, cwd: Path | None = None,
                 build: Path | None = None, host: str = HOST, prebuild: bool = True):
        """service_port: a port, None (a free one is picked) or "auto" (no --service-port: 4000, 4001 ...).
        prebuild: build the scene here (the compiler's start-up is paid once per test session) and run
        the build folder (`morsec run build/x`); else `morsec run scene.yaml -o build/x`."""
        self.scene_path = Path(scene_path)
        self.workdir = Path(workdir)
        self.host = host
        self.port_base = port_base if port_base is not None else free_ports(20)
        self.cwd = Path(cwd) if cwd else self.workdir
        self.build = Path(build) if build else self.workdir / f"build-{self.scene_path.stem}"
        if self.scene_path.is_dir():  # a build folder: run it as it is
            self.build = self.scene_path
            command = [str(MORSEC), "run", str(self.build)]
        elif prebuild:
            build_folder(self.scene_path, self.build)
            command = [str(MORSEC), "run", str(self.build)]
        else:
            command = [str(MORSEC), "run", str(self.scene_path), "-o", str(self.build)]
        command += ["--port-base", str(self.port_base)]
        if service_port == "auto":
            self.service_port = None  # known from the table
        else:
            self.service_port = service_port or free_port()
            command += ["--service-port", str(self.service_port)]
        if strategy:
            command += ["--time-strategy", strategy]
        self.command = command + [str(a) for a in args]
        self.proc: subprocess.Popen | None = None
        self.stdout: list[str] = []
        self.stderr: list[str] = []
        self._lines: queue.Queue = queue.Queue()
        self.streams: dict[str, tuple[str, int]] = {}  # fqn -> (direction, port) of socket streams
        self.text_files: list[tuple[str, Path]] = []  # (fqn, file) of text streams
        self.sync_port: int | None = None
        self.announced_service_port: int | None = None
        self.seen_at: dict[str, float] = {}  # stdout line -> time.monotonic() when first read
        self.eof_at: float | None = None

    # ---- lifecycle
    def start(self) -> Morsec:
        env = dict(os.environ, PYTHONUNBUFFERED="1")
        self.proc = subprocess.Popen(self.command, cwd=self.cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, env=env, start_new_session=True)
        threading.Thread(target=self._pump, args=(self.proc.stdout, self.stdout, True), daemon=True).start()
        threading.Thread(target=self._pump, args=(self.proc.stderr, self.stderr, False), daemon=True).start()
        return self

    def _pump(self, pipe, sink: list[str], forward: bool) -> None:
        for line in pipe:
            sink.append(line.rstrip("\n"))
            if forward:
                self.seen_at.setdefault(line.strip(), time.monotonic())
                self._lines.put(line.rstrip("\n"))
        if forward:
            self.eof_at = time.monotonic()  # the process closed its stdout: it is exiting
            self._lines.put(None)

    def wait_ready(self, timeout: float = START_TIMEOUT) -> Morsec:
        deadline = time.monotonic() + timeout
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                self.stop()
                raise TimeoutError(f"morsec did not start within {timeout}s: {self.output()}")
            try:
                line = self._lines.get(timeout=remaining)
            except queue.Empty:
                continue
            if line is None:
                self.proc.wait(10)
                raise RuntimeError(f"morsec exited ({self.proc.returncode}) before {READY}: {self.output()}")
            if line.strip() == READY:
                break
        # the table is written in the same write as the ready line
        while True:
            try:
                line = self._lines.get(timeout=0.3)
            except queue.Empty:
                break
            if line is None or not line.startswith("  "):
                break
            self._parse_table_line(line)
        if self.service_port is None:
            self.service_port = self.announced_service_port
        assert self.announced_service_port == self.service_port, self.output()
        return self

    def _parse_table_line(self, line: str) -> None:
        parts = line.split()
        if parts[0] == "services":
            self.announced_service_port = int(parts[1].rsplit(":", 1)[1])
        elif parts[0] == "lockstep":
            self.sync_port = int(parts[1].rsplit(":", 1)[1])
        elif len(parts) >= 4 and parts[2] == "socket":
            self.streams[parts[0]] = (parts[1], int(parts[3].rsplit(":", 1)[1]))
        elif len(parts) >= 4 and parts[2] == "text":
            self.text_files.append((parts[0], Path(parts[3])))

    def __enter__(self) -> Morsec:
        self.start()
        try:
            return self.wait_ready()
        except BaseException:
            self.stop()
            raise

    def __exit__(self, *exc) -> None:
        self.stop()

    @property
    def pid(self) -> int:
        return self.proc.pid

    def alive(self) -> bool:
        return self.proc is not None and self.proc.poll() is None

    def signal(self, sig: int) -> None:
        self.proc.send_signal(sig)

    def wait(self, timeout: float = 30.0) -> int:
        return self.proc.wait(timeout)

    def stop(self, timeout: float = 15.0) -> int | None:
        """SIGTERM (a clean shutdown), then SIGKILL; the exit code."""
        if self.proc is None:
            return None
        if self.proc.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                with contextlib.suppress(ProcessLookupError):
                    self.proc.kill()
                self.proc.wait(10)
        return self.proc.returncode

    def output(self) -> str:
        time.sleep(0.05)
        return "\nstdout:\n" + "\n".join(self.stdout[-40:]) + "\nstderr:\n" + "\n".join(self.stderr[-40:])

    # ---- clients
    def client(self, timeout: float = 15.0) -> ServiceClient:
        return ServiceClient(self.service_port, self.host, timeout=timeout)

    def port(self, fqn: str) -> int:
        return self.streams[fqn][1]

    def stream(self, fqn: str, timeout: float = 10.0) -> LineSocket:
        return LineSocket(self.port(fqn), self.host, timeout=timeout)

    def request(self, line: str, timeout: float = 15.0) -> str:
        """One raw request line on a fresh connection, its raw response line."""
        with LineSocket(self.service_port, self.host, timeout=timeout) as sock:
            sock.send(line if line.endswith("\n") else line + "\n")
            return sock.line()

    def fd_count(self) -> int:
        return len(os.listdir(f"/proc/{self.pid}/fd"))


def stop_all(*sims: Morsec) -> None:
    """Stop several simulations at once (their shutdowns overlap)."""
    for sim in sims:
        if sim.alive():
            with contextlib.suppress(ProcessLookupError):
                sim.signal(signal.SIGTERM)
    for sim in sims:
        sim.stop()


def start_all(*sims: Morsec) -> tuple[Morsec, ...]:
    """Start several simulations at once (their start-ups overlap) and wait until all are ready."""
    try:
        for sim in sims:
            sim.start()
        for sim in sims:
            sim.wait_ready()
    except BaseException:
        stop_all(*sims)
        raise
    return sims


def run_many(commands: list[list[str]], cwd: Path, timeout: float = 120.0) -> list[subprocess.CompletedProcess]:
    """Run commands side by side until they exit; their CompletedProcess, in order."""
    procs = [subprocess.Popen(c, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in commands]
    results = []
    try:
        for command, proc in zip(commands, procs):
            out, err = proc.communicate(timeout=timeout)
            results.append(subprocess.CompletedProcess(command, proc.returncode, out, err))
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait(10)
    return results


# ------------------------------------------------------------------------------------------- geometry
def wrap(angle: float) -> float:
    return (angle + math.pi) % (2 * math.pi) - math.pi


def wait_until(predicate, timeout: float = 10.0, interval: float = 0.01, message: str = "condition"):
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"{message} not met within {timeout}s")
        time.sleep(interval)


def stream_client(harness, fqn: str) -> socket.socket:
    """A client on a component's socket stream in an in-process simulation (morsec.testing.simulate), once
    the simulation's loop has accepted it."""
    port = harness.sim.middlewares["socket"].ports()[fqn]
    client = socket.create_connection((HOST, port), timeout=5)
    for _ in range(50):  # the loop accepts clients when it polls
        harness.sim.poller.poll(0.01)
        if any(s.listening for s in harness.sim.component(fqn).out_streams):
            return client
    raise AssertionError(f"{fqn}: the stream never accepted the client")


def read_lines(client: socket.socket, timeout: float = 5.0) -> list[bytes]:
    """The complete lines a stream client has been sent so far (at least one, unless it closed)."""
    client.settimeout(timeout)
    data = b""
    while not data.endswith(b"\n"):
        chunk = client.recv(1 << 20)
        if not chunk:
            break
        data += chunk
        client.settimeout(0.2)
    return data.splitlines()


def friction_loss(robot_friction: float | None = None, tick: float = 1.0 / 60) -> float:
    """m/s of the speed set at each tick that MORSE's ground friction takes from a ground robot, over the tick
    (morsec.kits.ground_friction: the same at any speed; damping aside)."""
    (mean, _), _, _ = slide(1.0, 0.0, ground_friction(robot_friction), 9.81, tick, tick)
    return 1.0 - mean
