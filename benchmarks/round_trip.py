"""A service's round trip against an echo server's, side by side in one run (issue 14's row, target <= 2):

- morsec: `morsec run` of the reference scene (an ATRV with pose, odometry and motion_vw at 60 Hz, socket
  streams) answering `time now` on its service port, in three cases:
  - best_effort: the loop waits for the wall clock between frames, and answers while it waits;
  - fixed_step, a client between sleeps: from a client's first request (and after each of its sleeps) the
    loop follows the wall clock for SLEEP_HOLD_GRACE (docs/running.md), and answers as best_effort does;
  - fixed_step, flat out: after that, with no sleep asked, frames run back to back. While a client
    converses, a frame's physics runs its sub-steps one at a time and the service connections are read
    after each: `time now` (an `anytime` service) is answered there, a sub-step (about 10 us here) after
    it arrived at most; a request that arrives after the frame's physics (its sensors, the messages sent)
    waits for the next poll, at the frame's end;
- anchor: a single-threaded `selectors` echo server in its own Python process, answering each line.

The client is the same for both: one TCP connection (TCP_NODELAY), one request in flight, the next sent when
the answer's line is read. `--apart` keeps the client on the first CPU and both servers on the second: each
server then answers from a CPU of its own, as a simulation running frames always does; without it the kernel
places them, and on an idle machine it wakes the echo server on its client's CPU (no CPU is woken for a
round trip), which it cannot do for a loop busy with frames (docs/running.md#performance).

Calls alternate between the sides (morsec, echo, morsec ...) so that both see the
same machine load at the same moments; each side's figure is the mean of its calls but the slowest 5% (a
process preempted by another's work, which load brings, costs either side a scheduler's time slice: that is
the machine's, not the design's), its median beside it.

Where the time goes (2 cores, medians): the echo answers in 16 us (two loopback hops, two Python processes
reading and writing a line); best_effort in 21 us (the request parsed, dispatched, its listeners told, the
answer written: about 5 us more). Flat out, each trip used to wait for the frame running when its request
arrived (0.14 ms, 7 to 18 x the echo); now it waits for the sub-step running (12 us each, 6 on average), and
a request that arrives after the physics (about 1 in 9: the sensors tick, the messages leave, the loop
polls at the next frame's start) waits 20 to 40 us: median 31 us, a mean of about 1.9 x the echo's, the
dearest case and the closest to the target. A thread answering while `mj_step` runs (it releases the GIL)
would not answer sooner after the physics (the loop holds the GIL there), and would cost a lock around
every step and GIL hand-offs: not taken.

    python benchmarks/round_trip.py [--calls 2000] [--apart]
"""

from __future__ import annotations

import argparse
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from morsec.constants import SLEEP_HOLD_GRACE  # noqa: E402

SCENE = Path(__file__).resolve().parent / "reference.yaml"

ECHO_SERVER = """\
import selectors, socket, sys
server = socket.socket()
server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
server.bind(("127.0.0.1", 0))
server.listen()
sel = selectors.DefaultSelector()
sel.register(server, selectors.EVENT_READ)
print(server.getsockname()[1], flush=True)
while True:
    for key, _ in sel.select():
        if key.fileobj is server:
            conn, _ = server.accept()
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            sel.register(conn, selectors.EVENT_READ)
        else:
            data = key.fileobj.recv(65536)
            if not data:
                sel.unregister(key.fileobj)
                key.fileobj.close()
            else:
                key.fileobj.sendall(data)
"""


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class Client:
    def __init__(self, port: int):
        self.sock = socket.create_connection(("127.0.0.1", port))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.lines = self.sock.makefile("rb")
        self.count = 0

    def call(self, request: bytes) -> bytes:
        self.count += 1
        self.sock.sendall(b"%d %s\n" % (self.count, request))
        return self.lines.readline()

    def timed(self, request: bytes) -> float:
        """Seconds of one round trip."""
        start = time.perf_counter()
        self.call(request)
        return time.perf_counter() - start

    def close(self) -> None:
        self.lines.close()
        self.sock.close()


