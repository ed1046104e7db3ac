"""morsec's main loop against a bare MuJoCo loop over the same compiled model, for three reference scenes
(issue 14's rows):

- reference (target ratio <= 1.10): an ATRV with a pose sensor, an odometry sensor and a motion_vw
  actuator, all at 60 Hz with socket streams, no client connected, `fixed_step`;
- sensors (target <= 1.15): an ATRV in the boxes room with a Sick laser at 10 Hz, an IMU and a GPS at
  60 Hz with noise modifiers, and motion_vw;
- fleet (target <= 1.05): 128 ATRVs on a grid, each with a pose sensor and motion_vw at 60 Hz.

The morsec side is `Simulation.run(duration)`,
the whole loop as `morsec run` drives it: socket polling, actuator and sensor ticks (default_action,
timestamps, modifiers), the clock, the service flush. The bare side is `mujoco.mj_step(m, d, nstep)` per
frame, with the same number of physics sub-steps per frame, on a fresh MjData of the same scene.xml, for
the same number of frames. Runs alternate (morsec, bare, morsec, ...) so that both see the same machine
load, and the best of each is kept.

    python benchmarks/run_loop.py [--scene reference|sensors|fleet] [--duration 20] [--repeats 5] [--profile]
    python benchmarks/run_loop.py --callgrind [--scene ...] [--callgrind-duration 2]

Prints both wall times, their ratio, the overhead per frame (split into the loop's own cost, measured
with every component deactivated, and the components' ticks) and the real-time factors. --callgrind
also counts instructions (valgrind's callgrind, which machine load does not change): each side runs in a
child process twice, for --callgrind-duration (2 simulated s; 0.25 for the fleet, whose frames cost 1e9
instructions each) and for twice as long, and the difference is the instructions of that many frames
(start-up cancels out), with one OpenBLAS thread and PYTHONHASHSEED=0 (see callgrind_frames).

Where each scene stands, and what the difference is made of: docs/running.md#performance (the figures
are kept there only). Counts move by up to 1% with the heap's layout (any change of code shifts where
MuJoCo's arrays fall).
"""

from __future__ import annotations

import argparse
import cProfile
import io
import json
import os
import pstats
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import mujoco

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from morsec.app.project import build_scene  # noqa: E402
from morsec.runtime.simulation import RunOptions, Simulation  # noqa: E402

SCENES = {}  # name -> (description, YAML, target ratio)
CALLGRIND_DURATION = {"fleet": 0.25}  # simulated s counted under callgrind, else 2 (a fleet's frame: ~1e9 instructions)

SCENE = (Path(__file__).resolve().parent / "reference.yaml").read_text()  # ATRV: pose, odometry, motion_vw
SCENES["reference"] = ("ATRV: pose, odometry, motion_vw at 60 Hz, socket streams", SCENE, 1.10)

SENSORS = """\
environment:
  name: indoors-1/boxes
  time: {strategy: fixed_step, frequency: 60}
  properties: {longitude: 1.4437, latitude: 43.6045, altitude: 146.0}
  seed: 1
robots:
  - name: robot
    type: atrv
    components:
      - {name: sick, type: sick, translate: [0.5, 0.0, 0.4], frequency: 10, streams: [socket]}
      - {name: imu, type: imu, frequency: 60, streams: [socket], modifiers: [{name: noise}]}
      - {name: gps, type: gps, frequency: 60, streams: [socket], modifiers: [{name: noise}]}
      - {name: motion, type: motion_vw, frequency: 60, streams: [socket]}
"""
SCENES["sensors"] = ("ATRV in the boxes room: Sick laser at 10 Hz, IMU and GPS at 60 Hz with noise", SENSORS, 1.15)

FLEET_SIZE = 128
FLEET = "environment:\n  name: empty\n  time: {strategy: fixed_step, frequency: 60}\nrobots:\n" + "".join(
    f"  - {{name: atrv{i}, type: atrv, translate: [{(i % 16) * 3.0}, {(i // 16) * 3.0}, 0.0], components: "
    f"[{{name: pose, type: pose, frequency: 60, streams: [socket]}}, "
    f"{{name: motion, type: motion_vw, frequency: 60, streams: [socket]}}]}}\n" for i in range(FLEET_SIZE))
SCENES["fleet"] = (f"{FLEET_SIZE} ATRVs, each with pose and motion_vw at 60 Hz", FLEET, 1.05)


def run_morsec(build: Path, duration: float, profile: cProfile.Profile | None = None,
               components: bool = True) -> tuple[float, int]:
    """Wall seconds of Simulation.run(duration) (construction excluded) and the frames it ran.
    components=False: every component deactivated (`simulation deactivate`), to see the loop's own cost."""
    options = RunOptions(strategy="fixed_step", service_port=0, port_base=0)
    sim = Simulation(build, options)
    for comp in sim.components:
        comp.active = components
    start = time.perf_counter()
    if profile:
        profile.enable()
    sim.run(duration)
    if profile:
        profile.disable()
    wall = time.perf_counter() - start
    return wall, sim.clock.frames


