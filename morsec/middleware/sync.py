"""Socket lockstep (configure_stream_manager('socket', time_sync=True, sync_port=N)): while a client is
connected to the sync port, each line it sends (or each read without a newline) allows one frame."""

from __future__ import annotations

import socket

from morsec.middleware.poller import Connection, Poller, listen


class SyncServer:
    def __init__(self, poller: Poller, host: str, port: int):
        self.poller = poller
        self.server = listen(host, port)
        self.port = self.server.getsockname()[1]
        self.clients: list[Connection] = []
        self.steps = 0
        poller.register(self.server, self._accept)

    @property
    def engaged(self) -> bool:
        return bool(self.clients)

    def _accept(self, server: socket.socket) -> None:
        while True:
            try:
                sock, _ = server.accept()
            except (BlockingIOError, InterruptedError, OSError):
                return
            conn = Connection(sock)
            self.clients.append(conn)
            self.poller.register(sock, lambda s, c=conn: self._readable(c))

    def _readable(self, conn: Connection) -> None:
        data = conn.receive()
        if data is None:
            self.poller.unregister(conn.sock)
            conn.close()
            self.clients.remove(conn)
            if not self.clients:
                self.steps = 0
            return
        self.steps += data.count(b"\n") or (1 if data else 0)

    def take(self) -> bool:
        if self.steps > 0:
            self.steps -= 1
            return True
        return False

    def close(self) -> None:
        for conn in self.clients:
            self.poller.unregister(conn.sock)
            conn.close()
        self.poller.unregister(self.server)
        self.server.close()
