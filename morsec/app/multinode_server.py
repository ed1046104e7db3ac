"""`morsec multinode-server`: MORSE's multinode_server, the hub of a world split over several `morsec run --node`
processes (docs/multinode.md). Each node sends the poses of its robots once a frame with its simulated time
(morsec.middleware.multinode) and waits for the answer: the last known poses of every other node's robots.

Time stays consistent: a node's answer is held while its simulated time is ahead of the slowest node still
connected, so the nodes' clocks stay within one frame of each other, whatever their time strategies. A node
that disconnects is reported; its robots stay where they were last seen, and it holds no one any more. As
MORSE's, the server can slow every node down (DELAY: wall-clock seconds at least between two answers to a
node) and pause them all (p then Enter on its terminal).

Standard library and morsec's socket poller only: it loads neither MuJoCo nor a scene."""

from __future__ import annotations

import math
import os
import signal
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from morsec.middleware import multinode as wire
from morsec.middleware.poller import Connection, Poller, Server

IDLE_POLL = 1.0  # s: the longest wait on the sockets when no delayed answer is due
EPSILON = 1e-9  # s of simulated time: rounding between two nodes' frame counts


@dataclass
class Node:
    conn: Connection
    address: str
    lines: wire.Lines = field(default_factory=wire.Lines)
    name: str | None = None  # from its first message
    time: float | None = None  # simulated s of its last message; None: it sends no time (an observer)
    dt: float = 0.0  # its frame, simulated s
    waiting: bool = False  # it sent a message not answered yet
    answered_at: float = -math.inf  # wall clock of its last answer (DELAY)
    warned: bool = False  # a bad message was reported (once per connection)


class MultinodeServer(Server):
    def __init__(self, poller: Poller, host: str, port: int, delay: float = 0.0,
                 say: Callable[[str], None] = print):
        super().__init__(poller, host, port)
        self.delay = delay
        self.say = say
        self.paused = False
        self.poses: dict[str, wire.Pose] = {}  # robot -> its last known pose
        self.owner: dict[str, str] = {}  # robot -> the node that sends it
        self.nodes: dict[Connection, Node] = {}
        self.gone: dict[str, float | None] = {}  # node -> its simulated time when it left

    # ---- connections
    def accepted(self, conn: Connection) -> None:
        try:
            host, port = conn.sock.getpeername()[:2]
            address = f"{host}:{port}"
        except OSError:
            address = "?"
        self.nodes[conn] = Node(conn, address)

    def received(self, conn: Connection, data: bytes) -> None:
        node = self.nodes[conn]
        try:
            lines = node.lines.feed(data)
        except ValueError as err:
            self.say(f"{node.name or node.address}: {err}: disconnected")
            self.drop(conn)
            return
        for line in lines:
            self._message(node, line)
        self.answer()

    def _message(self, node: Node, line: bytes) -> None:
        try:
            name, poses, stamp, discarded = wire.parse_node_message(line)
        except ValueError as err:
            self._warn(node, f"a message that is not a node's was discarded ({err})")
            return
        if node.name is None:
            node.name = name
            back = name in self.gone
            self.gone.pop(name, None)
            self.say(f"node {name} connected from {node.address}" + (" (back)" if back else ""))
        for robot, pose in poses.items():
            self.poses[robot] = pose
            self.owner[robot] = node.name
        if discarded:
            self._warn(node, f"entries that are not poses were discarded: {', '.join(discarded)}")
        if stamp is not None:
            node.time, node.dt = stamp[0], max(stamp[1], 0.0)
        node.waiting = True

    def _warn(self, node: Node, text: str) -> None:
        if not node.warned:
            node.warned = True
            self.say(f"{node.name or node.address}: {text}")

    def dropped(self, conn: Connection) -> None:
        node = self.nodes.pop(conn)
        if node.name is None:
            return
        if any(other.name == node.name for other in self.nodes.values()):
            return  # the same node is still connected by another connection
        self.gone[node.name] = node.time
        robots = sorted(robot for robot, owner in self.owner.items() if owner == node.name)
        when = f" at simulated time {node.time:.3f} s" if node.time is not None else ""
        stay = f": {', '.join(robots)} stay{'s' if len(robots) == 1 else ''} where last seen" if robots else ""
        self.say(f"node {node.name} left{when}{stay}")
        self.answer()

    # ---- answers
    def held(self, node: Node) -> bool:
        """Whether `node` runs ahead: its time past the slowest other node's. Each node sends its time before
        its frame, so the nodes' clocks are never more than one frame apart; the slowest is never held."""
        if node.time is None:
            return False
        others = [other.time for other in self.nodes.values()
                  if other is not node and other.time is not None and other.name != node.name]
        return bool(others) and node.time > min(others) + EPSILON

    def answer(self) -> float | None:
        """Answer every waiting node whose turn it is; the wall-clock seconds until a DELAY lets the next one
        be answered (None: no answer is waiting for DELAY)."""
        if self.paused:
            return None
        now = time.monotonic()
        soonest = None
        for node in list(self.nodes.values()):
            if not node.waiting or self.held(node):
                continue
            due = node.answered_at + self.delay
            if due > now:
                soonest = min(soonest or math.inf, due - now)
                continue
            node.waiting = False
            node.answered_at = now
            node.conn.send(wire.encode(self.answer_for(node)))
        return soonest

    def answer_for(self, node: Node) -> dict:
        """The last known pose of every robot of the other nodes, the world's time (the slowest node's) and the
        nodes' states."""
        out: dict = {robot: pose for robot, pose in self.poses.items() if self.owner[robot] != node.name}
        times = [n.time for n in self.nodes.values() if n.time is not None]
        out[wire.TIME] = [min(times) if times else 0.0, node.dt, time.time()]
        states = {name: {"time": t, "connected": False} for name, t in self.gone.items()}
        for other in self.nodes.values():
            if other.name is not None:
                states[other.name] = {"time": other.time, "connected": True}
        out[wire.NODES] = states
        return out

    def toggle_pause(self) -> None:
        self.paused = not self.paused
        self.say("paused: every node waits (p then Enter runs them again)" if self.paused else "running")
        self.answer()

    def status(self) -> str:
        live = sorted((n.name, n.time) for n in self.nodes.values() if n.name is not None)
        return ", ".join(f"{name} at {t:.3f} s" if t is not None else name for name, t in live) or "no node"