def run_bare(build: Path, frames: int, substeps: int) -> float:
    """Wall seconds of `frames` frames of mj_step(nstep=substeps) on the same compiled model."""
    model = mujoco.MjModel.from_xml_path(str(build / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    start = time.perf_counter()
    for _ in range(frames):
        mujoco.mj_step(model, data, substeps)  # nstep positional, as morsec's loop calls it (a keyword costs more)
    return time.perf_counter() - start


def callgrind_frames(build: Path, side: str, duration: float) -> int:
    """Instructions of `duration` simulated seconds of one side's loop: a child process under callgrind
    runs 2 x duration, another runs duration, and start-up cancels out of the difference."""
    def count(seconds: float) -> int:
        with tempfile.TemporaryDirectory() as out:
            cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}/cg.%p", sys.executable, __file__,
                   "--child", side, "--build", str(build), "--duration", repr(seconds)]
            # OpenBLAS's idle worker threads (numpy's, in both sides' processes) would be counted too:
            # valgrind runs one thread at a time and gives them a turn at every system call of the main
            # thread, where they spin; with one BLAS thread there are none (neither loop calls BLAS).
            # A fixed PYTHONHASHSEED: with random string hashes, dicts and sets differ from one process to the
            # next, and so do the instructions of each (by 0.5% of a frame's, run to run); fixed, by 0.001%.
            # malloc grows its heap 64 MiB at a time: valgrind caps the heap brk grows, and a failed brk leaves
            # errno set where MuJoCo's XML parser, reading a large scene.xml, takes it for an error of its own
            # ("XML Error: unknown error in attribute 'quat'")
            env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "PYTHONHASHSEED": "0",
                   "GLIBC_TUNABLES": "glibc.malloc.top_pad=67108864"}
            result = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if result.returncode != 0:
                raise SystemExit(f"failed under callgrind: {' '.join(cmd)}\n{result.stderr[-2000:]}")
            return sum(int(m) for m in re.findall(r"Collected : (\d+)", result.stderr))
    return count(2 * duration) - count(duration)


def child(side: str, build: Path, duration: float) -> None:
    """One side's loop, for --callgrind: morsec's Simulation.run or bare mj_step, for `duration`."""
    loop = json.loads((build / "manifest.json").read_text())["loop"]
    frames = round(duration * float(loop["frequency"]))
    if side == "morsec":
        run_morsec(build, duration)
    else:
        run_bare(build, frames, int(loop["physics_substeps"]))


def measure(build: Path, name: str, description: str, target: float, args) -> None:
    loop = json.loads((build / "manifest.json").read_text())["loop"]
    substeps, frequency = int(loop["physics_substeps"]), float(loop["frequency"])

    run_morsec(build, 1.0)  # warm-up: imports, caches
    best_morsec = best_bare = best_loop = float("inf")
    frames = 0
    for _ in range(args.repeats):
        wall, frames = run_morsec(build, args.duration)
        best_morsec = min(best_morsec, wall)
        best_bare = min(best_bare, run_bare(build, frames, substeps))
        best_loop = min(best_loop, run_morsec(build, args.duration, components=False)[0])

    simulated = frames / frequency
    ratio = best_morsec / best_bare
    print(f"scene: {description}")
    print(f"loop: {frequency:g} Hz x {substeps} physics sub-steps (timestep {loop['timestep']:.6g} s), "
          f"{frames} frames = {simulated:g} simulated s, best of {args.repeats}")
    print(f"bare mujoco.mj_step : {best_bare:8.3f} s wall  ({best_bare / frames * 1e6:7.1f} us/frame, "
          f"real-time factor {simulated / best_bare:7.1f})")
    print(f"morsec Simulation   : {best_morsec:8.3f} s wall  ({best_morsec / frames * 1e6:7.1f} us/frame, "
          f"real-time factor {simulated / best_morsec:7.1f})")
    print(f"overhead            : {(best_morsec - best_bare) / frames * 1e6:8.1f} us/frame, of which the loop "
          f"itself (components deactivated) {(best_loop - best_bare) / frames * 1e6:.1f} and the components' "
          f"ticks {(best_morsec - best_loop) / frames * 1e6:.1f}")
    print(f"ratio morsec / bare : {ratio:8.3f}  (target <= {target}) {'OK' if ratio <= target else 'ABOVE TARGET'}")

    if args.callgrind:
        counted = args.callgrind_duration or CALLGRIND_DURATION.get(name, 2.0)
        ours = callgrind_frames(build, "morsec", counted)
        theirs = callgrind_frames(build, "bare", counted)
        frames = round(counted * frequency)
        print(f"instructions per frame (callgrind, {frames} frames): morsec {ours / frames:,.0f} | "
              f"bare {theirs / frames:,.0f} | "
              f"ratio {ours / theirs:.3f}  (target <= {target}) {'OK' if ours / theirs <= target else 'ABOVE TARGET'}")

    if args.profile:
        profile = cProfile.Profile()
        run_morsec(build, args.duration, profile)
        out = io.StringIO()
        pstats.Stats(profile, stream=out).sort_stats("tottime").print_stats(15)
        print(out.getvalue())
    print()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration", type=float, default=20.0, help="simulated seconds per run")
    parser.add_argument("--repeats", type=int, default=5, help="runs of each side; the best is kept")
    parser.add_argument("--build", type=Path, help="an existing build folder instead of the reference scene")
    parser.add_argument("--profile", action="store_true", help="also profile one morsec run (cProfile)")
    parser.add_argument("--scene", choices=sorted(SCENES), help="only this reference scene (default: all)")
    parser.add_argument("--callgrind", action="store_true", help="also count instructions per frame (valgrind)")
    parser.add_argument("--callgrind-duration", type=float,
                        help="simulated seconds counted under callgrind (default 2; 0.25 for the fleet)")
    parser.add_argument("--child", choices=["morsec", "bare"], help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        child(args.child, args.build, args.duration)
        return 0

    names = [args.scene] if args.scene else list(SCENES)
    for name in names:
        with tempfile.TemporaryDirectory() as tmp:
            if args.build:
                build, description, target = args.build, str(args.build), SCENES["reference"][2]
            else:
                description, text, target = SCENES[name]
                source = Path(tmp) / f"{name}.yaml"
                source.write_text(text)
                build = build_scene(source, Path(tmp) / "build")
            measure(build, name, description, target, args)
        if args.build:
            break
    return 0


if __name__ == "__main__":
    sys.exit(main())
