"""A service's round trip against an echo server's, side by side in one run (issue 14's row, target <= 2):

- morsec: `morsec run` of the reference scene (an ATRV with pose, odometry and motion_vw at 60 Hz, socket
  streams) in fixed_step, then in best_effort, answering `time now` on its service port;
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
    parser.add_argument("--calls", type=int, default=500, help="round trips per batch")
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
            for strategy in ("fixed_step", "best_effort"):
                proc, port = start_morsec(build, strategy)
                ours = Client(port)
                try:
                    if ours.call(b"time now").split()[1] != b"SUCCESS":
                        raise SystemExit("morsec did not answer `time now` with SUCCESS")
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
                print(f"`time now` round trip, {strategy:<11} {best_ours * 1e3:7.3f} ms | selectors echo server "
                      f"{best_echo * 1e3:7.3f} ms | ratio {ratio:5.2f} | target <= 2 {verdict}")
        finally:
            echo.close()
            echo_proc.terminate()
            echo_proc.wait()
    return 0


if __name__ == "__main__":
    sys.exit(main())
