"""MORSE socket datastreams: one TCP server per component stream; JSON lines out (sensors) or in (actuators)."""

from __future__ import annotations

import json
import logging
import math
import re
from typing import TYPE_CHECKING

import numpy as np

from morsec.constants import MAX_INPUT_LINE, MAX_JSON_DEPTH, MAX_REQUEST_LINE
from morsec.middleware.poller import Connection, Poller, Server

if TYPE_CHECKING:
    from morsec.middleware.base import RunContext

log = logging.getLogger("morsec.middleware.socket")

MAX_JSON_SIZE = max(MAX_INPUT_LINE, MAX_REQUEST_LINE)  # what decode reads at most, whoever calls it
_JSON_STRING = re.compile(r'"(?:[^"\\]|\\.)*"', re.S)
_NOT_BRACKET = re.compile(r"[^\[\]{}]+")


def encode(local_data) -> bytes:
    """json.dumps with Python's default separators, as MORSE (clients such as ArduPilot parse ', ')."""
    return (json.dumps(local_data, default=_plain) + "\n").encode("utf-8")


def decode(text: str | bytes):
    """json.loads of standard JSON only: NaN, Infinity and numbers that overflow a float are refused
    (ValueError). One of them in a command reaches MuJoCo's state (a flying robot's velocity), and
    MuJoCo then resets the whole world. So is a text longer than MAX_JSON_SIZE or nested deeper than
    MAX_JSON_DEPTH (the decoder would recurse until Python gives up)."""
    if isinstance(text, (bytes, bytearray)):
        text = text.decode("utf-8")
    if len(text) > MAX_JSON_SIZE:
        raise ValueError(f"longer than {MAX_JSON_SIZE} bytes")
    if nesting(text) > MAX_JSON_DEPTH:
        raise ValueError(f"nested deeper than {MAX_JSON_DEPTH} levels")
    return json.loads(text, parse_constant=_not_json, parse_float=_finite)


def nesting(text: str) -> int:
    """How deep [ and { nest outside strings; an upper bound (the number of brackets) when that is
    within MAX_JSON_DEPTH already: the usual case, at the cost of two counts."""
    opening = text.count("[") + text.count("{")
    if opening <= MAX_JSON_DEPTH:
        return opening
    brackets = _NOT_BRACKET.sub("", _JSON_STRING.sub("", text)).encode("ascii")
    codes = np.frombuffer(brackets, dtype=np.uint8)
    steps = np.where((codes == ord("[")) | (codes == ord("{")), 1, -1)
    return int(np.cumsum(steps).max(initial=0))


def _not_json(name: str):
    raise ValueError(f"{name} is not a JSON number")


def _finite(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is out of range")
    return value


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (bytes, bytearray)):
        return value.decode("latin-1")
    raise TypeError(f"cannot serialise {type(value).__name__}")


class SocketStream(Server):
    # a client reads it: kept as clients come and go (the loop asks at every tick of the sensor)
    listening = False

    def __init__(self, poller: Poller, component: str, direction: str, host: str, port: int, hint_only: bool,
                 context: RunContext | None = None):
        super().__init__(poller, host, port, attempts=100 if hint_only else 1)
        self.component = component
        self.direction = direction
        # each client's complete actuator messages not yet applied, with the frame count at their arrival (the
        # last of each frame's only): a message is applied from the second frame after it arrived (take)
        self.pending: dict[Connection, list[tuple[int, dict]]] = {}
        self.accepted_at: dict[Connection, int] = {}  # frame count when each client connected
        self.context = context if direction == "IN" else None  # told of clients opening, sending, closing
        self.frames = context.frames if context is not None else (lambda: 0)
        self.reader_opened = context.reader_opened if context is not None and direction == "OUT" else None

    def accepted(self, conn: Connection) -> None:
        self.listening = True
        if self.context is not None:
            self.accepted_at[conn] = self.frames()
            self.context.stream_opened(conn)
        elif self.reader_opened is not None:
            self.reader_opened()

    def dropped(self, conn: Connection) -> None:
        self.listening = bool(self.clients)
        self.pending.pop(conn, None)
        self.accepted_at.pop(conn, None)
        if self.context is not None:
            self.context.stream_closed(conn)

    def received(self, conn: Connection, data: bytes) -> None:
        if self.direction == "OUT":
            return  # clients of a sensor stream have nothing to say; reading only notices them leaving
        conn.inbuf += data
        if b"\n" not in conn.inbuf:
            if len(conn.inbuf) > MAX_INPUT_LINE:
                log.warning("%s: input line longer than %d bytes dropped", self.component, MAX_INPUT_LINE)
                conn.inbuf = b""
            return
        complete, _, conn.inbuf = conn.inbuf.rpartition(b"\n")
        if self.context is not None:
            self.context.stream_heard(conn)
        last = complete.rsplit(b"\n", 1)[-1]
        try:
            message = decode(last)
        except ValueError as err:  # UnicodeDecodeError included
            log.warning("%s: ignored a message that is not JSON (%s): %.80r", self.component, err, last)
            return
        if not isinstance(message, dict):
            log.warning("%s: ignored a message that is not a JSON object: %.80r", self.component, last)
            return
        stamp = self.frames()
        queue = self.pending.setdefault(conn, [])
        if queue and queue[-1][0] == stamp:
            queue.pop()  # of the messages that arrived between the same two frames, the last one counts
        queue.append((stamp, message))

    def take(self, frames: int) -> dict | None:
        """At a tick of the actuator, in the frame after `frames` frames: the last message of the clients that
        arrived before the previous frame ran (MORSE's frame order, docs/running.md#time: what a client sends
        after a frame's messages and answers is read at the next frame's logic, and acts from the frame after).
        A client that connected meanwhile is read a frame later still, as MORSE's socket reader accepted a
        new client at one tick and read it at the next (`motion = sim.robot.motion; motion.publish(cmd)`)."""
        message = None
        for conn in self.clients:  # in the order they connected: the last one read has the last word
            queue = self.pending.get(conn)
            if not queue or self.accepted_at.get(conn, -1) + 1 >= frames:
                continue
            while queue and queue[0][0] < frames:
                message = queue.pop(0)[1]
            if not queue:
                del self.pending[conn]
        return message

    def publish(self, message: dict) -> None:
        line = encode(message)
        for conn in list(self.clients):
            if not conn.send(line, droppable=True):
                self.drop(conn)
