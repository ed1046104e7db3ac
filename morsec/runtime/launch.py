"""A build folder to a running simulation: check the folder, start, stop on SIGINT/SIGTERM."""

from __future__ import annotations

import json
import signal
from pathlib import Path

from morsec.component.catalogue import Catalogue
from morsec.compiler.build import FORMAT_VERSION, MANIFEST
from morsec.errors import RuntimeFailure
from morsec.runtime.simulation import RunOptions, Simulation


# what the runtime reads from a build folder: a damaged one, or one from another morsec, fails in one line
_REQUIRED = {MANIFEST: ("format", "scene", "loop", "robots", "components"),
             "middleware.json": ("service_port", "services", "streams", "stream_managers")}


def check_build(build_dir: Path) -> None:
    for name, keys in _REQUIRED.items():
        try:
            data = json.loads((Path(build_dir) / name).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue  # unreadable: Simulation says so
        missing = [k for k in keys if not isinstance(data, dict) or k not in data]
        if missing:
            raise RuntimeFailure(f"{build_dir}: not a usable build folder: {name} lacks {', '.join(missing)}; "
                                 "rebuild it (morsec build)")
        if name == MANIFEST and data["format"] != FORMAT_VERSION:
            raise RuntimeFailure(f"{build_dir}: built by another morsec (format {data['format']}, this one reads "
                                 f"{FORMAT_VERSION}); rebuild it (morsec build)")


def run_simulation(build_dir: Path, cat: Catalogue, options: RunOptions, duration: float | None) -> None:
    check_build(build_dir)
    sim = Simulation(build_dir, cat, options)
    previous = {sig: signal.signal(sig, lambda *_: sim.request_quit()) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        sim.announce()
        sim.run(duration)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
