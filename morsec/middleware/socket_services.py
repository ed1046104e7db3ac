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
        return f"{request_id} {status}\n".encode("utf-8")
    if type(result) is float and math.isfinite(result):  # `time now`: JSON writes a finite float as repr does
        return f"{request_id} {status} {result!r}\n".encode("utf-8")
    return f"{request_id} {status} {json.dumps(result, default=_plain)}\n".encode("utf-8")


class ServiceServer(Server):
    """Request lines wait in a per-client queue, served in order, at most MAX_REQUESTS_PER_POLL per client
    and poll: a client that pipelines thousands of requests gets them answered in turn without delaying
    the others, and is not read from while that many are waiting (what it sends meanwhile waits in the
    kernel, and TCP slows it down). Answers wait in the client's output buffer; past MAX_QUEUED_ANSWERS
    bytes the client, which is not reading them, is dropped."""

    def __init__(self, poller: Poller, requests: RequestHandler, host: str, port: int, attempts: int):
        super().__init__(poller, host, port, attempts)
        self.requests = requests
        self.discarding: set[Connection] = set()
        self.waiting: dict[Connection, deque[bytes]] = {}  # request lines not served yet

    def _readable(self, conn: Connection) -> None:
        if len(self.waiting.get(conn, ())) >= MAX_REQUESTS_PER_POLL:
            self._serve(conn)  # what it sent before first; not reading keeps its waiting lines bounded
        else:
            super()._readable(conn)

    def received(self, conn: Connection, data: bytes) -> None:
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
        self._serve(conn)

    def _serve(self, conn: Connection) -> None:
        lines = self.waiting.get(conn)
        if lines is None:
            return
        for _ in range(min(len(lines), MAX_REQUESTS_PER_POLL)):
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
        text = raw.decode("utf-8", errors="replace").strip()
        if not text:
            return
        tokens = text.split(None, 3)
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
            self.drop(conn)
        elif len(conn.outbuf) > MAX_QUEUED_ANSWERS:
            log.warning("dropped a service client that does not read its answers (more than %d bytes waiting)",
                        MAX_QUEUED_ANSWERS)
            self.drop(conn)

    def flush(self) -> None:
        """Serve the request lines that wait (a share of each client's), then send the answers that wait."""
        for conn in list(self.waiting):
            self._serve(conn)
        self._send_answers()

    def _send_answers(self) -> None:
        for conn in list(self.clients):
            if conn.outbuf and not conn.flush():
                self.drop(conn)

    def dropped(self, conn: Connection) -> None:
        self.requests.drop_client(conn)
        self.discarding.discard(conn)
        self.waiting.pop(conn, None)

    def close(self) -> None:
        self._send_answers()
        super().close()


def _first_token(buf: bytes) -> str | None:
    head = buf[:MAX_ID + 1].decode("utf-8", errors="replace").split(None, 1)
    return head[0] if head and len(head[0]) <= MAX_ID else None
