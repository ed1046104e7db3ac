"""Socket lockstep (configure_stream_manager('socket', time_sync=True, sync_port=N)): while a client is
connected to the sync port, each line it sends (or each read without a newline) allows one frame."""

from __future__ import annotations

from morsec.middleware.poller import Connection, Poller, Server


class SyncServer(Server):
    def __init__(self, poller: Poller, host: str, port: int):
        super().__init__(poller, host, port)
        self.steps = 0

    @property
    def engaged(self) -> bool:
        return bool(self.clients)

    def received(self, conn: Connection, data: bytes) -> None:
        self.steps += data.count(b"\n") or (1 if data else 0)

    def dropped(self, conn: Connection) -> None:
        if not self.clients:
            self.steps = 0

    def take(self) -> bool:
        if self.steps > 0:
            self.steps -= 1
            return True
        return False
