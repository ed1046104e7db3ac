"""A simulation in a child process, as a test drives one: build a scene from a Python function that makes
builder calls, start `morsec run` on the build folder, wait for SCENE INITIALIZED, stop it.

    build = build_call(case.setUpEnv, Path("logs/build/PoseTest"))    # BuilderError/SceneError: file:line
    sim = SimulationProcess(build, Path("logs/PoseTest.log"), time_strategy="fixed_step")
    sim.start()          # returns once the scene is initialized; SimulationDidNotStart otherwise
    ...                  # clients (pymorse) talk to the simulation on its ports
    sim.stop()           # SIGINT, then SIGKILL after a timeout

MORSE's test framework (`morse.testing.testing.MorseTestCase`) is a thin layer over this.
"""

from __future__ import annotations

import collections
import inspect
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, TextIO

from morsec.app.children import die_with_parent
from morsec.compiler.build import MANIFEST, compile_scene, write_build
from morsec.component.catalogue import Catalogue, load_catalogue
from morsec.errors import MorsecError
from morsec.frontends.builder.script import recording, script_error
from morsec.frontends.builder.session import Recording
from morsec.scene.validate import validate_scene

READY = "SCENE INITIALIZED"
START_TIMEOUT = 60.0  # seconds from `morsec run` to SCENE INITIALIZED (a loaded machine starts slowly)
STOP_TIMEOUT = 10.0  # seconds from SIGINT to the end of the process, before SIGKILL


class SimulationDidNotStart(MorsecError):
    """`morsec run` ended, or said nothing, before SCENE INITIALIZED."""


# ---------------------------------------------------------------- a scene from a function

def record_call(fn: Callable[[], Any], catalogue: Catalogue | None = None) -> Recording:
    """The builder calls made by `fn()`, recorded as a builder script's would be. Components are named after
    the variables that hold them, `fn`'s own locals included (read when it returns). An exception raised by
    `fn` becomes a SceneError at the line of `fn`'s file that raised it."""
    source = Path(inspect.getsourcefile(fn) or "<builder>")
    code = getattr(getattr(fn, "__func__", fn), "__code__", None)
    with recording(catalogue or load_catalogue(source.parent), source) as session:
        previous = sys.getprofile()

        def at_return(frame, event, arg):
            if event == "return" and frame.f_code is code:
                session.scan(frame)
            if previous is not None:
                previous(frame, event, arg)

        sys.setprofile(at_return)
        try:
            fn()
        except MorsecError:
            raise
        except Exception as err:
            raise script_error(err, source) from None
        finally:
            sys.setprofile(previous)
        session.end_of_script(None)
        return session.recording()


def build_call(fn: Callable[[], Any], out_dir: Path, catalogue: Catalogue | None = None,
               report: TextIO | None = None) -> Path:
    """Record `fn()` (see `record_call`), check the scene, compile it into `out_dir` (rewritten only when it
    changed). Warnings go to `report` (default stderr); errors are raised, located in `fn`'s file."""
    source = Path(inspect.getsourcefile(fn) or ".")
    cat = catalogue or load_catalogue(source.parent)
    rec = record_call(fn, cat)
    rec.report(report)
    files = compile_scene(validate_scene(rec.data, rec.smap, cat), cat)
    out_dir = Path(out_dir)
    try:
        same = (out_dir / MANIFEST).read_text(encoding="utf-8") == files[MANIFEST]
    except OSError:
        same = False
    if not same:
        write_build(files, out_dir)
    return out_dir


# ---------------------------------------------------------------- the child process

