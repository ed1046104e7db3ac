"""What `morsec run --foxglove` costs the main loop (docs/foxglove.md#cost): `Simulation.run(duration)` in
fixed_step (as fast as the machine allows) on the same build, three ways:

- plain: no Foxglove server (the reference);
- no client: `--foxglove`, nobody connected (target ratio <= 1.05: nothing is converted or sent while no
  client subscribes, the loop pays a clock read per frame and one has_sinks() per sensor tick);
- one client: Foxglove's own client (`@foxglove/ws-protocol`, tests/node/watch.mjs --count) connected and
  subscribed to every channel before the run starts, counting what it receives (reported, no target: it
  is the price of every message converted and sent, and the client shares the machine's cores).

Runs alternate (plain, no client, one client, plain ...) so that all see the same machine load; the best of
each is kept. Scenes: `reference` (benchmarks/reference.yaml: ATRV with pose, odometry and motion_vw at 60
Hz) and `laser` (the same ATRV in the boxes room with a Sick laser at 10 Hz: LaserScan messages).

    python benchmarks/foxglove_loop.py [--scene reference|laser] [--duration 60] [--repeats 5]

Needs node and the packages of tests/node (`npm ci --prefix tests/node`) for the connected run.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from morsec.app.project import build_scene  # noqa: E402
from morsec.runtime.simulation import RunOptions, Simulation  # noqa: E402

WATCH = ROOT / "tests" / "node" / "watch.mjs"
REFERENCE = (ROOT / "benchmarks" / "reference.yaml").read_text()
LASER = """\
environment:
  name: indoors-1/boxes
  time: {strategy: fixed_step, frequency: 60}
robots:
  - name: robot
    type: atrv
    components:
      - {name: pose, type: pose, frequency: 60, streams: [socket]}
      - {name: sick, type: sick, translate: [0.5, 0.0, 0.4], frequency: 10, streams: [socket]}
      - {name: motion, type: motion_vw, frequency: 60, streams: [socket]}
"""
SCENES = {"reference": ("ATRV: pose, odometry, motion_vw at 60 Hz", REFERENCE),
          "laser": ("ATRV in the boxes room: pose at 60 Hz, Sick laser at 10 Hz, motion_vw", LASER)}
TARGET_NO_CLIENT = 1.05
SUBSCRIBE_TIMEOUT = 30.0


def run(build: Path, duration: float, foxglove: bool, client: bool) -> tuple[float, dict]:
    """Wall seconds of Simulation.run(duration) (construction and connection excluded), and what the client
    counted (topic -> messages)."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0,
                                       foxglove=0 if foxglove else None))
    watcher = None
    try:
        if client:
            assert sim.foxglove is not None
            watcher = subprocess.Popen(["node", str(WATCH), sim.foxglove.url, "--count", "--until-stdin-closes",
                                        "--seconds", "600"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            deadline = time.monotonic() + SUBSCRIBE_TIMEOUT
            while not (sim.foxglove.tf.has_sinks() and all(s.listening for s in sim.foxglove.streams)):
                if time.monotonic() > deadline:
                    raise SystemExit("Foxglove's client did not subscribe (npm ci --prefix tests/node?)")
                time.sleep(0.05)
        start = time.perf_counter()
        sim.run(duration)
        wall = time.perf_counter() - start
    finally:
        sim.close()
    counts: dict = {}
    if watcher is not None:
        out, _ = watcher.communicate(timeout=30)
        counts = next((json.loads(line)["messages"] for line in out.splitlines() if '"count"' in line), {})
    return wall, counts


def measure(name: str, duration: float, repeats: int) -> None:
    description, text = SCENES[name]
    with tempfile.TemporaryDirectory() as tmp:
        source = Path(tmp) / f"{name}.yaml"
        source.write_text(text)
        build = build_scene(source, Path(tmp) / "build")
        run(build, 1.0, True, False)  # warm-up: imports, caches
        best = {"plain": float("inf"), "no client": float("inf"), "one client": float("inf")}
        counts: dict = {}
        for _ in range(repeats):
            best["plain"] = min(best["plain"], run(build, duration, False, False)[0])
            best["no client"] = min(best["no client"], run(build, duration, True, False)[0])
            wall, counts = run(build, duration, True, True)
            best["one client"] = min(best["one client"], wall)
    plain = best["plain"]
    print(f"scene: {description}; {duration:g} simulated s in fixed_step, best of {repeats}")
    for label, wall in best.items():
        print(f"{label:<11}: {wall:7.3f} s wall  (real-time factor {duration / wall:7.1f})")
    ratio = best["no client"] / plain
    print(f"ratio no client / plain  : {ratio:6.3f}  (target <= {TARGET_NO_CLIENT}) "
          f"{'OK' if ratio <= TARGET_NO_CLIENT else 'ABOVE TARGET'}")
    sent = sum(counts.values())
    each = (best["one client"] - plain) / sent * 1e6 if sent else float("nan")
    print(f"ratio one client / plain : {best['one client'] / plain:6.3f}  ({each:.0f} us per message; the client "
          f"received {sent}: {', '.join(f'{t} {n}' for t, n in sorted(counts.items()))})")
    print()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", choices=sorted(SCENES), help="only this scene (default: both)")
    parser.add_argument("--duration", type=float, default=60.0, help="simulated seconds per run")
    parser.add_argument("--repeats", type=int, default=5, help="runs of each kind; the best is kept")
    args = parser.parse_args(argv)
    for name in [args.scene] if args.scene else list(SCENES):
        measure(name, args.duration, args.repeats)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
