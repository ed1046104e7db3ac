"""`morsec sweep` running for real: `morsec run` processes on OS-picked ports, real clients, the local engine and
a real Dask cluster (a scheduler and two worker processes on 127.0.0.1). Runs are short (a second or less of
simulated time) to keep the suite's time down."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from morsec.app.sweep.driver import run_sweep
from morsec.app.sweep.table import CSV, PARQUET

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "scenes" / "sweeps" / "go_to_goal.yaml"

SCENE = """\
environment: {name: empty, time: {frequency: 60}}
robots:
  - name: robot
    type: atrv
    components:
      - name: pose
        type: pose
        streams: [socket]
        modifiers: [{name: noise, pos_std: 0.1, rot_std: 0.05}]
      - {name: motion, type: motion_vw, streams: [socket]}
      - {name: crasher, type: crasher}
"""
# a project component that makes `morsec run` crash (SIGABRT) once the simulated time reaches crash_at
CRASHER = '''\
import os

from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor


class Crasher(Sensor):
    """Aborts the simulation process at a given simulated time (tests)."""

    short_descr = "Aborts the simulation"
    builder_name = "Crasher"
    frequency = 60.0

    class Properties(ComponentProperties):
        crash_at: float = Field(0.0, description="simulated seconds; 0: never")

    data = (DataField("t", 0.0, "float", "simulated time"),)

    def default_action(self):
        self.local_data["t"] = t = self.sim.clock.elapsed
        if 0 < self.properties.crash_at <= t:
            os.abort()


COMPONENT = Crasher
'''
# seed 0 ends well with metrics, seed 1 fails, seed 2 never ends by itself (stopped when the simulation ends)
CLIENT = """\
import json, os, sys, time
from morsec.client import Morse

seed = int(os.environ["MORSEC_SEED"])
with Morse("localhost", int(os.environ["MORSEC_SERVICE_PORT"])) as sim:
    sim.robot.motion.publish({"v": 1.0, "w": 0.0})
    sim.sleep(0.5)
    x = sim.robot.pose.get()["x"]
    ports = json.loads(os.environ["MORSEC_STREAM_PORTS"])
    assert ports["robot.pose"] == int(os.environ["MORSEC_PORT_ROBOT_POSE"]) == sim.get_stream_port("robot.pose")
    if seed == 2:
        time.sleep(120)
if seed == 1:
    sys.exit("the robot went the wrong way")
print(json.dumps({"x": x, "params": json.loads(os.environ["MORSEC_PARAMS"])}))
"""


class Quiet:
    def start(self, total, done, workers):
        self.total, self.done, self.workers = total, done, workers

    def row(self, row):
        pass


@pytest.fixture
def project(tmp_path) -> Path:
    folder = tmp_path / "project"
    (folder / "components" / "sensors" / "crasher").mkdir(parents=True)
    (folder / "morsec.toml").write_text("[project]\nname = 'sweeps'\n", encoding="utf-8")
    (folder / "components" / "sensors" / "crasher" / "component.py").write_text(CRASHER, encoding="utf-8")
    (folder / "scene.yaml").write_text(SCENE, encoding="utf-8")
    (folder / "client.py").write_text(CLIENT, encoding="utf-8")
    return folder


def write(folder: Path, name: str, text: str) -> Path:
    (folder / name).write_text(text, encoding="utf-8")
    return folder / name


NOISE_SWEEP = """\
scene: scene.yaml
duration: 0.5
seeds: [0, 1, 2]
grid:
  robots[robot].components[crasher].properties.crash_at: [0, 0.25]
metrics:
  - {robot: robot, pose: pose}
