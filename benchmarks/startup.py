"""Start-up, build and memory of morsec against MuJoCo alone, each as a ratio measured side by side in one run
(issue 14's rows):

- `morsec run BUILD` to SCENE INITIALIZED (target <= 1.3) against `python -c "import mujoco"` loading the
  same scene.xml. The morsec side runs one frame (`--duration` of one frame, fixed_step) and exits: start-up
  is all of its cost;
- `morsec build` of the scene, cold (a new build folder; target <= 1 s) and unchanged (built again into the
  same folder; target <= 0.3 s), against loading its output (import mujoco, load scene.xml);
- peak memory, one robot (target <= 1.3): `morsec run` for --seconds of simulated time against loading and
  stepping the same scene.xml bare (mj_step with the same sub-steps, for the same number of frames).

The scene is the tutorial's robot: an ATRV with pose, odometry and motion_vw at 60 Hz with socket streams.
Times are CPU seconds (user + system, of the child process and its children), which a loaded machine
disturbs far less than wall time; sides alternate and the best of --repeats is kept. The children run as a
user's would: bytecode caches written (in a private folder, PYTHONPYCACHEPREFIX; a warm-up run fills it),
the build cache in a private folder (XDG_CACHE_HOME). --callgrind also counts the instructions of one run of
each side (valgrind's callgrind; minutes), which load does not change at all.

    python benchmarks/startup.py [--repeats 7] [--seconds 5] [--callgrind]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SCENE = (Path(__file__).resolve().parent / "reference.yaml").read_text()  # ATRV: pose, odometry, motion_vw

BARE_LOAD = "import mujoco, sys; mujoco.MjModel.from_xml_path(sys.argv[1])"
BARE_STEP = """\
import mujoco, sys
model = mujoco.MjModel.from_xml_path(sys.argv[1])
data = mujoco.MjData(model)
for _ in range(int(sys.argv[2])):
    mujoco.mj_step(model, data, nstep=int(sys.argv[3]))
"""


def child_env(tmp: Path) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = str(tmp / "pycache")
    env["XDG_CACHE_HOME"] = str(tmp / "cache")
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), *filter(None, [env.get("PYTHONPATH")])])
    return env


def measure_one(cmd: list[str], env: dict[str, str], cwd: Path) -> tuple[float, float]:
    """(CPU seconds, peak resident MiB) of one run of `cmd`, which must succeed."""
    proc = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    out, err = proc.communicate()
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}\n{err.decode()}")
    return usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def best(pairs: list[tuple[list[str], list[str]]], env, cwd, repeats: int, before=None):
    """Best (CPU, peak MiB) of each side over `repeats` alternating runs; `before()` runs ahead of each."""
    results = [[(float("inf"), float("inf"))] * 2 for _ in pairs]
    for _ in range(repeats):
        for i, sides in enumerate(pairs):
            for j, cmd in enumerate(sides):
                if before:
                    before(cmd)
                cpu, rss = measure_one(cmd, env, cwd)
                old = results[i][j]
                results[i][j] = (min(old[0], cpu), min(old[1], rss))
    return results


def instructions(cmd: list[str], env, cwd) -> int:
    """Instructions executed by `cmd` (callgrind, children followed)."""
    with tempfile.TemporaryDirectory() as out:
        result = subprocess.run(["valgrind", "--tool=callgrind", "--trace-children=yes",
                                 f"--callgrind-out-file={out}/cg.%p", *cmd], env=env, cwd=cwd,
                                capture_output=True, text=True)
        if result.returncode != 0:
            raise SystemExit(f"failed under callgrind: {' '.join(cmd)}\n{result.stderr[-2000:]}")
        return sum(int(m) for m in re.findall(r"Collected : (\d+)", result.stderr))


def row(what: str, ours: float, anchor: str, theirs: float, target: str, ok: bool, unit: str = "s") -> None:
    ratio = ours / theirs
    print(f"{what:<34} {ours:7.3f} {unit:<3} | {anchor:<34} {theirs:7.3f} {unit:<3} | ratio {ratio:5.2f} | "
          f"target {target:<14} {'OK' if ok else 'ABOVE TARGET'}")


@dataclass
class Figures:
    """CPU seconds and peak MiB (best of the runs) of each row's two sides, as `measure` returns them."""

    start: tuple[float, float]  # morsec run BUILD to SCENE INITIALIZED
    load: tuple[float, float]  # import mujoco + load scene.xml, the start's anchor
    cold: tuple[float, float]  # morsec build into a new folder
    cold_anchor: tuple[float, float]
    again: tuple[float, float]  # morsec build into the folder built already
    again_anchor: tuple[float, float]
    memory: tuple[float, float]  # morsec run for `seconds`
    bare_step: tuple[float, float]  # load + as many mj_step bare
    frames: int
    commands: dict[str, list[str]]  # each side's command line, for --callgrind
    env: dict[str, str]
    cwd: Path


