"""The `text` middleware: each message of a sensor appended to a file, as readable `key = value` blocks
or as CSV (one header line, then one row per message; lists and dicts JSON-encoded in their cell)."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, Field

from morsec.middleware.base import Middleware, StreamRequest
from morsec.middleware.socket_streams import _plain


class Text(Middleware):
    name = "text"
    description = "each message of a sensor appended to a file: key = value blocks, or CSV"

    class Options(BaseModel):
        file: str | None = Field(None, description="text: output file (default from the component name)")
        format: Literal["text", "csv"] | None = Field(None, description="text: 'text' (key = value blocks) or 'csv'")


    @classmethod
    def assign(cls, streams: list[StreamRequest]) -> list[dict[str, Any]]:
        endpoints = []
        for stream in streams:
            fmt = stream.options.get("format") or "text"
            default = f"{stream.component}.{'csv' if fmt == 'csv' else 'txt'}"
            endpoints.append({"file": stream.options.get("file") or default, "format": fmt})
        return endpoints

    def __init__(self, context, settings):
        super().__init__(context, settings)
        self.streams: list[TextStream] = []

    def open_stream(self, component: str, direction: str, endpoint: dict[str, Any]) -> TextStream:
        if direction != "OUT":
            raise ValueError(f"{component}: the text middleware only writes sensor output")
        stream = TextStream(component, Path(self.context.output_dir) / endpoint["file"], endpoint["format"])
        self.streams.append(stream)
        return stream

    def describe(self) -> list[tuple[str, str, str]]:
        return [(s.component, "OUT", str(s.path)) for s in self.streams]

    def close(self) -> None:
        for stream in self.streams:
            stream.close()
        self.streams = []


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

    def publish(self, local_data: dict) -> None:
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
        if not self.file.closed:
            self.file.close()


def _cell(value) -> str:
    if isinstance(value, (list, tuple, dict)) or hasattr(value, "tolist"):
        return json.dumps(value, default=_plain)
    return repr(value) if isinstance(value, float) else str(value)
