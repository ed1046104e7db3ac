"""MORSE's socket service protocol on port 4000: `id component service [json array]` lines in,
`id STATUS[ json]` lines out; `id cancel` aborts a running asynchronous request."""

from __future__ import annotations

import json
import logging

from morsec.component.services import FAILED, Request, RequestHandler
from morsec.middleware.poller import Connection, Poller, Server
from morsec.middleware.socket_streams import _plain, decode

log = logging.getLogger("morsec.middleware.services")

MAX_REQUEST_LINE = 4 * 1024 * 1024
MAX_ID = 80


def format_response(request_id: str, status: str, result) -> bytes:
    line = f"{request_id} {status}"
    if result:  # MORSE leaves out falsy results (None, False, 0, [], "")
        line += " " + json.dumps(result, default=_plain)
    return (line + "\n").encode("utf-8")


class ServiceServer(Server):
    def __init__(self, poller: Poller, requests: RequestHandler, host: str, port: int, attempts: int):
        super().__init__(poller, host, port, attempts)
        self.requests = requests
        self.discarding: set[Connection] = set()

    def received(self, conn: Connection, data: bytes) -> None:
        conn.inbuf += data
        *lines, conn.inbuf = conn.inbuf.split(b"\n")  # one pass, however many lines arrived
        for line in lines:
            if conn in self.discarding:
                self.discarding.discard(conn)
                continue
            if len(line) > MAX_REQUEST_LINE:  # refused whether it came in one read or in many
                request_id = _first_token(line)
                if request_id:
                    self._reply(conn, request_id, FAILED, f"request line longer than {MAX_REQUEST_LINE} bytes")
                continue
            self._request(conn, line)
            if conn.closed:
                return
        if len(conn.inbuf) > MAX_REQUEST_LINE:
            request_id = _first_token(conn.inbuf) if conn not in self.discarding else None
            if request_id:
                self._reply(conn, request_id, FAILED, f"request line longer than {MAX_REQUEST_LINE} bytes")
            self.discarding.add(conn)
            conn.inbuf = b""

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
            except ValueError:
                self._reply(conn, request_id, FAILED,
                            f"malformed request: parameters are not valid JSON: {tokens[3][:80]!r}")
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

    def flush(self) -> None:
        for conn in list(self.clients):
            if conn.outbuf and not conn.flush():
                self.drop(conn)

    def dropped(self, conn: Connection) -> None:
        self.requests.drop_client(conn)
        self.discarding.discard(conn)

    def close(self) -> None:
        self.flush()
        super().close()


def _first_token(buf: bytes) -> str | None:
    head = buf[:MAX_ID + 1].decode("utf-8", errors="replace").split(None, 1)
    return head[0] if head and len(head[0]) <= MAX_ID else None
