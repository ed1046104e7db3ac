"""A service's round trip against an echo server's, side by side in one run (issue 14's row, target <= 2):

- morsec: `morsec run` of the reference scene (an ATRV with pose, odometry and motion_vw at 60 Hz, socket
  streams) answering `time now` on its service port, in three cases:
  - best_effort: the loop waits for the wall clock between frames, and answers while it waits;
  - fixed_step, a client between sleeps: from a client's first request (and after each of its sleeps) the
    loop follows the wall clock for SLEEP_HOLD_GRACE (docs/running.md), and answers as best_effort does;
  - fixed_step, flat out: after that, with no sleep asked, frames run back to back; the sockets are polled
    between every two frames while requests come, so an answer waits for the frame running when its
    request arrived (half a frame on average);
- anchor: a single-threaded `selectors` echo server in its own Python process, answering each line.

The client is the same for both: one TCP connection (TCP_NODELAY), one request in flight, the next sent when
the answer's line is read. Batches of --calls round trips alternate between the sides so that both see the
same machine load; the best batch's mean of each side is kept.

    python benchmarks/round_trip.py [--calls 500] [--repeats 7]
"""

from __future__ import annotations

import argparse
import os
import socket
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

    def batch(self, request: bytes, calls: int) -> float:
        """Mean seconds of one round trip over `calls`."""
        start = time.perf_counter()
        for _ in range(calls):
            self.call(request)
        return (time.perf_counter() - start) / calls

    def close(self) -> None:
        self.lines.close()
        self.sock.close()


def start_morsec(build: Path, strategy: str) -> tuple[subprocess.Popen, int]:
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-m", "morsec", "run", str(build), "--time-strategy", strategy,
                             "--service-port", str(port), "--port-base", "0"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert proc.stdout is not None
    for line in proc.stdout:
        if "SCENE INITIALIZED" in line:
            return proc, port
    raise SystemExit(f"morsec run ended before SCENE INITIALIZED (exit {proc.wait()})")


def start_echo() -> tuple[subprocess.Popen, int]:
    proc = subprocess.Popen([sys.executable, "-c", ECHO_SERVER], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    return proc, int(proc.stdout.readline())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=200, help="round trips per batch")
    parser.add_argument("--repeats", type=int, default=7, help="batches of each side; the best is kept")
    args = parser.parse_args(argv)

    env_path = os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])])
    os.environ["PYTHONPATH"] = env_path
    with tempfile.TemporaryDirectory() as tmp:
        build = Path(tmp) / "build"
        subprocess.run([sys.executable, "-m", "morsec", "build", str(SCENE), "-o", str(build)], check=True,
                       capture_output=True)
        echo_proc, echo_port = start_echo()
        echo = Client(echo_port)
        try:
            for strategy, case in (("best_effort", "best_effort"), ("fixed_step", "fixed_step, between sleeps"),
                                   ("fixed_step", "fixed_step, flat out")):
                proc, port = start_morsec(build, strategy)
                ours = Client(port)
                try:
                    if ours.call(b"time now").split()[1] != b"SUCCESS":
                        raise SystemExit("morsec did not answer `time now` with SUCCESS")
                    if case.endswith("flat out"):  # past the wall-clock phase of the first request
                        start = time.perf_counter()
                        while time.perf_counter() - start < SLEEP_HOLD_GRACE + 0.2:
                            ours.call(b"time now")
                    best_ours = best_echo = float("inf")
                    for _ in range(args.repeats):
                        best_ours = min(best_ours, ours.batch(b"time now", args.calls))
                        best_echo = min(best_echo, echo.batch(b"time now", args.calls))
                finally:
                    ours.close()
                    proc.terminate()
                    proc.wait()
                ratio = best_ours / best_echo
                verdict = "OK" if ratio <= 2 else "ABOVE TARGET"
                print(f"`time now` round trip, {case:<26} {best_ours * 1e3:7.3f} ms | selectors echo server "
                      f"{best_echo * 1e3:7.3f} ms | ratio {ratio:5.2f} | target <= 2 {verdict}")
        finally:
            echo.close()
            echo_proc.terminate()
            echo_proc.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
