"""One run, on whichever machine executes it (a thread of the local engine, a Dask worker): its build put in
place, `morsec run` in fixed_step on ports the OS picks (no other run can have them), the client command with
those ports in its environment, then the row: status, metrics, times, and the log's text.

The run is over when the client ends (the simulation ends then: `--wait-for-client`, else SIGINT), or when the
simulation has run its duration (a client still running is stopped: SIGTERM to its process group, SIGKILL 5 s
later); past the timeout everything is stopped. Standard library only, and no exception escapes: whatever
happens is a row."""

from __future__ import annotations

import contextlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from pathlib import Path
from typing import Any

from morsec.app.children import die_with_parent
from morsec.app.sweep import metrics as measures

READY = "SCENE INITIALIZED"
OK, CLIENT_FAILED, SIMULATION_FAILED, TIMED_OUT = "ok", "client_failed", "simulation_failed", "timed_out"
STATUSES = (OK, CLIENT_FAILED, SIMULATION_FAILED, TIMED_OUT)
# the columns every row has, in order; a variant's values come after `seed`, the metrics after `reason`
HEAD = ("run", "variant", "seed")
MIDDLE = ("status", "reason")
TAIL = ("sim_time", "wall_time", "rtf", "host", "log")
POLL = 0.005  # s between looks at the processes
TABLE_QUIET = 0.02  # s without a new line after SCENE INITIALIZED: the table of ports is complete
SIM_STOP_WAIT = 10.0  # s from SIGINT to SIGKILL of `morsec run`
SIM_ENDS_WITH_CLIENT = 2.0  # s for `morsec run --wait-for-client` to end by itself once its client has ended
CLIENT_GRACE = 0.5  # s a client still running when the simulation ran its duration has to end by itself
CLIENT_STOP_WAIT = 5.0  # s from SIGTERM to SIGKILL of a client still running when the simulation ended
_STATS = re.compile(r"^simulated ([0-9.eE+-]+) s in ([0-9.eE+-]+) s")
_SERVER = re.compile(r"^  (services|lockstep)\s+(\S+):(\d+)")
_STREAM = re.compile(r"^  (\S+)\s+(IN|OUT)\s+socket\s+(\S+):(\d+)\s*$")

_live: dict[subprocess.Popen, bool] = {}  # the processes of the runs going on: True for a process group
_live_lock = threading.Lock()
cancelled = threading.Event()  # set by the local engine when the sweep is interrupted: no new run starts


def execute_run(task: Any, files: dict[str, bytes] | None = None) -> dict[str, Any]:
    """The row of `task` (a morsec.app.sweep.plan.RunTask); `files`: the build's files, when the build folder
    is on another machine (Dask), written once per worker into a local folder named by its content key."""
    started = time.monotonic()
    try:
        build = Path(task.build_dir) if files is None else local_build(task.build_key, files)
        with tempfile.TemporaryDirectory(prefix=f"morsec-{task.run}-") as scratch:
            row = Run(task, build, Path(scratch)).go()
    except Exception:  # a bug of the sweep itself: the run is reported failed, with the traceback as its log
        row = run_row(task, SIMULATION_FAILED, "the run could not be carried out (see its log)")
        row["_log"] = traceback.format_exc()
    row["wall_time"] = time.monotonic() - started
    return row


def local_build(key: str, files: dict[str, bytes]) -> Path:
    """The build `key` in this machine's temporary folder, written (atomically) if it is not there yet."""
    root = Path(tempfile.gettempdir()) / f"morsec-sweep-builds-{os.getuid()}"
    target = root / key
    if (target / "manifest.json").is_file():
        return target
    tmp = root / f".{key}.{os.getpid()}.{threading.get_ident()}"
    for name, content in files.items():
        path = tmp / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(content)
    try:
        tmp.rename(target)
    except OSError:  # another run on this machine put it there first
        shutil.rmtree(tmp, ignore_errors=True)
    return target


def read_build(build: Path) -> dict[str, bytes]:
    """A build folder's files, to send to workers."""
    return {p.relative_to(build).as_posix(): p.read_bytes() for p in sorted(Path(build).rglob("*")) if p.is_file()}


