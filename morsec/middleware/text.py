"""The `text` middleware: each message of a sensor appended to a file, as readable `key = value` blocks
or as CSV (one header line, then one row per message; lists and dicts JSON-encoded in their cell)."""

from __future__ import annotations

import csv
import json
import logging
from pathlib import Path

from morsec.middleware.socket_streams import _plain

log = logging.getLogger("morsec.middleware.text")


class TextStream:
    def __init__(self, component: str, path: Path, fmt: str):
        self.component = component
        self.path = path
        self.format = fmt
        path.parent.mkdir(parents=True, exist_ok=True)
        self.file = open(path, "w", encoding="utf-8", newline="")
        self.csv = csv.writer(self.file) if fmt == "csv" else None
        self.header: list[str] | None = None

    listening = True
    failed = False  # a write failed (full disk ...): the stream has stopped

    def write(self, local_data: dict) -> None:
        """Append one message; when the file cannot be written (full disk, quota, device gone), warn once
        and stop this stream: the simulation goes on."""
        if self.failed:
            return
        try:
            self._write(local_data)
        except OSError as err:
            self.failed = True
            log.warning("%s: text stream stopped, cannot write %s: %s", self.component, self.path,
                        err.strerror or err)
            self.close()

    def _write(self, local_data: dict) -> None:
        if self.csv is not None:
            if self.header is None:
                self.header = list(local_data)
                self.csv.writerow(self.header)
            self.csv.writerow([_cell(local_data.get(key)) for key in self.header])
        else:
            self.file.write(f"==> Data at simulated time {local_data.get('timestamp', 0.0)!r} ({self.component})\n")
            for key, value in local_data.items():
                self.file.write(f"{key} = {_cell(value)}\n")
            self.file.write("\n")
        self.file.flush()

    def close(self) -> None:
        try:
            self.file.close()  # flushes: may fail like a write
        except OSError:
            pass


def _cell(value) -> str:
    if isinstance(value, (list, tuple, dict)) or hasattr(value, "tolist"):
        return json.dumps(value, default=_plain)
    return repr(value) if isinstance(value, float) else str(value)
