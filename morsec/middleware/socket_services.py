"""MORSE's socket service protocol on port 4000: `id component service [json array]` lines in,
`id STATUS[ json]` lines out; `id cancel` aborts a running asynchronous request."""

from __future__ import annotations

import json
import logging
import math
from collections import deque

from morsec.component.services import FAILED, Request, RequestHandler
from morsec.constants import MAX_QUEUED_ANSWERS, MAX_REQUEST_LINE, MAX_REQUESTS_PER_POLL
from morsec.middleware.poller import Connection, Poller, Server
from morsec.middleware.socket_streams import _plain, decode

log = logging.getLogger("morsec.middleware.services")

MAX_ID = 80


def format_response(request_id: str, status: str, result) -> bytes:
    if not result:  # MORSE leaves out falsy results (None, False, 0, [], "")
        return f"{request_id} {status}\n".encode()
    if type(result) is float and math.isfinite(result):  # `time now`: JSON writes a finite float as repr does
        return f"{request_id} {status} {result!r}\n".encode()
    return f"{request_id} {status} {json.dumps(result, default=_plain)}\n".encode()


class ServiceServer(Server):
    """Request lines wait in a per-client queue, served in order, at most MAX_REQUESTS_PER_POLL per client
    and poll: a client that pipelines thousands of requests gets them answered in turn without delaying
    the others, and is not read from while that many are waiting (what it sends meanwhile waits in the
    kernel, and TCP slows it down). Answers wait in the client's output buffer; past MAX_QUEUED_ANSWERS
    bytes the client, which is not reading them, is dropped.

    Between two physics sub-steps of a frame (`answer_anytime`) only the clients are read, and only the
    requests of `anytime` services answered (see there)."""

    # a client's bytes are acknowledged by the answers they bring at once, else explicitly
    # (`_serve_and_acknowledge`): a quick-ack per read would send a packet of its own before each answer
    acknowledges = False

    def __init__(self, poller: Poller, requests: RequestHandler, host: str, port: int, attempts: int):
        super().__init__(poller, host, port, attempts)
        self.requests = requests
        self.discarding: set[Connection] = set()
        self.waiting: dict[Connection, deque[bytes]] = {}  # request lines not served yet
        self.talkers = Poller()  # the clients alone, for answer_anytime
        self.mid_frame = False  # in answer_anytime: a frame's physics is running
        self.leaving: set[Connection] = set()  # clients to drop at the frame's end (their answer failed mid-frame)

    def accepted(self, conn: Connection) -> None:
        self.talkers.register(conn.sock, lambda _, c=conn: self._anytime_readable(c))

    def _readable(self, conn: Connection) -> None:
        if len(self.waiting.get(conn, ())) >= MAX_REQUESTS_PER_POLL:
            self._serve(conn)  # what it sent before first; not reading keeps its waiting lines bounded
        else:
            super()._readable(conn)

    def answer_anytime(self) -> None:
        """Called between two physics sub-steps of a frame, on the loop's thread: read the clients that wrote,
        and answer the requests at the head of each one's queue whose service is `anytime` (it reads and
        changes nothing a frame changes: `time now`). The first other request waits for the frame's end
        (`flush`, the next poll), and so do those its client sent after it: each client's requests are
        still answered in their order. Nothing else happens here: no client is accepted, and one that left
        is dropped at the frame's end (its end of file stays readable)."""
        self.mid_frame = True
        try:
            self.talkers.poll(0.0)
        finally:
            self.mid_frame = False

    def _anytime_readable(self, conn: Connection) -> None:
        """A client that wrote, mid-frame (answer_anytime)."""
        lines = self.waiting.get(conn)
        if conn.closed or (lines and not self._anytime(lines[0])):
            return  # its next request waits for the frame's end: so does all it sends after it
        if lines is None or len(lines) < MAX_REQUESTS_PER_POLL:
            data = conn.receive(acknowledge=False)
            if not data:  # nothing after all, or the client left: the frame's end sees to it
                return
            self.poller.polls += 1  # what arrived here arrived together (TimeServices counts round trips)
            self._take(conn, data)
        self._serve_and_acknowledge(conn, anytime=True)

    def _anytime(self, raw: bytes) -> bool:
        tokens = _tokens(raw)
        if not tokens:  # a blank line: skipped, wherever
            return True
        return len(tokens) >= 3 and len(raw) <= MAX_REQUEST_LINE and self.requests.anytime(tokens[1], tokens[2])

    def received(self, conn: Connection, data: bytes) -> None:
        self._take(conn, data)
        self._serve_and_acknowledge(conn)

    def _serve_and_acknowledge(self, conn: Connection, anytime: bool = False) -> None:
        """Serve what a client sent, then acknowledge it at once unless an answer went out meanwhile (it
        carries the acknowledgement): a client writing two requests in a row without waiting for an answer
        (pymorse: `rotate(...)` from its thread pool, then `sleep(1)`) has its second one held by Nagle's
        algorithm until the first is acknowledged, and a delayed acknowledgement takes 40 ms."""
        sent = conn.sent
        self._serve(conn, anytime)
        if conn.sent == sent and not conn.closed:
            conn.acknowledge()

    def _take(self, conn: Connection, data: bytes) -> None:
        """The complete lines of what arrived join the client's queue."""
        conn.inbuf += data
        *lines, conn.inbuf = conn.inbuf.split(b"\n")  # one pass, however many lines arrived
        if lines and conn in self.discarding:  # the end of a line refused already as too long
            self.discarding.discard(conn)
            lines = lines[1:]
        if lines:
            self.waiting.setdefault(conn, deque()).extend(lines)
        if len(conn.inbuf) > MAX_REQUEST_LINE:  # too long already: refused in its turn, its end skipped
            if conn not in self.discarding:
                self.waiting.setdefault(conn, deque()).append(conn.inbuf[:MAX_REQUEST_LINE + 1])
            self.discarding.add(conn)
            conn.inbuf = b""

    def _serve(self, conn: Connection, anytime: bool = False) -> None:
        """Serve the client's waiting lines in order (`anytime`: up to the first that is not such a request)."""
        lines = self.waiting.get(conn)
        if lines is None:
            return
        for _ in range(min(len(lines), MAX_REQUESTS_PER_POLL)):
            if anytime and not self._anytime(lines[0]):
                return
            line = lines.popleft()
            if len(line) > MAX_REQUEST_LINE:  # refused whether it came in one read or in many
                request_id = _first_token(line)
                if request_id:
                    self._reply(conn, request_id, FAILED, f"request line longer than {MAX_REQUEST_LINE} bytes")
            else:
                self._request(conn, line)
            if conn.closed:
                return
        if not lines:
            del self.waiting[conn]

    def _request(self, conn: Connection, raw: bytes) -> None:
        tokens = _tokens(raw)
        if not tokens:
            return
        request_id = tokens[0][:MAX_ID]
        if len(tokens) == 2 and tokens[1] == "cancel":
            self.requests.cancel(conn, request_id)
            return
        if len(tokens) < 3:
            self._reply(conn, request_id, FAILED, "malformed request: expected 'id component service [json array]'")
            return
        args: list = []
        if len(tokens) == 4:
            try:
                args = decode(tokens[3])
            except ValueError as err:
                self._reply(conn, request_id, FAILED,
                            f"malformed request: parameters are not valid JSON ({err}): {tokens[3][:80]!r}")
                return
            if not isinstance(args, list):
                self._reply(conn, request_id, FAILED, "malformed request: parameters must be a JSON array")
                return
        reply = lambda rid, status, result, c=conn: self._reply(c, rid, status, result)  # noqa: E731
        self.requests.handle(Request(request_id, tokens[1], tokens[2], args, reply, client=conn))

    def _reply(self, conn: Connection, request_id: str, status: str, result) -> None:
        if conn.closed:
            return
        try:
            line = format_response(request_id, status, result)
        except (TypeError, ValueError) as err:
            line = format_response(request_id, FAILED, f"result cannot be serialised: {err}")
        if not conn.send(line):
            self._drop_soon(conn)
        elif len(conn.outbuf) > MAX_QUEUED_ANSWERS:
            log.warning("dropped a service client that does not read its answers (more than %d bytes waiting)",
                        MAX_QUEUED_ANSWERS)
            self._drop_soon(conn)

    def _drop_soon(self, conn: Connection) -> None:
        """Drop a client now, or at the frame's end when a frame's physics is running (answer_anytime)."""
        if self.mid_frame:
            conn.closed = True  # nothing more is sent to it, nor served
            self.leaving.add(conn)
        else:
            self.drop(conn)

    def flush(self) -> None:
        """Serve the request lines that wait (a share of each client's), then send the answers that wait."""
        if not self.clients and not self.leaving:  # nobody connected: nothing waits (at every frame, usually)
            return
        while self.leaving:
            self.drop(self.leaving.pop())
        for conn in list(self.waiting):
            self._serve(conn)
        self._send_answers()

    def _send_answers(self) -> None:
        for conn in list(self.clients):
            if conn.outbuf and not conn.flush():
                self.drop(conn)

    def dropped(self, conn: Connection) -> None:
        self.talkers.unregister(conn.sock)  # closed already: found by its object
        self.leaving.discard(conn)
        self.requests.drop_client(conn)
        self.discarding.discard(conn)
        self.waiting.pop(conn, None)

    def close(self) -> None:
        self._send_answers()
        super().close()
        self.talkers.close()  # its clients all dropped (and unregistered) by now: only its epoll is left


def _tokens(raw: bytes) -> list[str]:
    """A request line's `id component service [json array]`, as split for handling."""
    return raw.decode("utf-8", errors="replace").strip().split(None, 3)


def _first_token(buf: bytes) -> str | None:
    head = buf[:MAX_ID + 1].decode("utf-8", errors="replace").split(None, 1)
    return head[0] if head and len(head[0]) <= MAX_ID else None
