"""The sockets under `morsec.client`: one I/O thread per `Morse`, a selector over its TCP connections.

Standard library only (`selectors`, `socket`, `threading`): no asyncore, no asynchat, so it runs on
every Python from 3.11 on. Every connection carries newline-terminated lines; the I/O thread reads
them and hands each complete line to its connection's `on_line`, which must return quickly (it never
runs user code: `Dispatcher` does that, on a thread of its own). Writes never block the caller: what
the socket does not take at once waits in the connection's buffer and the I/O thread sends it.
"""

from __future__ import annotations

import contextlib
import logging
import queue
import selectors
import socket
import threading
import time
from collections.abc import Callable

logger = logging.getLogger("morsec.client")

CONNECT_TIMEOUT = 10.0  # seconds to open a TCP connection
READ_SIZE = 256 * 1024
JOIN_TIMEOUT = 5.0  # seconds close() waits for a thread of its own to end


class Connection:
    """One TCP connection of a `Loop`: lines in (`on_line(bytes)`, without the newline), bytes out."""

    def __init__(self, loop: Loop, sock: socket.socket, name: str, on_line: Callable[[bytes], None],
                 on_close: Callable[[str], None]):
        self.loop = loop
        self.sock = sock
        self.name = name
        self._on_line = on_line
        self._on_close = on_close
        self._in = bytearray()
        self._scan = 0  # where the search for the next newline resumes in _in
        self._out = bytearray()
        self._closing = False
        self.closed = threading.Event()
        self.reason = ""

    # ---- any thread
    def send(self, data: bytes) -> None:
        """Queue `data`; sent at once if the socket takes it, else by the I/O thread."""
        with self.loop.lock:
            if self._closing or self.closed.is_set():
                raise ConnectionError(f"{self.name}: connection closed ({self.reason or 'by the client'})")
            if not self._out:
                try:
                    sent = self.sock.send(data)
                except (BlockingIOError, InterruptedError):
                    sent = 0
                except OSError:
                    sent = 0  # the I/O thread meets the same error and closes the connection
                data = data[sent:]
            if not data:
                return
            self._out += data
            self.loop.dirty.add(self)
        self.loop.wake()

    def pending_output(self) -> int:
        with self.loop.lock:
            return len(self._out)

    def flush(self, timeout: float) -> bool:
        """Wait until everything queued is sent (or the connection closed). True when nothing is left."""
        deadline = time.monotonic() + timeout
        while self.pending_output() and not self.closed.is_set():
            if time.monotonic() > deadline:
                return False
            time.sleep(0.002)
        return True

    def close(self, reason: str = "") -> None:
        with self.loop.lock:
            if self._closing:
                return
            self._closing = True
            self.reason = self.reason or reason
            self.loop.dirty.add(self)
        self.loop.wake()

    # ---- the I/O thread
    def wanted_events(self) -> int:
        return selectors.EVENT_READ | (selectors.EVENT_WRITE if self._out else 0)

    def handle_read(self) -> None:
        try:
            data = self.sock.recv(READ_SIZE)
        except (BlockingIOError, InterruptedError):
            return
        except OSError as err:
            self.loop.finish(self, f"{err.strerror or err}")
            return
        if not data:
            self.loop.finish(self, "closed by the simulation")
            return
        buffer = self._in
        buffer += data
        start = 0
        while True:
            end = buffer.find(b"\n", max(self._scan, start))
            if end < 0:
                break
            line = bytes(buffer[start:end])
            start = end + 1
            self._scan = start
            if line.endswith(b"\r"):
                line = line[:-1]
            try:
                self._on_line(line)
            except Exception:  # a bug of the client must not stop the loop
                logger.exception("%s: error while handling a line", self.name)
        if start:
            del buffer[:start]
        self._scan = len(buffer)

    def handle_write(self) -> None:
        with self.loop.lock:
            if not self._out:
                return
            try:
                sent = self.sock.send(self._out)
            except (BlockingIOError, InterruptedError):
                return
            except OSError as err:
                error = f"{err.strerror or err}"
            else:
                del self._out[:sent]
                return
        self.loop.finish(self, error)

    def closed_by_loop(self, reason: str) -> None:
        with contextlib.suppress(OSError):
            self.sock.close()
        with self.loop.lock:
            self._closing = True
            self.reason = self.reason or reason
            self._out.clear()
        self.closed.set()
        try:
            self._on_close(self.reason)
        except Exception:
            logger.exception("%s: error while handling the end of the connection", self.name)


