"""What recording costs the loop (issue 16): morsec's loop on the reference scene (benchmarks/reference.yaml: an
ATRV with pose and odometry at 60 Hz and motion_vw, socket streams, no client, `fixed_step`) without and with
`--record` (every stream recorded: two sensor messages a frame, each as JSON and as its ROS 2 message), in one
run, side by side. Runs alternate (plain, recording, plain, ...) so that both see the same machine load, and
the best of each is kept.

    python benchmarks/record.py [--duration 200] [--repeats 5] [--services]
    python benchmarks/record.py --callgrind [--duration 20]

Prints, for each side, the loop's wall time (first frame to last: `Simulation.loop_wall_time`) and the CPU
time of the simulation's process during the run (its threads: the loop's and the recording's sender), their
ratios (target <= 1.10), and, apart, the writer process's CPU time, the time the end of a recording run waits
for the writer to finish the file, and the file's size and message count. The writer works on another core:
where one is free, the loop's wall time follows its CPU time; on a machine whose cores are all busy, the
writer takes its CPU time from the others, the loop included, and the wall-time ratio shows it.
--callgrind counts the instructions of the loop's process instead (valgrind's callgrind, which machine load
does not change; the writer process is not counted): each side runs in a child process twice, for --duration
and for twice as long, and the difference is the instructions of --duration's frames.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from morsec.app.project import build_scene  # noqa: E402
from morsec.runtime.simulation import RunOptions, Simulation  # noqa: E402

SCENE = Path(__file__).resolve().parent / "reference.yaml"
TARGET = 1.10


def run(build: Path, duration: float, record: Path | None, services: bool) -> dict[str, float]:
    """One run: the loop's wall seconds, the seconds from the loop's end to the run's end, the frames, the
    CPU seconds of this process and of the writer process."""
    options = RunOptions(strategy="fixed_step", service_port=0, port_base=0, record=record,
                         record_services=services and record is not None)
    sim = Simulation(build, options)
    writer_before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start, cpu = time.perf_counter(), time.process_time()
    sim.run(duration)
    total, cpu = time.perf_counter() - start, time.process_time() - cpu
    writer = resource.getrusage(resource.RUSAGE_CHILDREN)  # the writer has ended: its whole life, start-up included
    writer_cpu = (writer.ru_utime + writer.ru_stime) - (writer_before.ru_utime + writer_before.ru_stime)
    return {"loop": sim.loop_wall_time, "close": total - sim.loop_wall_time, "frames": sim.clock.frames, "cpu": cpu,
            "writer": writer_cpu}


def callgrind(build: Path, record: Path | None, duration: float) -> int:
    """Instructions of `duration` simulated seconds of the loop's process (start-up cancels out)."""
    def count(seconds: float) -> int:
        with tempfile.TemporaryDirectory() as out:
            cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}/cg.%p", sys.executable, __file__,
                   "--child", str(build), "--duration", repr(seconds)]
            cmd += ["--record-to", str(record)] if record else []
            env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}  # idle BLAS threads spin under valgrind
            result = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if result.returncode != 0:
                raise SystemExit(f"failed under callgrind: {' '.join(cmd)}\n{result.stderr[-2000:]}")
            return sum(int(m) for m in re.findall(r"Collected : (\d+)", result.stderr))
    return count(2 * duration) - count(duration)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=20.0, help="simulated seconds per run")
    parser.add_argument("--repeats", type=int, default=5, help="runs of each side; the best is kept")
    parser.add_argument("--services", action="store_true", help="also record services (--record-services)")
    parser.add_argument("--callgrind", action="store_true", help="count the loop process's instructions (valgrind)")
    parser.add_argument("--child", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--record-to", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:  # one side's run, under callgrind
        run(args.child, args.duration, args.record_to, False)
        return 0
    if args.callgrind:
        with tempfile.TemporaryDirectory() as tmp:
            build = build_scene(SCENE, Path(tmp) / "build")
            plain = callgrind(build, None, args.duration)
            recorded = callgrind(build, Path(tmp) / "run.mcap", args.duration)
            frames = round(args.duration * 60)
        print(f"instructions per frame of the loop's process (callgrind, {frames} frames): without recording "
              f"{plain / frames:,.0f} | with --record {recorded / frames:,.0f}")
        ratio = recorded / plain
        print(f"ratio recording / not: {ratio:.3f}  (target <= {TARGET}) {'OK' if ratio <= TARGET else 'ABOVE TARGET'}")
        return 0

    with tempfile.TemporaryDirectory() as tmp:
        build = build_scene(SCENE, Path(tmp) / "build")
        recording = Path(tmp) / "run.mcap"
        run(build, 1.0, recording, args.services)  # warm-up: imports, caches
        plain: dict[str, float] = {}
        recorded: dict[str, float] = {}
        for _ in range(args.repeats):
            for best, result in ((plain, run(build, args.duration, None, False)),
                                 (recorded, run(build, args.duration, recording, args.services))):
                for key, value in result.items():
                    best[key] = min(best.get(key, float("inf")), value)
        size = recording.stat().st_size

        from mcap.reader import make_reader
        with open(recording, "rb") as f:
            statistics = make_reader(f).get_summary().statistics

    frames = plain["frames"]
    us = 1e6 / frames

    def verdict(ratio: float) -> str:
        return f"{ratio:6.3f}  (target <= {TARGET}) {'OK' if ratio <= TARGET else 'ABOVE TARGET'}"

    print("scene: ATRV: pose, odometry, motion_vw at 60 Hz, socket streams, no client (benchmarks/reference.yaml)")
    print(f"{frames:.0f} frames = {args.duration:g} simulated s per run, best of {args.repeats}, "
          f"{'streams and services' if args.services else 'streams'} recorded")
    for name, side in (("without recording", plain), ("with --record    ", recorded)):
        print(f"loop {name} : {side['loop']:7.3f} s wall ({side['loop'] * us:6.1f} us/frame), "
              f"process CPU {side['cpu']:7.3f} s ({side['cpu'] * us:6.1f} us/frame)")
    print(f"writer process CPU     : {recorded['writer']:7.3f} s ({recorded['writer'] * us:6.1f} us/frame, its "
          f"start-up included); the run's end waited {recorded['close']:.3f} s for it")
    print(f"the file               : {size / 1e6:.2f} MB, {statistics.message_count} messages on "
          f"{statistics.channel_count} channels")
    print(f"ratio, loop wall time  : {verdict(recorded['loop'] / plain['loop'])}")
    print(f"ratio, process CPU time: {verdict(recorded['cpu'] / plain['cpu'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
