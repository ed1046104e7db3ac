"""Every row of issue 14's table, measured side by side in one run and printed as one table: what, morsec's
figure, its anchor's, their ratio, the target and whether it is met.

- the loop, for run_loop.py's three scenes (reference, sensors, fleet): wall time per frame of
  `Simulation.run` against bare `mj_step` on the same scene.xml (runs alternating, best of each), and the
  instructions per frame of each (callgrind: what machine load does not change);
- start-up (`morsec run` to SCENE INITIALIZED), `morsec build` cold and unchanged, and peak memory against
  importing MuJoCo and loading (and stepping) the same scene.xml: startup.py's rows, in CPU seconds;
- a service's round trip in its three cases (best_effort, fixed_step between sleeps, flat out) against a
  `selectors` echo server: round_trip.py's rows, with each server on a CPU of its own (`--apart`, judged) and
  where the kernel puts them (shown).

Each row's method is its script's (see their docstrings). --quick runs shorter and fewer repeats, and leaves
out the fleet's instruction count (about 5 minutes more of valgrind): its wall-time ratios are rougher, its other
instruction counts as good.

    python benchmarks/speed.py [--quick]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

BENCHMARKS = Path(__file__).resolve().parent
sys.path.insert(0, str(BENCHMARKS))

import round_trip  # noqa: E402
import run_loop  # noqa: E402


@dataclass
class Row:
    what: str
    ours: str  # morsec's figure, with its unit
    anchor: str  # what it is compared with, and its figure
    ratio: float | None  # None: not measured in this run
    target: str
    ok: bool | None


@dataclass(frozen=True)
class Plan:
    loop_seconds: dict[str, float]  # simulated seconds of a run, per scene
    loop_repeats: int
    callgrind_seconds: dict[str, float]
    startup_repeats: int
    memory_seconds: float
    calls: int


# the single-robot scenes' runs are 30 simulated s (1,800 frames, a tenth of a second of wall time): what a run
# pays once, at its first frames (the IMU's first geomagnetic field, the first batch of each noise, the first
# command's ground-friction plan, MuJoCo's first step on cold caches: about 1 ms in the sensors scene), is then
# under 1% of the time per frame; at the 10 s the sensors scene ran before, about 2%
FULL = Plan({"reference": 30.0, "sensors": 30.0, "fleet": 3.0}, 5, {"reference": 2.0, "sensors": 1.0, "fleet": 0.1},
            7, 5.0, 2000)
# without the fleet's instructions: about 5 minutes more of valgrind (128 robots' start-up, twice a side)
QUICK = Plan({"reference": 5.0, "sensors": 3.0, "fleet": 1.0}, 3, {"reference": 0.5, "sensors": 0.5}, 3, 2.0, 500)


def build(name: str, tmp: Path) -> Path:
    source = tmp / f"{name}.yaml"
    source.write_text(run_loop.SCENES[name][1])
    return run_loop.build_scene(source, tmp / f"build-{name}")


def loop_wall_row(name: str, build: Path, plan: Plan) -> Row:
    """Wall time per frame, run_loop.py's way: runs alternating, the best of each side."""
    target = run_loop.SCENES[name][2]
    substeps = int(json.loads((build / "manifest.json").read_text())["loop"]["physics_substeps"])
    seconds = plan.loop_seconds[name]
    run_loop.run_morsec(build, min(seconds, 1.0))  # warm-up: imports, caches
    best_ours = best_bare = float("inf")
    frames = 0
    for _ in range(plan.loop_repeats):
        wall, frames = run_loop.run_morsec(build, seconds)
        best_ours = min(best_ours, wall)
        best_bare = min(best_bare, run_loop.run_bare(build, frames, substeps))
    ratio = best_ours / best_bare
    return Row(f"loop, {name}: wall per frame", f"{best_ours / frames * 1e6:.1f} us",
               f"bare mj_step: {best_bare / frames * 1e6:.1f} us", ratio, f"<= {target:.2f}", ratio <= target)


def loop_instruction_rows(builds: dict[str, Path], plan: Plan) -> list[Row]:
    """Instructions per frame, run_loop.py's callgrind way, the children of all scenes two at a time (a count
    of instructions does not depend on what else runs)."""
    measured = [name for name in reversed(list(builds)) if name in plan.callgrind_seconds]  # the longest first
    jobs = {(name, side): (builds[name], plan.callgrind_seconds[name]) for name in measured
            for side in ("morsec", "bare")}
    with ThreadPoolExecutor(max_workers=2) as pool:
        futures = {key: pool.submit(run_loop.callgrind_frames, build, key[1], seconds)
                   for key, (build, seconds) in jobs.items()}
        counts = {key: future.result() for key, future in futures.items()}
    rows = []
    for name, build in builds.items():
        target = run_loop.SCENES[name][2]
        if name not in plan.callgrind_seconds:
            rows.append(Row(f"loop, {name}: instructions per frame", "not measured", "(--quick)", None,
                            f"<= {target:.2f}", None))
            continue
        frames = round(plan.callgrind_seconds[name] * loop_frequency(build))
        ours, theirs = counts[(name, "morsec")], counts[(name, "bare")]
        rows.append(Row(f"loop, {name}: instructions per frame", f"{ours / frames / 1e3:.0f} k",
                        f"bare mj_step: {theirs / frames / 1e3:.0f} k", ours / theirs, f"<= {target:.2f}",
                        ours / theirs <= target))
    return rows


