"""Non-blocking sockets, polled once per frame on the loop thread: one `epoll` for all of them."""

from __future__ import annotations

import errno
import logging
import math
import select
import socket
from collections.abc import Callable
from typing import Any

from morsec.constants import MAX_PORT

log = logging.getLogger("morsec.middleware")

READ_CHUNK = 65536
READ_LIMIT = 1024 * 1024  # bytes read from one client per poll: a flood cannot stall a frame
# Linux: acknowledge what a client sent at once. A client writing two requests in a row without waiting for
# an answer (pymorse: `rotate(...)` from its thread pool, then `sleep(1)`) has its second one held by Nagle's
# algorithm until the first is acknowledged, and a delayed acknowledgement takes 40 ms: 2 or 3 frames
QUICKACK = getattr(socket, "TCP_QUICKACK", None)


class Poller:
    """The loop's sockets and what handles each when it is readable. Linux's epoll, called directly (poll(2)
    elsewhere): a poll that finds nothing, the common case at every frame, costs one call (selectors'
    select costs three times as much in Python around it)."""

    def __init__(self):
        self.handlers: dict[int, tuple[socket.socket, Callable[[socket.socket], None]]] = {}  # fd -> them
        self.polls = 0  # how many polls read something: what arrives in one poll arrived together
        if hasattr(select, "epoll"):
            self._epoll: Any = select.epoll()
            self._readable = select.EPOLLIN
            self._wait = self._epoll.poll  # timeout in seconds
        else:
            self._epoll = select.poll()
            self._readable = select.POLLIN
            self._wait = lambda timeout: self._epoll.poll(math.ceil(timeout * 1000))  # in ms

    def register(self, sock: socket.socket, handler) -> None:
        fd = sock.fileno()
        if fd in self.handlers:
            raise KeyError(f"{sock!r} is registered already")
        self._epoll.register(fd, self._readable)
        self.handlers[fd] = (sock, handler)

    def unregister(self, sock: socket.socket) -> None:
        fd = sock.fileno()
        if self.handlers.get(fd, (None,))[0] is not sock:  # closed already (fileno -1): found by its object
            fd = next((f for f, (s, _) in self.handlers.items() if s is sock), -1)
            if fd < 0:
                return
        del self.handlers[fd]
        try:
            self._epoll.unregister(fd)
        except (OSError, KeyError):  # closed already
            pass

    def poll(self, timeout: float = 0.0) -> None:
        handlers = self.handlers
        if not handlers:
            return
        ready = self._wait(timeout if timeout > 0.0 else 0.0)
        if ready:
            self.polls += 1
            # every ready socket's handler, as found before any runs (one may unregister another)
            for sock, handler in [handlers[fd] for fd, _ in ready if fd in handlers]:
                handler(sock)

    def close(self) -> None:
        for sock, _ in self.handlers.values():  # always sockets: only sockets are registered
            try:
                sock.close()
            except OSError:
                pass
        self.handlers = {}
        if hasattr(self._epoll, "close"):  # poll(2)'s object has nothing to close
            self._epoll.close()


def listen(host: str, port: int, attempts: int = 1) -> socket.socket:
    """Bind a listening socket on port, port+1, ... (attempts tries); OSError when none is free."""
    last: OSError | None = None
    for candidate in range(port, min(port + attempts, MAX_PORT + 1)):
        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind((host, candidate))
        except OSError as err:
            sock.close()
            last = err
            if err.errno not in (errno.EADDRINUSE, errno.EACCES):
                raise
            continue
        sock.listen(128)
        sock.setblocking(False)
        return sock
    raise last or OSError(f"no free port from {port}")


class Connection:
    """One client: buffered, non-blocking; a slow reader skips whole messages rather than block the loop."""

    MAX_PENDING = 8 * 1024 * 1024

    def __init__(self, sock: socket.socket):
        sock.setblocking(False)
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        except OSError:
            pass
        self.sock = sock
        self.inbuf = b""
        self.outbuf = bytearray()  # appended to and consumed in place: no quadratic copying
        self.closed = False
        self.sent = 0  # messages sent (or queued to be)

    def fileno(self) -> int:
        return self.sock.fileno()

    def receive(self, acknowledge: bool = True) -> bytes | None:
        """New bytes (at most about READ_LIMIT; the rest waits for the next poll), b'' when nothing is
        there, None when the peer closed or failed. `acknowledge`: at once, per read (else the caller
        does, when no answer of its own carries the acknowledgement)."""
        chunks: list[bytes] = []
        size = 0
        while size < READ_LIMIT:
            try:
                data = self.sock.recv(READ_CHUNK)
            except (BlockingIOError, InterruptedError):
                break
            except OSError:
                return None
            if not data:
                return None if not chunks else b"".join(chunks)
            chunks.append(data)
            size += len(data)
            if acknowledge:
                self.acknowledge()
            if len(data) < READ_CHUNK:
                break
        return b"".join(chunks)

    def acknowledge(self) -> None:
        """Have the kernel acknowledge received bytes at once (quick-ack mode does not last: set per read)."""
        if QUICKACK is not None:
            try:
                self.sock.setsockopt(socket.IPPROTO_TCP, QUICKACK, 1)
            except OSError:
                pass

    def send(self, data: bytes, droppable: bool = False) -> bool:
        """Queue and flush. A droppable message is skipped when the client lags too far behind."""
        if self.closed:
            return False
        if droppable and len(self.outbuf) > self.MAX_PENDING:
            return True
        self.outbuf += data
        self.sent += 1
        return self.flush()

    def flush(self) -> bool:
        while self.outbuf:
            try:
                sent = self.sock.send(self.outbuf)
            except (BlockingIOError, InterruptedError):
                return True
            except OSError:
                self.closed = True
                return False
            del self.outbuf[:sent]
        return True

    def close(self) -> None:
        self.closed = True
        try:
            self.sock.close()
        except OSError:
            pass


class Server:
    """A listening socket and its clients, all polled by the same Poller. Subclasses say what a client's
    bytes mean (`received`) and what leaving means (`dropped`)."""

    acknowledges = True  # what a client sends is acknowledged per read (False: `received` sees to it)

    def __init__(self, poller: Poller, host: str, port: int, attempts: int = 1):
        self.poller = poller
        self.server = listen(host, port, attempts)
        self.port = self.server.getsockname()[1]
        self.clients: list[Connection] = []
        poller.register(self.server, self._accept)

    def _accept(self, server: socket.socket) -> None:
        while True:
            try:
                sock, _ = server.accept()
            except OSError:  # nothing more to accept now (BlockingIOError), or a client already gone
                return
            conn = Connection(sock)
            self.clients.append(conn)
            self.poller.register(sock, lambda s, c=conn: self._readable(c))
            self.accepted(conn)

    def _readable(self, conn: Connection) -> None:
        data = conn.receive(self.acknowledges)
        if data is None:
            self.drop(conn)
        else:
            self.received(conn, data)

    def accepted(self, conn: Connection) -> None:
        """A client connected."""

    def received(self, conn: Connection, data: bytes) -> None:
        """New bytes from a client."""

    def dropped(self, conn: Connection) -> None:
        """A client went away (or was dropped)."""

    def drop(self, conn: Connection) -> None:
        self.poller.unregister(conn.sock)
        conn.close()
        if conn in self.clients:
            self.clients.remove(conn)
            self.dropped(conn)

    def close(self) -> None:
        for conn in list(self.clients):
            self.drop(conn)
        self.poller.unregister(self.server)
        self.server.close()