class Run:
    def __init__(self, task: Any, build: Path, scratch: Path):
        self.task, self.build, self.scratch = task, build, scratch
        self.lines: list[str] = []
        self.last_line_at = 0.0
        self.sim: subprocess.Popen | None = None
        self.client: subprocess.Popen | None = None
        self.client_stopped = False  # the client was still running when the simulation ended: stopped by us
        self.sim_stopped = False  # SIGINT sent to the simulation (its client ended, or the run timed out)

    def go(self) -> dict[str, Any]:
        task = self.task
        if cancelled.is_set():
            row = run_row(task, SIMULATION_FAILED, "the sweep was interrupted")
            row["_log"] = ""
            return row
        deadline = time.monotonic() + task.timeout
        self.sim = self._start(self.sim_command(), cwd=self.scratch, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, env=dict(os.environ, PYTHONUNBUFFERED="1"))
        reader = threading.Thread(target=self._read, daemon=True)
        reader.start()
        timed_out = False
        ports: dict[str, Any] | None = None
        sim_ended_at = None
        try:
            while True:
                now = time.monotonic()
                if now > deadline:
                    timed_out = True
                    break
                sim_ended = self.sim.poll() is not None
                if sim_ended:
                    reader.join(5.0)  # all it printed
                if ports is None and self._table_complete(sim_ended):
                    ports = self._ports()
                    if task.client and not sim_ended:
                        self.client = self._start_client(ports)
                if self.client is not None and self.client.poll() is not None:
                    break  # the client ended: so does the run
                if sim_ended:
                    if self.client is None:
                        break
                    if self._ran_its_duration():  # the client is still there: it has CLIENT_GRACE to end
                        sim_ended_at = sim_ended_at or now
                        if now - sim_ended_at > CLIENT_GRACE:
                            break
                    # else the simulation ended because its client left: the client ends in its own time
                time.sleep(POLL)
        finally:
            self._stop(timed_out)
            reader.join(5.0)
        return self._result(timed_out, READY in self.lines)

    def _stats(self) -> tuple[float, float] | None:
        """(simulated seconds, wall seconds of the loop) from `morsec run`'s closing line."""
        found = next((m for line in self.lines if (m := _STATS.match(line))), None)
        return (float(found.group(1)), float(found.group(2))) if found else None

    def _ran_its_duration(self) -> bool:
        """Whether the simulation ended at its duration, or crashed (not because its client left)."""
        stats = self._stats()
        return stats is None or stats[0] >= self.task.duration - 1e-6

    def sim_command(self) -> list[str]:
        task = self.task
        cmd = [sys.executable, "-m", "morsec", "run", str(self.build), "--time-strategy", "fixed_step",
               "--duration", repr(float(task.duration)), "--seed", str(task.seed), "--port-base", "0",
               "--service-port", "0", "--output-dir", str(self.scratch)]
        return cmd + (["--wait-for-client"] if task.client else [])

    def _start(self, cmd: list[str], **kwargs) -> subprocess.Popen:
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, preexec_fn=die_with_parent, **kwargs)
        with _live_lock:
            _live[proc] = bool(kwargs.get("start_new_session"))
        return proc

    def _read(self) -> None:
        assert self.sim is not None and self.sim.stdout is not None
        for raw in self.sim.stdout:
            self.lines.append(raw.decode("utf-8", "replace").rstrip("\n"))
            self.last_line_at = time.monotonic()

    def _table_complete(self, sim_ended: bool) -> bool:
        """SCENE INITIALIZED and the table after it (written at once: complete when a line of another kind
        follows, or nothing for TABLE_QUIET)."""
        lines = list(self.lines)
        if READY not in lines:
            return False
        after = lines[lines.index(READY) + 1:]
        return (sim_ended or any(not line.startswith("  ") for line in after)
                or time.monotonic() - self.last_line_at > TABLE_QUIET)

    def _ports(self) -> dict[str, Any]:
        lines = list(self.lines)
        table = []
        for line in lines[lines.index(READY) + 1:]:
            if not line.startswith("  "):
                break
            table.append(line)
        found: dict[str, Any] = {"streams": {}}
        for line in table:
            if m := _SERVER.match(line):
                found[m.group(1)] = int(m.group(3))
                found["host"] = m.group(2)
            elif m := _STREAM.match(line):
                found["streams"][m.group(1)] = int(m.group(4))
        return found

    def _start_client(self, ports: dict[str, Any]) -> subprocess.Popen:
        task = self.task
        env = dict(os.environ, PYTHONUNBUFFERED="1", MORSEC_HOST=ports.get("host", "127.0.0.1"),
                   MORSEC_SERVICE_PORT=str(ports.get("services", "")), MORSEC_STREAM_PORTS=json.dumps(ports["streams"]),
                   MORSEC_RUN=task.run, MORSEC_VARIANT=task.variant, MORSEC_SEED=str(task.seed),
                   MORSEC_DURATION=repr(float(task.duration)), MORSEC_PARAMS=json.dumps(task.values),
                   MORSEC_OUTPUT_DIR=str(self.scratch))
        if "lockstep" in ports:
            env["MORSEC_LOCKSTEP_PORT"] = str(ports["lockstep"])
        for name, port in ports["streams"].items():
            env["MORSEC_PORT_" + re.sub(r"\W", "_", name).upper()] = str(port)
        out = open(self.scratch / "client.out", "wb")
        err = open(self.scratch / "client.err", "wb")
        with out, err:
            return self._start(["/bin/sh", "-c", task.client], cwd=task.client_cwd, env=env, stdout=out, stderr=err,
                               start_new_session=True)

    def _stop(self, timed_out: bool) -> None:
        """Stop what still runs: the simulation (SIGINT: it quits cleanly), the client (its process group)."""
        sim, client = self.sim, self.client
        if client is not None and client.poll() is not None and sim is not None and not timed_out:
            with contextlib.suppress(subprocess.TimeoutExpired):  # it ends by itself when its client has left
                sim.wait(SIM_ENDS_WITH_CLIENT)
        if client is not None and client.poll() is None:
            self.client_stopped = not timed_out
            _stop_group(client)
        if sim is not None and sim.poll() is None:
            self.sim_stopped = True
            sim.send_signal(signal.SIGINT)
            try:
                sim.wait(2.0 if timed_out else SIM_STOP_WAIT)
            except subprocess.TimeoutExpired:
                sim.kill()
                sim.wait()
        with _live_lock:
            for proc in (sim, client):
                _live.pop(proc, None)

    def _result(self, timed_out: bool, started: bool) -> dict[str, Any]:
        task, sim, client = self.task, self.sim, self.client
        assert sim is not None
        status, reason = OK, ""
        if timed_out:
            status, reason = TIMED_OUT, f"still running after {task.timeout:g} s (wall clock); stopped"
        elif not started:
            status, reason = SIMULATION_FAILED, f"`morsec run` {_ended(sim.returncode)} before {READY}" \
                                                f"{self._last_error(True)}"
        elif sim.returncode != 0 and not (self.sim_stopped and sim.returncode == -signal.SIGINT):
            # (a SIGINT that came as the simulation was exiting by itself, its handler gone, ends it so)
            status, reason = SIMULATION_FAILED, f"`morsec run` {_ended(sim.returncode)}{self._last_error(False)}"
        elif client is not None and client.returncode != 0 and not (
                self.client_stopped and client.returncode in (-signal.SIGTERM, 128 + signal.SIGTERM)):
            status = CLIENT_FAILED
            reason = (f"the client did not stop within {CLIENT_STOP_WAIT:g} s of SIGTERM" if self.client_stopped
                      else f"the client exited with status {client.returncode}{self._client_error()}")
        row = run_row(task, status, reason)
        if task.metrics and started and not timed_out:
            try:
                row.update(measures.compute(task.metrics, self.scratch, self.build))
            except Exception as err:  # files cut short by a crash
                row["reason"] = (reason + "; " if reason else "") + f"metrics: {type(err).__name__}: {err}"
        if client is not None:
            for key, value in client_metrics(self._client_text("client.out")).items():
                row[f"client.{key}" if key in row or key in TAIL else key] = cell(value)
        stats = self._stats()
        if stats:
            row["sim_time"], loop = stats
            row["rtf"] = row["sim_time"] / loop if loop > 0 else None
        row["_log"] = self._log(status, reason)
        return row

    def _client_text(self, name: str) -> str:
        try:
            return (self.scratch / name).read_bytes().decode("utf-8", "replace")
        except OSError:
            return ""

    def _last_error(self, or_last_line: bool) -> str:
        """': ' and the simulation's last error line (else, if asked, its last line), for the reason."""
        lines = [line.strip() for line in self.lines if line.strip()]
        errors = [line for line in lines if line.lower().startswith("error") or "Error" in line.split(":")[0]]
        picked = errors[-1] if errors else (lines[-1] if lines and or_last_line else "")
        return f": {picked}" if picked else ""

    def _client_error(self) -> str:
        lines = [line.strip() for line in self._client_text("client.err").splitlines() if line.strip()]
        return f": {lines[-1]}" if lines else ""

    def _log(self, status: str, reason: str) -> str:
        parts = ["$ " + " ".join(self.sim_command()), *self.lines]
        if self.client is not None:
            parts += [f"$ {self.task.client}    (in {self.task.client_cwd})", self._client_text("client.out").rstrip()]
            err = self._client_text("client.err").rstrip()
            if err:
                parts += ["--- client stderr", err]
        parts.append(f"--- {status}" + (f": {reason}" if reason else ""))
        return "\n".join(parts) + "\n"


