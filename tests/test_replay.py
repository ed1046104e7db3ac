"""`morsec replay run.mcap`: a recording's sensor streams served again on the socket ports of its scene, in
simulated-time order at the recorded pace (or --rate), for a client to be tested against a fixed input: a real
`morsec run --record` with a client driving the robot, then a real `morsec replay` and morsec.client reading it."""

from __future__ import annotations

import json
import queue
import subprocess
import threading
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader
from mcap.writer import Writer

from morsec.app.replay import Replay, ReplayOptions
from morsec.client import Morse
from morsec.constants import STREAM_PORT_BASE
from tests.runtime_helpers import MORSEC, Morsec, free_port, free_ports, scene, scene_file


@pytest.fixture(scope="module")
def recorded(tmp_path_factory) -> dict:
    """Two simulated seconds of a robot turning (fixed_step, from its command on), recorded; its pose messages
    and socket ports."""
    folder = tmp_path_factory.mktemp("replay")
    path = folder / "turning.mcap"
    with Morsec(scene_file(folder, scene()), folder, args=["--record", path, "--wait-for-client"]) as sim:
        client = sim.client()
        with sim.stream("robot.motion") as motion:
            motion.send('{"v": 1.0, "w": 0.5}\n')
            client.ok("time", "sleep", 2.0)
        client.ok("simulation", "quit")
        assert sim.wait(60) == 0, sim.output()
        ports = {fqn: port for fqn, (_, port) in sim.streams.items()}
    with open(path, "rb") as f:
        poses = [json.loads(m.data) for _, _, m in make_reader(f).iter_messages(topics=["robot.pose"])]
    manifest = json.loads((folder / "build-scene" / "manifest.json").read_text())
    return {"path": path, "poses": poses, "ports": {s["component"]: s["endpoint"]["port"] for s in manifest["streams"]},
            "run_ports": ports, "base": sim.port_base}


