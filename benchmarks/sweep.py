"""`morsec sweep`'s engines (issue 11's targets, on 2 cores): 32 short runs of the reference scene
(benchmarks/reference.yaml: an ATRV with pose, odometry and motion_vw at 60 Hz; no client; `--duration`
simulated seconds each, seeds 0 to 31), executed

- one after the other (the local engine with one worker),
- by the local engine with 2 workers (target: a speed-up of at least 1.8 over one after the other),
- on a Dask cluster of 2 workers (one thread each) started on 127.0.0.1 (the same target).

The runs are planned (and built) once; each side times the engine alone, from the first run handed to it to
the last row back. The scheduling overhead per run is what a side's wall time holds beyond its runs' own
wall times (each run's, measured inside the run: `morsec run` and its start-up), per run and as a share of
a run (target under 5%):  overhead = (wall x workers - sum of the runs' wall times) / runs.

    python benchmarks/sweep.py [--runs 32] [--duration 10]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from morsec.app.sweep.engine import DaskEngine, LocalEngine  # noqa: E402
from morsec.app.sweep.plan import plan  # noqa: E402
from morsec.app.sweep.spec import load_sweep  # noqa: E402

SPEED_UP_TARGET = 1.8
OVERHEAD_TARGET = 0.05


def timed(engine, tasks) -> tuple[float, list[dict]]:
    start = time.perf_counter()
    rows = list(engine.run(tasks))
    wall = time.perf_counter() - start
    bad = [r for r in rows if r["status"] != "ok"]
    if bad:
        raise SystemExit(f"{len(bad)} runs failed: {bad[0]['reason']}\n{bad[0].get('_log', '')}")
    return wall, rows


def cluster(folder: Path, workers: int):
    """A scheduler and `workers` worker processes (one thread each) on 127.0.0.1; (address, processes)."""
    file = folder / "scheduler.json"
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                               "--port", "0", "--no-dashboard", "--scheduler-file", str(file)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    while not file.exists() or not file.read_text():
        time.sleep(0.05)
    address = json.loads(file.read_text())["address"]
    procs += [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address, "--nthreads", "1",
                                "--no-nanny", "--no-dashboard", "--host", "127.0.0.1"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) for _ in range(workers)]
    from distributed import Client
    with Client(address, timeout=60) as client:
        client.wait_for_workers(workers, timeout=60)
    return address, procs


def report(name: str, wall: float, rows: list[dict], workers: int, sequential: float | None) -> None:
    runs = sum(r["wall_time"] for r in rows)
    overhead = (wall * workers - runs) / len(rows)
    share = overhead / (runs / len(rows))
    line = f"{name:<24} {wall:7.2f} s   {len(rows) / wall:5.2f} runs/s   overhead per run {overhead * 1000:6.1f} ms " \
           f"({share:5.1%} of a run; target < {OVERHEAD_TARGET:.0%})"
    if sequential is not None:
        line += f"   speed-up {sequential / wall:4.2f} (target >= {SPEED_UP_TARGET})"
    print(line, flush=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=32)
    parser.add_argument("--duration", type=float, default=10.0, help="simulated seconds of each run")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="morsec-sweep-bench-") as tmp:
        folder = Path(tmp)
        sweep_file = folder / "bench.yaml"
        sweep_file.write_text(f"scene: {ROOT / 'benchmarks' / 'reference.yaml'}\nduration: {args.duration}\n"
                              f"seeds: {args.runs}\n", encoding="utf-8")
        _, tasks = plan(load_sweep(sweep_file), folder / "out")
        print(f"{len(tasks)} runs of the reference scene, {args.duration:g} simulated s each, no client; "
              f"Python {sys.version.split()[0]}; {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} "
              "(other work on the machine takes cores from the speed-ups)", flush=True)
        sequential, rows = timed(LocalEngine(1), tasks)
        report("one after the other", sequential, rows, 1, None)
        wall, rows = timed(LocalEngine(2), tasks)
        report("local, 2 workers", wall, rows, 2, sequential)
        address, procs = cluster(folder, 2)
        try:
            engine = DaskEngine(address)
            try:
                wall, rows = timed(engine, tasks)
            finally:
                engine.close()
            report("Dask, 2 workers", wall, rows, 2, sequential)
        finally:
            for proc in procs:
                proc.kill()
                proc.wait()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