def serve(host: str, port: int, delay: float = 0.0) -> None:
    """Run the server until SIGINT or SIGTERM; one line per event on stdout."""
    def say(line: str) -> None:
        print(line, flush=True)

    poller = Poller()
    try:
        server = MultinodeServer(poller, host, port, delay, say)
    except OSError as err:
        poller.close()
        from morsec.errors import RuntimeFailure
        raise RuntimeFailure(f"cannot listen on {host}:{port}: {err.strerror or err}") from None
    stopping = []
    previous = {sig: signal.signal(sig, lambda *_: stopping.append(True)) for sig in (signal.SIGINT, signal.SIGTERM)}
    console = _console(poller, server)
    say(f"MULTINODE SERVER {host}:{server.port}" + (f" (at least {delay:g} s between two answers)" if delay else ""))
    try:
        while not stopping:
            wait = server.answer()
            poller.poll(min(wait, IDLE_POLL) if wait is not None else IDLE_POLL)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        if console is not None:
            poller.unregister(console)  # type: ignore[arg-type]
        server.close()
        poller.close()
        say(f"multinode server stopped ({server.status()})")


def _console(poller: Poller, server: MultinodeServer):
    """Standard input, when it can be read: `p` then Enter pauses and runs the nodes (MORSE's)."""
    stdin = sys.stdin
    try:
        if stdin is None or stdin.closed:
            return None
        fd = stdin.fileno()
    except (OSError, ValueError):
        return None

    def readable(_):
        try:
            data = os.read(fd, 1024)
        except OSError:
            data = b""
        if not data:  # end of input (a pipe closed, /dev/null): nothing more to read
            poller.unregister(stdin)  # type: ignore[arg-type]
            return
        for line in data.decode(errors="replace").splitlines():
            if line.strip().lower() == "p":
                server.toggle_pause()

    try:
        poller.register(stdin, readable)  # type: ignore[arg-type]
    except (OSError, ValueError, PermissionError):
        return None  # a regular file: nothing to wait for
    return stdin