"""


def measured(rows: list[dict]) -> dict[str, dict]:
    return {r["run"]: {k: v for k, v in r.items() if k.startswith("robot.")} for r in rows if r["status"] == "ok"}


def check_noise_sweep(rows: list[dict], out: Path) -> None:
    """Three seeds of a variant that runs, and of one that crashes at 0.25 s."""
    assert len(rows) == 6 and len({r["run"] for r in rows}) == 6
    crashed = [r for r in rows if r["robots[robot].components[crasher].properties.crash_at"] == 0.25]
    fine = [r for r in rows if r["robots[robot].components[crasher].properties.crash_at"] == 0]
    assert [r["status"] for r in fine] == ["ok"] * 3
    for row in crashed:
        assert row["status"] == "simulation_failed"
        assert row["reason"] == "`morsec run` died of SIGABRT"
        log = Path(row["log"]).read_text()
        assert log.startswith("$ ") and "--seed" in log and log.endswith("--- simulation_failed: " + row["reason"] +
                                                                       "\n")
    for row in fine:
        assert row["sim_time"] == 0.5 and row["rtf"] > 0 and row["wall_time"] > 0
        assert "EXITING SIMULATION" in Path(row["log"]).read_text()
    # a noisy pose: each seed its own noise (the robot stands still: the final pose is the noise)
    assert len({r["robot.final_x"] for r in fine}) == 3 and all(r["robot.distance"] > 0 for r in fine)
    assert pq.read_table(out / PARQUET).num_rows == 6
    assert len((out / CSV).read_text().splitlines()) == 7


def test_the_local_engine_runs_every_variant_and_seed_and_a_crash_is_a_failed_row(project):
    sweep = write(project, "noise.yaml", NOISE_SWEEP)
    first = run_sweep(sweep, project / "first", Quiet(), workers=2)
    check_noise_sweep(first.rows, project / "first")
    second = run_sweep(sweep, project / "second", Quiet(), workers=2)
    assert measured(second.rows) == measured(first.rows)  # bit-identical, seed by seed


def test_a_client_gets_its_runs_ports_and_its_status_and_metrics_make_the_row(project):
    sweep = write(project, "client.yaml", """\