def measure(tmp: Path, repeats: int, seconds: float) -> Figures:
    """Every row's two sides, run alternately `repeats` times in the scratch folder `tmp`. The peak memory of a
    child counts the process it was forked from (Linux's ru_maxrss keeps the size before exec): measure from
    a process that imported little (startup.py, not one that ran simulations: speed.py runs this script)."""
    py = sys.executable
    env = child_env(tmp)
    (tmp / "scene.yaml").write_text(SCENE)
    build = tmp / "build"
    morsec = [py, "-m", "morsec"]
    subprocess.run([*morsec, "build", "scene.yaml", "-o", str(build)], env=env, cwd=tmp, check=True,
                   capture_output=True)
    xml = str(build / "scene.xml")
    manifest = json.loads((build / "manifest.json").read_text())
    frequency, substeps = manifest["loop"]["frequency"], manifest["loop"]["physics_substeps"]
    frames = round(seconds * frequency)
    run = [*morsec, "run", str(build), "--time-strategy", "fixed_step", "--port-base", "0", "--service-port", "0"]
    commands = {
        "start": [*run, "--duration", f"{1.0 / frequency:.9f}"],
        "load": [py, "-c", BARE_LOAD, xml],
        "build_cold": [*morsec, "build", "scene.yaml", "-o", str(tmp / "cold")],
        "build_again": [*morsec, "build", "scene.yaml", "-o", str(build)],
        "memory": [*run, "--duration", f"{seconds:g}"],
        "bare_step": [py, "-c", BARE_STEP, xml, str(frames), str(substeps)],
    }
    cold_dir = str(tmp / "cold")

    def fresh_build(cmd):  # a cold build writes into a folder built never before
        if cmd[-1] == cold_dir:
            shutil.rmtree(cold_dir, ignore_errors=True)

    for cmd in commands.values():  # warm-up: bytecode caches
        fresh_build(cmd)
        measure_one(cmd, env, tmp)
    c = commands
    (start, load), (cold, cold_anchor), (again, again_anchor), (memory, bare_step) = best(
        [(c["start"], c["load"]), (c["build_cold"], c["load"]), (c["build_again"], c["load"]),
         (c["memory"], c["bare_step"])], env, tmp, repeats, before=fresh_build)
    return Figures(start, load, cold, cold_anchor, again, again_anchor, memory, bare_step, frames, commands, env,
                   tmp)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="runs of each side; the best is kept")
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated seconds of the memory row")
    parser.add_argument("--callgrind", action="store_true", help="also count instructions (valgrind)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON (for speed.py)")
    args = parser.parse_args(argv)

    py = sys.executable
    with tempfile.TemporaryDirectory() as tmp_name:
        tmp = Path(tmp_name)
        f = measure(tmp, args.repeats, args.seconds)
        if args.json:
            print(json.dumps({name: value for name, value in vars(f).items() if isinstance(value, (tuple, int))}))
            return 0
        mujoco_version = subprocess.run([py, "-c", "import mujoco; print(mujoco.__version__)"], capture_output=True,
                                        text=True).stdout.strip()
        print(f"CPU seconds (user + sys), best of {args.repeats}; Python {sys.version.split()[0]}, "
              f"MuJoCo {mujoco_version}")
        row("morsec run BUILD to SCENE INIT.", f.start[0], "import mujoco + load scene.xml", f.load[0],
            "<= 1.3", f.start[0] / f.load[0] <= 1.3)
        row("morsec build, cold", f.cold[0], "import mujoco + load scene.xml", f.cold_anchor[0], "<= 1 s",
            f.cold[0] <= 1.0)
        row("morsec build, unchanged", f.again[0], "import mujoco + load scene.xml", f.again_anchor[0], "<= 0.3 s",
            f.again[0] <= 0.3)
        row(f"peak memory, run {args.seconds:g} s", f.memory[1], f"load + {f.frames} x mj_step bare",
            f.bare_step[1], "<= 1.3", f.memory[1] / f.bare_step[1] <= 1.3, unit="MiB")

        if args.callgrind:
            c, env = f.commands, f.env
            print("instructions (callgrind), one run of each side:")
            for what, ours, theirs in (("morsec run BUILD to SCENE INIT.", c["start"], c["load"]),
                                       ("morsec build, unchanged", c["build_again"], c["load"])):
                a, b = instructions(ours, env, tmp), instructions(theirs, env, tmp)
                print(f"{what:<34} {a / 1e6:9.1f} M | import mujoco + load scene.xml {b / 1e6:9.1f} M | "
                      f"ratio {a / b:5.2f}")
            shutil.rmtree(tmp / "cold", ignore_errors=True)
            a, b = instructions(c["build_cold"], env, tmp), instructions(c["load"], env, tmp)
            print(f"{'morsec build, cold':<34} {a / 1e6:9.1f} M | import mujoco + load scene.xml {b / 1e6:9.1f} M | "
                  f"ratio {a / b:5.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
