"""A build folder to a running simulation: start it, stop it on SIGINT/SIGTERM."""

from __future__ import annotations

import gc
import signal
from pathlib import Path

from morsec.runtime.simulation import RunOptions, Simulation


def run_simulation(build_dir: Path, options: RunOptions, duration: float | None) -> tuple[float, float]:
    """Run until `duration` simulated seconds or a request to quit; (simulated seconds, wall seconds of the
    loop, from the first frame on: the time spent waiting for a client (--wait-for-client) is left out)."""
    sim = Simulation(build_dir, options)  # a damaged build folder, or one from another morsec: one line
    # what start-up built (modules, models, the simulation) lives as long as the process: kept out of the
    # collector's generations, and the collector on again if `morsec run` turned it off while starting
    gc.freeze()
    gc.enable()
    previous = {sig: signal.signal(sig, lambda *_: sim.request_quit()) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        sim.announce()
        sim.run(duration)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    return sim.clock.elapsed, sim.loop_wall_time