scene: scene.yaml
duration: 1.0
seeds: [0, 1, 2]
client: python3 client.py
metrics: [{robot: robot}]
timeout: 60
""")
    outcome = run_sweep(sweep, project / "out", Quiet(), workers=3)
    rows = {r["seed"]: r for r in outcome.rows}
    assert rows[0]["status"] == "ok" and rows[0]["reason"] == ""
    assert abs(rows[0]["x"] - 0.45) < 0.5  # the client's (noisy) pose
    assert rows[0]["params"] == "{}" and rows[0]["sim_time"] < 1.0  # the client ended the run
    assert 0.3 < rows[0]["robot.final_x"] < 0.6 and rows[0]["robot.collisions"] == 0  # 1 m/s for 0.5 s, from rest
    assert rows[1]["status"] == "client_failed"
    assert rows[1]["reason"] == "the client exited with status 1: the robot went the wrong way"
    assert rows[2]["status"] == "ok" and rows[2]["sim_time"] == 1.0  # stopped when the simulation ended
    assert "the robot went the wrong way" in Path(rows[1]["log"]).read_text()

    late = write(project, "late.yaml", "scene: scene.yaml\nduration: 1\nclient: sleep 60\ntimeout: 2\n")
    [row] = run_sweep(late, project / "late", Quiet()).rows
    assert row["status"] == "timed_out" and row["reason"] == "still running after 2 s (wall clock); stopped"
    assert 2 <= row["wall_time"] < 15


def test_a_killed_sweep_keeps_its_rows_and_resume_runs_only_the_rest(project):
    sweep = write(project, "resume.yaml", NOISE_SWEEP.replace("crash_at: [0, 0.25]", "crash_at: [0]")
                  .replace("duration: 0.5", "duration: 5"))
    out = project / "out"
    command = [sys.executable, "-m", "morsec", "sweep", str(sweep), "-o", str(out), "--workers", "1"]
    proc = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while not (out / PARQUET).exists() or pq.read_table(out / PARQUET).num_rows < 1:
        assert proc.poll() is None and time.monotonic() < deadline, "the sweep ended, or made no row in 60 s"
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    kept = pq.read_table(out / PARQUET).to_pylist()
    assert 1 <= len(kept) < 3

    again = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert again.returncode == 2 and "holds the results of a sweep already: add --resume" in again.stderr

    (sweep).write_text(sweep.read_text().replace("seeds: [0, 1, 2]", "seeds: [0, 1, 2, 3]"), encoding="utf-8")
    resumed = subprocess.run([*command, "--resume"], capture_output=True, text=True, timeout=120)
    assert resumed.returncode == 0, resumed.stderr
    rows = pq.read_table(out / PARQUET).to_pylist()
    assert sorted(r["seed"] for r in rows) == [0, 1, 2, 3] and rows[:len(kept)] == kept
    assert f"4 runs: 4 ok ({4 - len(kept)} run now)" in resumed.stdout
    assert len((out / CSV).read_text().splitlines()) == 5


def test_the_example_sweep_runs_and_draws_its_summary(tmp_path):
    out = tmp_path / "go_to_goal"
    result = subprocess.run([sys.executable, "-m", "morsec", "sweep", str(EXAMPLE), "-o", "go_to_goal", "--plot"],
                            capture_output=True, text=True, timeout=600, cwd=tmp_path)  # a folder relative to here
    assert result.returncode == 0, result.stdout + result.stderr
    rows = pq.read_table(out / PARQUET).to_pylist()
    assert len(rows) == 8 and {r["status"] for r in rows} == {"ok"}
    straight = [r for r in rows if r["robots[robot].translate[1]"] == 0.0]
    blocked = [r for r in rows if r["robots[robot].translate[1]"] == 1.0]
    assert len(straight) == len(blocked) == 4
    assert all(r["robot.collisions"] == 0 for r in straight)
    precise = [r for r in straight if r["robots[robot].components[pose].modifiers[0].pos_std"] == 0.05]
    assert all(r["arrived"] and 3 < r["robot.time_to.goal"] < 6 for r in precise)  # (1 m of noise may fool it)
    assert all(not r["arrived"] and r["robot.collisions"] >= 1 for r in blocked)  # the crate is in the way
    assert "robots[robot].translate[1]  runs  failed" in result.stdout
    assert (out / "summary.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / "summary.csv").read_text().startswith("parameter,value,runs,failed,metric,n,mean,std,min,max\n")


# ---------------------------------------------------------------- a real Dask cluster on 127.0.0.1

class Cluster:
    def __init__(self, folder: Path, workers: int = 2):
        self.file = folder / "scheduler.json"
        self.logs = folder
        self.scheduler = self._start("scheduler", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                                     "--port", "0", "--no-dashboard", "--scheduler-file", str(self.file))
        deadline = time.monotonic() + 60
        while not self.file.exists() or not self.file.read_text():
            assert self.scheduler.poll() is None and time.monotonic() < deadline, self.log("scheduler")
            time.sleep(0.05)
        self.address = json.loads(self.file.read_text())["address"]
        self.workers = [self._start(f"worker{i}", "distributed.cli.dask_worker", "--scheduler-file", str(self.file),
                                    "--nthreads", "1", "--no-nanny", "--no-dashboard", "--host", "127.0.0.1",
                                    "--name", f"worker{i}")
                        for i in range(workers)]
        from distributed import Client
        with Client(self.address, timeout=60) as client:
            client.wait_for_workers(workers, timeout=60)

    def _start(self, name: str, module: str, *args: str) -> subprocess.Popen:
        log = open(self.logs / f"{name}.log", "wb")
        with log:
            return subprocess.Popen([sys.executable, "-m", module, *args], stdout=log, stderr=subprocess.STDOUT)

    def log(self, name: str) -> str:
        return (self.logs / f"{name}.log").read_text(errors="replace")

    def stop(self) -> None:
        for proc in [*self.workers, self.scheduler]:
            proc.kill()  # nothing of theirs is to be kept: the sweep has its rows
            proc.wait()


@pytest.fixture
def cluster(tmp_path):
    cluster = Cluster(tmp_path)
    yield cluster
    cluster.stop()


def test_a_dask_cluster_runs_the_sweep_with_the_same_rows_as_this_machine(project, cluster):
    sweep = write(project, "noise.yaml", NOISE_SWEEP)
    reporter = Quiet()
    on_dask = run_sweep(sweep, project / "dask", reporter, scheduler=cluster.address)
    assert reporter.workers == 2
    check_noise_sweep(on_dask.rows, project / "dask")
    here = run_sweep(sweep, project / "here", Quiet(), workers=2)
    assert measured(on_dask.rows) == measured(here.rows)  # bit-identical, seed by seed, wherever it ran


def test_a_worker_killed_in_the_middle_of_the_sweep_loses_no_run(project, cluster):
    sweep = write(project, "many.yaml", """\
scene: scene.yaml
duration: 10
seeds: 10
metrics: [{robot: robot, pose: pose}]
""")
    from distributed import Client
    seen, lost = [], []

    class KillAfterTwo(Quiet):
        def row(self, row):
            seen.append(row)
            if len(seen) == 2:  # the runs worker 0 has at this moment die with it
                workers = probe.scheduler_info()["workers"]
                address = next(a for a, w in workers.items() if w["name"] == "worker0")
                lost.extend(key.split("-")[3] for key in probe.processing([address])[address])
                cluster.workers[0].kill()

    with Client(cluster.address, timeout=60) as probe:
        outcome = run_sweep(sweep, project / "out", KillAfterTwo(), scheduler=cluster.address)
    assert cluster.workers[0].poll() is not None and lost
    rows = {r["seed"]: r for r in outcome.rows}
    assert sorted(rows) == list(range(10)) and len(outcome.rows) == 10
    assert {r["status"] for r in outcome.rows} == {"ok"}
    assert all(rows[int(seed.removeprefix("s"))]["status"] == "ok" for seed in lost)  # redone on worker 1
