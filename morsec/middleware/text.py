"""The `text` middleware: each message of a sensor appended to a file, as readable `key = value` blocks
or as CSV (one header line, then one row per message; lists and dicts JSON-encoded in their cell)."""

from __future__ import annotations

import csv
import json
import logging
from pathlib import Path, PurePosixPath
from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, ConfigDict, Field

from morsec.errors import RuntimeFailure
from morsec.middleware.base import Middleware, StreamRequest
from morsec.middleware.socket_streams import _plain

log = logging.getLogger("morsec.middleware.text")


def check_output_file(name: str, what: str = "a text stream's file") -> str:
    """A file a scene names for a run to write (a text stream's, a recording's): a relative path that stays
    inside the run's output folder (`morsec run --output-dir`, the current folder by default), whatever the
    scene says; else ValueError."""
    path = PurePosixPath(name)
    if not name or name.endswith("/") or path.name in ("", ".", ".."):
        raise ValueError(f"{what} must name a file inside the run's output folder")
    if path.is_absolute() or ".." in path.parts:
        raise ValueError(f"{what} must be a relative path inside the run's output folder "
                         "(not absolute, no '..'); choose the folder with morsec run --output-dir")
    if any(not c.isprintable() for c in name):
        raise ValueError(f"{what} cannot contain control characters")
    return name


class Text(Middleware):
    name = "text"
    description = "each message of a sensor appended to a file: key = value blocks, or CSV"

    class Options(BaseModel):
        model_config = ConfigDict(defer_build=True)  # read by a build, not by a run
        file: Annotated[str, AfterValidator(check_output_file)] | None = Field(
            None, description="text: output file, relative to the run's output folder (default from the component "
            "name)")
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
        try:
            path = Path(self.context.output_dir) / check_output_file(endpoint["file"])
        except ValueError as err:  # a manifest written by hand or by an older morsec
            raise RuntimeFailure(f"{component}: text stream file {endpoint['file']!r}: {err}; "
                                 "rebuild the scene") from None
        try:
            stream = TextStream(component, path, endpoint["format"])
        except OSError as err:
            raise RuntimeFailure(f"{component}: cannot open the text stream's file {path}: "
                                 f"{err.strerror or err}") from None
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
    failed = False  # a write failed (full disk ...): the stream has stopped

    def publish(self, local_data: dict) -> None:
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
        if self.file.closed:
            return
        try:
            self.file.close()  # flushes: may fail like a write
        except OSError:
            pass


def _cell(value) -> str:
    if isinstance(value, (list, tuple, dict)) or hasattr(value, "tolist"):
        return json.dumps(value, default=_plain)
    return repr(value) if isinstance(value, float) else str(value)