def client_metrics(text: str) -> dict[str, Any]:
    """The JSON object on the client's last line of output, if that is what it is."""
    lines = [line for line in text.splitlines() if line.strip()]
    if not lines:
        return {}
    try:
        value = json.loads(lines[-1])
    except ValueError:
        return {}
    return value if isinstance(value, dict) else {}


def cell(value: Any) -> Any:
    """A table cell: numbers, booleans, text and nothing as they are; lists and mappings as their JSON."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return json.dumps(value)


def run_row(task: Any, status: str, reason: str) -> dict[str, Any]:
    row: dict[str, Any] = {"run": task.run, "variant": task.variant, "seed": task.seed}
    row.update({path: cell(value) for path, value in task.values.items()})
    row.update(status=status, reason=reason, host=socket.gethostname())
    return row


def _ended(status: int) -> str:
    if status < 0:
        try:
            return f"died of {signal.Signals(-status).name}"
        except ValueError:
            return f"died of signal {-status}"
    return f"exited with status {status}"


def _stop_group(proc: subprocess.Popen) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.wait(CLIENT_STOP_WAIT)
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def stop_everything() -> None:
    """An interrupted sweep: no new run starts, and the processes of the running ones are stopped."""
    cancelled.set()
    with _live_lock:
        procs = list(_live.items())
    for proc, group in procs:
        with contextlib.suppress(ProcessLookupError, OSError):
            if group:
                os.killpg(proc.pid, signal.SIGKILL)
            else:
                proc.kill()