def loop_frequency(build: Path) -> float:
    return float(json.loads((build / "manifest.json").read_text())["loop"]["frequency"])


def startup_rows(plan: Plan) -> tuple[list[Row], Row]:
    """The start-up and build rows, and the memory row (printed last, as in the issue), from startup.py run
    in a process of its own (see startup.measure: a child's peak memory counts its parent's)."""
    out = subprocess.run([sys.executable, str(BENCHMARKS / "startup.py"), "--json", "--repeats",
                          str(plan.startup_repeats), "--seconds", f"{plan.memory_seconds:g}"],
                         check=True, capture_output=True, text=True).stdout
    f = json.loads(out)
    load = "import mujoco + load scene.xml"
    start, cold, again = f["start"][0], f["cold"][0], f["again"][0]
    rows = [
        Row("morsec run to SCENE INITIALIZED", f"{start:.3f} s", f"{load}: {f['load'][0]:.3f} s",
            start / f["load"][0], "<= 1.3", start / f["load"][0] <= 1.3),
        Row("morsec build, cold", f"{cold:.3f} s", f"{load}: {f['cold_anchor'][0]:.3f} s",
            cold / f["cold_anchor"][0], "<= 1 s", cold <= 1.0),
        Row("morsec build, unchanged", f"{again:.3f} s", f"{load}: {f['again_anchor'][0]:.3f} s",
            again / f["again_anchor"][0], "<= 0.3 s", again <= 0.3),
    ]
    memory, bare = f["memory"][1], f["bare_step"][1]
    return rows, Row(f"peak memory, one robot, {plan.memory_seconds:g} s run", f"{memory:.1f} MiB",
                     f"load + {f['frames']} x mj_step bare: {bare:.1f} MiB", memory / bare, "<= 1.3",
                     memory / bare <= 1.3)


def round_trip_rows(plan: Plan) -> list[Row]:
    """Judged with each server on a CPU of its own (`round_trip.py --apart`), as a simulation running frames
    always is; the kernel's own placement is shown beside, unjudged: it may put the idle echo server on its
    client's CPU, which the simulation's loop, busy with frames, never is (docs/running.md#performance)."""
    rows = []
    for apart in (True, False):
        where = "servers on their own CPU" if apart else "kernel's placement"
        for case, mine, theirs in round_trip.measure(plan.calls, apart):
            ours, echo = round_trip.typical(mine), round_trip.typical(theirs)
            rows.append(Row(f"`time now` round trip, {case} ({where})", f"{ours * 1e6:.1f} us",
                            f"selectors echo server: {echo * 1e6:.1f} us", ours / echo,
                            f"<= {round_trip.TARGET:g}" if apart else "-",
                            ours / echo <= round_trip.TARGET if apart else None))
    return rows


def print_table(rows: list[Row]) -> None:
    header = ("what", "morsec", "anchor (same run)", "ratio", "target", "within target")
    cells = [(r.what, r.ours, r.anchor, "-" if r.ratio is None else f"{r.ratio:.2f}", r.target,
              "-" if r.ok is None else "yes" if r.ok else "NO") for r in rows]
    widths = [max(len(row[i]) for row in [header, *cells]) for i in range(len(header))]
    for line in [header, tuple("-" * w for w in widths), *cells]:
        print(" | ".join(cell.ljust(width) for cell, width in zip(line, widths)).rstrip())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="shorter runs and fewer repeats")
    args = parser.parse_args(argv)
    plan = QUICK if args.quick else FULL
    began = time.perf_counter()

    def step(what: str) -> None:
        print(f"[{time.perf_counter() - began:4.0f} s] {what} ...", file=sys.stderr, flush=True)
    rows: list[Row] = []
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        builds = {name: build(name, tmp) for name in run_loop.SCENES}
        for name, folder in builds.items():
            step(f"loop, {name}: wall time")
            rows.append(loop_wall_row(name, folder, plan))
        step("loop: instructions (callgrind)")
        instruction_rows = loop_instruction_rows(builds, plan)
        rows = [row for pair in zip(rows, instruction_rows) for row in pair]
        step("start-up, build, memory")
        first, memory = startup_rows(plan)
        rows += first
        step("round trips")
        rows += round_trip_rows(plan)
        rows.append(memory)
    print_table(rows)
    print(f"\n{sum(bool(r.ok) for r in rows)} of {sum(r.ok is not None for r in rows)} rows within target; measured in "
          f"{time.perf_counter() - began:.0f} s{' (--quick)' if args.quick else ''}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
