"""A build folder to a running simulation: start it, stop it on SIGINT/SIGTERM."""

from __future__ import annotations

import signal
from pathlib import Path

from morsec.runtime.simulation import RunOptions, Simulation


def run_simulation(build_dir: Path, options: RunOptions, duration: float | None) -> None:
    sim = Simulation(build_dir, options)  # a damaged build folder, or one from another morsec: one line
    previous = {sig: signal.signal(sig, lambda *_: sim.request_quit()) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        sim.announce()
        sim.run(duration)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