class Replaying:
    """`morsec replay` as a child process: its announced table, its output, its exit."""

    def __init__(self, path: Path, *args: str):
        self.service_port = free_port()
        self.port_base = free_ports(20)
        self.proc = subprocess.Popen([str(MORSEC), "replay", str(path), "--service-port", str(self.service_port),
                                      "--port-base", str(self.port_base), *args],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue = queue.Queue()
        self.stdout: list[str] = []
        threading.Thread(target=self._pump, daemon=True).start()
        self.streams: dict[str, int] = {}
        while (line := self.lines.get(timeout=60)) != "SCENE INITIALIZED":
            assert line is not None, self.proc.stderr.read()
        self.ready_at = time.monotonic()
        while (line := self.lines.get(timeout=10)) is not None and line.startswith("  "):
            parts = line.split()
            if len(parts) == 4:
                self.streams[parts[0]] = int(parts[3].rsplit(":", 1)[1])
            if "waiting" in line:
                break

    def _pump(self) -> None:
        for line in self.proc.stdout:
            self.stdout.append(line.rstrip("\n"))
            self.lines.put(line.rstrip("\n"))
        self.lines.put(None)

    def wait(self, timeout: float = 60) -> int:
        code = self.proc.wait(timeout)
        self.ended_at = time.monotonic()
        return code

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            self.proc.wait(20)


def test_a_client_reads_the_recorded_pose_stream_from_the_replay(recorded):
    replay = Replaying(recorded["path"], "--wait-for-client")
    try:
        # the recording's socket ports, moved by --port-base as `morsec run --port-base` moves them
        for fqn in ("robot.pose", "robot.motion"):
            assert replay.streams[fqn] - replay.port_base == recorded["ports"][fqn] - STREAM_PORT_BASE
        with Morse(port=replay.service_port) as sim:
            got = [sim.robot.pose.get(timeout=10) for _ in range(30)]
            first = recorded["poses"].index(got[0])
            assert got == recorded["poses"][first:first + 30]  # the recorded values, in order, none missed
            assert got[-1]["x"] > got[0]["x"]  # the robot moving, as it was recorded
            sim.robot.motion.publish({"v": 5.0, "w": 0.0})  # commands are accepted, and change nothing
            before = sim.time()
            sim.sleep(0.25)  # in the recording's time
            after = sim.time()
            assert after - before >= 0.25 - 1e-6
            assert recorded["poses"][0]["timestamp"] <= before <= recorded["poses"][-1]["timestamp"]
            later = sim.robot.pose.get(timeout=10)
            assert later in recorded["poses"] and later["timestamp"] >= after - 0.02
        assert replay.wait() == 0
        assert replay.stdout[-1] == "EXITING SIMULATION"
        assert replay.stdout[-2].startswith(f"replayed {len(recorded['poses'])} messages")
    finally:
        replay.stop()


def test_the_replay_keeps_the_recorded_pace_or_the_rate(recorded):
    """Lower bounds only (a loaded machine may only make it later): the recording's span, divided by the rate."""
    span = recorded["poses"][-1]["timestamp"] - recorded["poses"][0]["timestamp"]
    assert span >= 1.9
    for rate in (1.0, 4.0):
        replay = Replaying(recorded["path"], "--rate", str(rate))
        try:
            assert replay.wait() == 0
            assert replay.ended_at - replay.ready_at >= span / rate - 0.05
            assert replay.stdout[-2].startswith(f"replayed {len(recorded['poses'])} messages (0 sent to clients)")
        finally:
            replay.stop()


def test_without_port_base_the_replay_serves_on_the_recorded_ports(recorded):
    replay = Replay(recorded["path"], ReplayOptions(service_port=0))
    try:
        assert replay.socket.ports() == {c: p for c, p in recorded["ports"].items()}
        details = replay.details()
        assert details["robots"][0]["components"]["robot.pose"]["stream_interfaces"] == [
            ["morsec.middleware.socket", "OUT"]]
        assert "services" not in details["robots"][0]["components"]["robot.motion"]  # nothing runs them
    finally:
        replay.close()


def test_a_file_that_is_not_a_recording_is_refused_in_one_line(tmp_path):
    plain = tmp_path / "plain.mcap"
    with open(plain, "wb") as f:
        writer = Writer(f)
        writer.start()
        writer.finish()
    text = tmp_path / "scene.mcap"
    text.write_text("robots: []\n")
    for path, message in ((tmp_path / "missing.mcap", "No such file or directory"),
                          (text, "not a readable MCAP file"),
                          (plain, "not a recording made by `morsec run --record` (no morsec metadata)")):
        result = subprocess.run([str(MORSEC), "replay", str(path)], capture_output=True, text=True, timeout=60)
        assert result.returncode == 2, result.stderr
        assert result.stderr.startswith(f"error: {path}: ") and message in result.stderr
        assert len(result.stderr.strip().splitlines()) == 1
    bad_rate = subprocess.run([str(MORSEC), "replay", str(plain), "--rate", "0"], capture_output=True, text=True,
                              timeout=60)
    assert bad_rate.returncode == 2 and bad_rate.stderr.strip() == "error: --rate must be a positive number, got 0.0"


def test_info_lists_what_the_recording_holds(recorded):
    result = subprocess.run([str(MORSEC), "replay", str(recorded["path"]), "--info"], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    head, *rows = result.stdout.splitlines()
    assert head.startswith(f"{recorded['path']}: ") and "simulated s" in head and "since the Unix epoch" in head
    table = {row.split()[0]: row.split()[1:] for row in rows}
    assert table["robot.pose"] == [str(len(recorded["poses"])), "json", "morsec/sensors/pose", "(jsonschema)"]
    assert table["/robot/pose"] == [str(len(recorded["poses"])), "cdr", "geometry_msgs/msg/PoseStamped", "(ros2msg)"]
    assert table["robot.motion"][:2] == ["1", "json"]


def test_a_stream_recorded_from_a_text_stream_is_served_on_a_free_port(tmp_path):
    pose = {"name": "pose", "type": "pose", "streams": [{"middleware": "text", "file": "pose.txt"}]}
    motion = {"name": "motion", "type": "motion_vw", "streams": ["socket"]}
    source = scene_file(tmp_path, scene({"name": "robot", "type": "atrv", "components": [pose, motion]}))
    path = tmp_path / "text.mcap"
    result = subprocess.run([str(MORSEC), "run", str(source), "--duration", "0.2", "--record", str(path),
                             "--port-base", "0", "--service-port", "0"], capture_output=True, text=True, timeout=120,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    replay = Replay(path, ReplayOptions(service_port=0))
    try:
        assert replay.socket.ports() == {"robot.motion": STREAM_PORT_BASE, "robot.pose": STREAM_PORT_BASE + 1}
    finally:
        replay.close()