def typical(times: list[float]) -> float:
    """The mean of the calls but the slowest 5% (see the module's docstring)."""
    kept = sorted(times)[:max(1, len(times) * 95 // 100)]
    return sum(kept) / len(kept)


def on_cpu(cpu: int | None):
    """A child's preexec_fn that keeps it (all its threads) on one CPU; None: the kernel's choice."""
    if cpu is None:
        return None
    return lambda: os.sched_setaffinity(0, {cpu})


def start_morsec(build: Path, strategy: str, cpu: int | None = None) -> tuple[subprocess.Popen, int]:
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "morsec", "run", str(build), "--time-strategy", strategy,
                             "--service-port", str(port), "--port-base", "0"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=_env(),
                            preexec_fn=on_cpu(cpu))
    assert proc.stdout is not None
    for line in proc.stdout:
        if "SCENE INITIALIZED" in line:
            return proc, port
    raise SystemExit(f"morsec run ended before SCENE INITIALIZED (exit {proc.wait()})")


def start_echo(cpu: int | None = None) -> tuple[subprocess.Popen, int]:
    proc = subprocess.Popen([sys.executable, "-c", ECHO_SERVER], stdout=subprocess.PIPE, text=True,
                            preexec_fn=on_cpu(cpu))
    assert proc.stdout is not None
    return proc, int(proc.stdout.readline())


CASES = (("best_effort", "best_effort"), ("fixed_step", "fixed_step, between sleeps"),
         ("fixed_step", "fixed_step, flat out"))
TARGET = 2.0


def measure(calls: int, apart: bool = False) -> list[tuple[str, list[float], list[float]]]:
    """(case, morsec's round trips, the echo server's) in seconds, `calls` of each, per case. `apart`: the
    client on the first CPU, both servers on the second (else where the kernel puts them)."""
    results = []
    client_cpus = os.sched_getaffinity(0)
    server_cpu = None
    if apart:
        first, server_cpu = sorted(client_cpus)[:2]
        os.sched_setaffinity(0, {first})
    with tempfile.TemporaryDirectory() as tmp:
        build = Path(tmp) / "build"
        subprocess.run([sys.executable, "-m", "morsec", "build", str(SCENE), "-o", str(build)], check=True,
                       capture_output=True, env=_env())
        echo_proc, echo_port = start_echo(server_cpu)
        echo = Client(echo_port)
        try:
            for strategy, case in CASES:
                proc, port = start_morsec(build, strategy, server_cpu)
                ours = Client(port)
                try:
                    greeted = time.perf_counter()  # the first request: the wall-clock phase starts
                    if ours.call(b"time now").split()[1] != b"SUCCESS":
                        raise SystemExit("morsec did not answer `time now` with SUCCESS")
                    if case.endswith("flat out"):  # past the wall-clock phase of the first request
                        start = time.perf_counter()
                        while time.perf_counter() - start < SLEEP_HOLD_GRACE + 0.2:
                            ours.call(b"time now")
                    for _ in range(50):  # warm-up
                        ours.call(b"time now")
                        echo.call(b"time now")
                    mine, theirs = [], []
                    for _ in range(calls):
                        mine.append(ours.timed(b"time now"))
                        theirs.append(echo.timed(b"time now"))
                    if case.endswith("between sleeps") and time.perf_counter() - greeted > SLEEP_HOLD_GRACE:
                        raise SystemExit(f"{case}: the calls took longer than the wall-clock phase "
                                         f"({SLEEP_HOLD_GRACE:g} s): ask for fewer --calls")
                finally:
                    ours.close()
                    proc.terminate()
                    proc.wait()
                results.append((case, mine, theirs))
        finally:
            echo.close()
            echo_proc.terminate()
            echo_proc.wait()
            os.sched_setaffinity(0, client_cpus)
    return results


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=2000, help="round trips of each side per case")
    parser.add_argument("--apart", action="store_true",
                        help="the client on one CPU and both servers on another (else: the kernel's choice)")
    args = parser.parse_args(argv)
    for case, mine, theirs in measure(args.calls, args.apart):
        ratio = typical(mine) / typical(theirs)
        print(f"`time now` round trip, {case:<26} {typical(mine) * 1e6:6.1f} us (median "
              f"{statistics.median(mine) * 1e6:5.1f}) | selectors echo server {typical(theirs) * 1e6:6.1f} us "
              f"(median {statistics.median(theirs) * 1e6:5.1f}) | ratio {ratio:5.2f} | target <= {TARGET:g} "
              f"{'OK' if ratio <= TARGET else 'ABOVE TARGET'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