class SimulationProcess:
    """`morsec run BUILD` as a child process whose output (stdout and stderr) is appended to `log`, run in the
    log's folder."""

    def __init__(self, build_dir: Path, log: Path, time_strategy: str | None = None, args: tuple[str, ...] = ()):
        self.build_dir = Path(build_dir).resolve()
        self.log_path = Path(log).resolve()
        self.time_strategy = time_strategy
        self.args = tuple(args)
        self.process: subprocess.Popen | None = None
        self.ready = threading.Event()
        self.tail: collections.deque[str] = collections.deque(maxlen=40)
        self.exited_by_itself: int | None = None  # the exit status, when it ended before stop()
        self._reader: threading.Thread | None = None
        self._log: TextIO | None = None
        self._stopped = False

    @property
    def command(self) -> list[str]:
        cmd = [sys.executable, "-m", "morsec", "run", str(self.build_dir)]
        if self.time_strategy:
            cmd += ["--time-strategy", self.time_strategy]
        return cmd + list(self.args)

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process else None

    @property
    def stopped(self) -> bool:
        return self._stopped

    def running(self) -> bool:
        return self.process is not None and self.process.poll() is None

    def start(self, timeout: float = START_TIMEOUT) -> None:
        """Start `morsec run` and wait for SCENE INITIALIZED; SimulationDidNotStart (process stopped) if the
        process ends first or `timeout` passes."""
        self.log_path.parent.mkdir(parents=True, exist_ok=True)
        self._log = open(self.log_path, "a", encoding="utf-8")
        self._log.write(f"$ {' '.join(self.command)}\n")
        self._log.flush()
        env = dict(os.environ, PYTHONUNBUFFERED="1")
        # it runs in the log's folder: files it writes there (MuJoCo's MUJOCO_LOG.TXT) stay out of the user's
        self.process = subprocess.Popen(
            self.command, cwd=self.log_path.parent, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL, env=env, text=True, encoding="utf-8", errors="replace", bufsize=1,
            preexec_fn=die_with_parent)
        self._reader = threading.Thread(target=self._read, name="morsec-run-output", daemon=True)
        self._reader.start()
        deadline = time.monotonic() + timeout
        while not self.ready.wait(0.05):
            if self.process.poll() is not None:
                self._reader.join(2.0)  # the last lines
                if self.ready.is_set():
                    break
                status = self.process.returncode
                self._close()
                raise SimulationDidNotStart(f"`morsec run` exited with status {status} before {READY}"
                                            f"{self.last_error()}; see {self.log_path}")
            if time.monotonic() > deadline:
                self.stop()
                raise SimulationDidNotStart(f"no {READY} from `morsec run` after {timeout:.0f} s; see "
                                            f"{self.log_path}")

    def stop(self, timeout: float = STOP_TIMEOUT) -> int | None:
        """SIGINT (the simulation quits cleanly), SIGKILL if it is still there after `timeout`. Returns the
        exit status; records it in `exited_by_itself` when the process had ended before. Idempotent."""
        proc = self.process
        if proc is None or self._stopped:
            return proc.returncode if proc else None
        if proc.poll() is not None:
            self.exited_by_itself = proc.returncode
        else:
            proc.send_signal(signal.SIGINT)
            try:
                proc.wait(timeout)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
        self._close()
        return proc.returncode

    def _read(self) -> None:
        assert self.process is not None and self.process.stdout is not None
        for line in self.process.stdout:
            self.tail.append(line.rstrip("\n"))
            log = self._log
            if log is not None and not log.closed:
                log.write(line)
                log.flush()
            if not self.ready.is_set() and line.startswith(READY):
                self.ready.set()

    def _close(self) -> None:
        self._stopped = True
        if self._reader is not None:
            self._reader.join(5.0)
        if self.process is not None and self.process.stdout is not None:
            self.process.stdout.close()
        if self._log is not None and not self._log.closed:
            self._log.close()

    def last_error(self) -> str:
        """': ' and the last error line of the output (else its last line), for messages."""
        lines = [line.strip() for line in self.tail if line.strip()]
        errors = [line for line in lines if line.lower().startswith("error") or "Error" in line.split(":")[0]]
        picked = errors[-1] if errors else (lines[-1] if lines else "")
        return f": {picked}" if picked else ""

    def __enter__(self) -> SimulationProcess:
        self.start()
        return self

    def __exit__(self, *exc) -> None:
        self.stop()