class Loop:
    """The I/O thread of one client and the connections it serves."""

    def __init__(self, name: str = "morsec-client-io"):
        self.lock = threading.Lock()
        self.dirty: set[Connection] = set()  # connections whose registration or state changed
        self._selector = selectors.DefaultSelector()
        self._connections: set[Connection] = set()
        self._registered: dict[Connection, int] = {}
        self._wake_r, self._wake_w = socket.socketpair()
        self._wake_r.setblocking(False)
        self._wake_w.setblocking(False)
        self._selector.register(self._wake_r, selectors.EVENT_READ, None)
        self._stopping = False
        self.thread = threading.Thread(target=self._run, name=name, daemon=True)
        self.thread.start()

    def open(self, host: str, port: int, name: str, on_line: Callable[[bytes], None],
             on_close: Callable[[str], None]) -> Connection:
        """Connect (in the calling thread, so that a refused connection raises here) and serve."""
        sock = socket.create_connection((host, port), timeout=CONNECT_TIMEOUT)
        try:
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            sock.setblocking(False)
        except OSError:
            sock.close()
            raise
        connection = Connection(self, sock, name, on_line, on_close)
        with self.lock:
            if self._stopping:
                sock.close()
                raise ConnectionError(f"{name}: the client is closed")
            self._connections.add(connection)
            self.dirty.add(connection)
        self.wake()
        return connection

    def wake(self) -> None:
        with contextlib.suppress(BlockingIOError, InterruptedError, OSError):
            self._wake_w.send(b"\0")

    def finish(self, connection: Connection, reason: str) -> None:
        """Unregister and close a connection (I/O thread)."""
        if connection in self._registered:
            with contextlib.suppress(KeyError, ValueError, OSError):
                self._selector.unregister(connection.sock)
            del self._registered[connection]
        with self.lock:
            self._connections.discard(connection)
            self.dirty.discard(connection)
        connection.closed_by_loop(reason)

    def _apply_changes(self) -> list[Connection]:
        """Registrations brought up to date; the connections to close. Called with the lock held."""
        to_close = []
        for connection in self.dirty:
            if connection._closing or self._stopping:
                to_close.append(connection)
                continue
            events = connection.wanted_events()
            if connection not in self._registered:
                self._selector.register(connection.sock, events, connection)
            elif self._registered[connection] != events:
                self._selector.modify(connection.sock, events, connection)
            self._registered[connection] = events
        self.dirty.clear()
        if self._stopping:
            to_close.extend(c for c in self._connections if c not in to_close)
        return to_close

    def _run(self) -> None:
        try:
            while True:
                with self.lock:
                    to_close = self._apply_changes()
                    stopping = self._stopping
                for connection in to_close:
                    self.finish(connection, "closed by the client")
                if stopping:
                    return
                for key, mask in self._selector.select(timeout=1.0):
                    connection = key.data
                    if connection is None:
                        with contextlib.suppress(BlockingIOError, InterruptedError, OSError):
                            while self._wake_r.recv(4096):
                                pass
                        continue
                    if connection not in self._registered:
                        continue  # finished earlier in this round
                    if mask & selectors.EVENT_WRITE:
                        connection.handle_write()
                    if mask & selectors.EVENT_READ and connection in self._registered:
                        connection.handle_read()
                    if connection in self._registered:
                        with self.lock:
                            if connection.wanted_events() != self._registered[connection]:
                                self.dirty.add(connection)
        except Exception:
            logger.exception("the client's I/O thread stopped on an error")
            with self.lock:
                self._stopping = True
                leftover = list(self._connections)
            for connection in leftover:
                self.finish(connection, "the client's I/O thread failed")
        finally:
            with contextlib.suppress(OSError):
                self._selector.close()
            for sock in (self._wake_r, self._wake_w):
                with contextlib.suppress(OSError):
                    sock.close()

    def stop(self) -> None:
        """Close every connection and end the thread (joined unless this is the thread itself)."""
        with self.lock:
            self._stopping = True
        self.wake()
        if threading.current_thread() is not self.thread:
            self.thread.join(JOIN_TIMEOUT)


class Dispatcher:
    """A thread that runs user code — stream callbacks, futures' done-callbacks — in arrival order, so
    that a callback may call services and wait for them without blocking the I/O thread. Started on
    first use."""

    _STOP = object()

    def __init__(self, name: str = "morsec-client-callbacks"):
        self._name = name
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._lock = threading.Lock()
        self._thread: threading.Thread | None = None
        self._stopped = False

    def post(self, function: Callable, *args) -> None:
        with self._lock:
            if self._stopped:
                return
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name=self._name, daemon=True)
                self._thread.start()
        self._queue.put((function, args))

    def _run(self) -> None:
        while True:
            item = self._queue.get()
            if item is self._STOP:
                return
            function, args = item
            try:
                function(*args)
            except Exception:
                logger.exception("error in a callback (%s)", getattr(function, "__qualname__", function))

    def stop(self) -> None:
        """Run what is queued, then end the thread (joined unless called from a callback)."""
        with self._lock:
            self._stopped = True
            thread = self._thread
        if thread is None:
            return
        self._queue.put(self._STOP)
        if threading.current_thread() is not thread:
            thread.join(JOIN_TIMEOUT)

    @property
    def thread(self) -> threading.Thread | None:
        return self._thread
