"""Multinode (configure_multinode, docs/multinode.md): a real `morsec multinode-server` and `morsec run --node`
processes on 127.0.0.1. A robot driven on one node is seen moving on the others (their ghost of it, their
semantic cameras); the server holds a node that runs ahead; a node that dies is reported and its robots stay
where they were last seen, while the others go on; MORSE's wire format, its server's delay and pause."""

from __future__ import annotations

import contextlib
import json
import math
import os
import queue
import re
import shutil
import signal
import socket
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest
from runtime_helpers import HOST, MORSEC, Morsec, build_folder, free_port, scene_file, start_all, stop_all

REPO = Path(__file__).resolve().parent.parent
TUTORIAL = REPO / "scenes" / "multinode"
DT = 1 / 60


class Hub:
    """A `morsec multinode-server` subprocess; its stdout lines, one per event."""

    def __init__(self, port: int, *args: str):
        self.port = port
        self.proc = subprocess.Popen([str(MORSEC), "multinode-server", "--port", str(port), *args],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, start_new_session=True)
        self.lines: list[str] = []
        self._queue: queue.Queue = queue.Queue()
        threading.Thread(target=self._pump, daemon=True).start()
        self.wait_for("MULTINODE SERVER")

    def _pump(self) -> None:
        for line in self.proc.stdout:
            self.lines.append(line.rstrip("\n"))
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def wait_for(self, text: str, timeout: float = 60.0) -> str:
        deadline = time.monotonic() + timeout
        for line in self.lines:
            if text in line:
                return line
        while (left := deadline - time.monotonic()) > 0:
            try:
                line = self._queue.get(timeout=left)
            except queue.Empty:
                break
            if line is None:
                break
            if text in line:
                return line
        raise AssertionError(f"the multinode server did not say {text!r}: {self.lines}")

    def type(self, text: str) -> None:
        self.proc.stdin.write(text)
        self.proc.stdin.flush()

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(10)


@contextlib.contextmanager
def hub(*args: str):
    server = Hub(free_port(), *args)
    try:
        yield server
    finally:
        server.stop()


class Peer:
    """A node written by hand, speaking MORSE's wire: `[name, {robot: [[x, y, z], [rx, ry, rz]], "__time": [t,
    dt, wall]}]` out, one answer in."""

    def __init__(self, port: int, name: str):
        self.name = name
        self.sock = socket.create_connection((HOST, port), timeout=20)
        self.file = self.sock.makefile("rb")

    def send(self, robots: dict, t: float | None = None) -> None:
        entries = dict(robots)
        if t is not None:
            entries["__time"] = [t, DT, time.time()]
        self.sock.sendall((json.dumps([self.name, entries]) + "\n").encode())

    def answer(self, timeout: float = 20.0) -> dict:
        self.sock.settimeout(timeout)
        line = self.file.readline()
        assert line, "the server closed the connection"
        return json.loads(line)

    def exchange(self, robots: dict, t: float | None = None) -> dict:
        self.send(robots, t)
        return self.answer()

    def close(self) -> None:
        self.file.close()
        self.sock.close()


def robot(name: str, *components: dict, x: float = 0.0, yaw: float = 0.0) -> dict:
    return {"name": name, "type": "atrv", "translate": [x, 0.0, 0.0], "rotate": [0.0, 0.0, yaw],
            "tags": {"Object": True}, "components": [
                {"name": "pose", "type": "pose", "streams": ["socket"]},
                {"name": "motion", "type": "motion_vw", "streams": ["socket"]}, *components]}


def world(port: int, distribution: dict, robots: list[dict], strategy: str = "best_effort") -> dict:
    return {"environment": {"name": "empty", "time": {"strategy": strategy, "relative": True},
                            "multinode": {"server_address": HOST, "server_port": port,
                                          "distribution": distribution}},
            "robots": robots}


def node(build: Path, tmp_path: Path, name: str, *args: str) -> Morsec:
    return Morsec(build, tmp_path, args=("--node", name, *args))


def poses(sim: Morsec) -> dict[str, list[float]]:
    with sim.client() as client:
        return {name: entry[1] for name, entry in client.ok("simulation", "get_scene_objects").items()}


def now(sim: Morsec) -> float:
    with sim.client() as client:
        return client.ok("time", "now")


def eventually(check, timeout: float = 30.0, every: float = 0.1):
    deadline = time.monotonic() + timeout
    while True:
        value = check()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(every)


# ------------------------------------------------------------------------------------------- two nodes
def test_a_robot_driven_on_one_node_moves_on_the_other(tmp_path):
    """dala1 is simulated by nodeA, dala2 (looking at dala1, 5 m away) by nodeB. Driven on nodeA, dala1 moves
    on nodeB too: its ghost's pose, nodeB's semantic camera and proximity sensor follow it; each node serves
    only its own robot's streams."""
    camera = {"name": "camera", "type": "semantic_camera", "translate": [0.3, 0.0, 0.8], "streams": ["socket"]}
    proximity = {"name": "proximity", "type": "proximity", "streams": ["socket"], "properties": {"Range": 10.0}}
    with hub() as server:
        scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"]},
                      [robot("dala1"), robot("dala2", camera, proximity, x=5.0, yaw=math.pi)])
        build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
        a, b = start_all(node(build, tmp_path, "nodeA"), node(build, tmp_path, "nodeB"))
        try:
            assert set(a.streams) == {"dala1.pose", "dala1.motion"}
            assert set(b.streams) == {"dala2.pose", "dala2.motion", "dala2.camera", "dala2.proximity"}
            server.wait_for("node nodeA connected")
            server.wait_for("node nodeB connected")
            start = poses(b)["dala1"]
            with a.stream("dala1.motion") as motion, b.stream("dala2.camera") as camera_stream, \
                    b.stream("dala2.proximity") as proximity_stream:
                motion.send('{"v": 1.0, "w": 0.0}\n')
                assert eventually(lambda: poses(a)["dala1"][0] > 1.5), poses(a)
                motion.send('{"v": 0.0, "w": 0.0}\n')
                time.sleep(0.5)  # stopped, on both nodes
                own, ghost = poses(a)["dala1"], poses(b)["dala1"]
                assert ghost == pytest.approx(own, abs=0.01)  # where nodeA has it, not fallen, not pushed
                assert ghost[0] - start[0] > 1.4
                camera_stream.drain()
                seen = {o["name"]: o["position"] for o in camera_stream.json()["visible_objects"]}
                assert seen["dala1"] == pytest.approx(own, abs=0.01)
                proximity_stream.drain()
                near = proximity_stream.json()["near_objects"]
                assert near["dala1"] == pytest.approx(math.dist(own, poses(b)["dala2"]), abs=0.01)
            with b.client() as client:  # nodeB runs none of dala1's components
                robots = {r["name"]: r for r in client.ok("simulation", "details")["robots"]}
                assert robots["dala1"]["components"] == {} and "dala2.camera" in robots["dala2"]["components"]
        finally:
            stop_all(a, b)


def test_a_ghost_is_kinematic_its_owner_alone_moves_it(tmp_path):
    """nodeB drives dala2 into dala1, which nodeA simulates standing still: on nodeB dala1 is a kinematic
    ghost, a wall dala2 cannot pass through nor push (it does not collide a second time there)."""
    with hub() as server:
        scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"]},
                      [robot("dala1"), robot("dala2", x=4.0, yaw=math.pi)])
        build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
        a, b = start_all(node(build, tmp_path, "nodeA"), node(build, tmp_path, "nodeB"))
        try:
            with b.stream("dala2.motion") as motion:
                motion.send('{"v": 1.0, "w": 0.0}\n')
                time.sleep(1.0)
                assert eventually(lambda: now(b) > 6.0, timeout=60)  # long enough to have gone 2 m past dala1
                on_b = poses(b)
                motion.send('{"v": 0.0, "w": 0.0}\n')
            on_a = poses(a)
            assert on_b["dala2"][0] - on_b["dala1"][0] > 0.6  # stopped by the ghost: ATRVs are about 1 m long
            assert on_b["dala1"] == pytest.approx(on_a["dala1"], abs=0.05)
            assert abs(on_b["dala1"][2] - on_a["dala1"][2]) < 0.01
        finally:
            stop_all(a, b)


# ------------------------------------------------------------------------------------------- time
def test_nodes_in_fixed_step_keep_the_same_time(tmp_path):
    """Two nodes as fast as their machine allows: at every answer of the server, seen by an observer (a peer
    that sends no time), their simulated times are within one frame of each other."""
    with hub() as server:
        scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"]},
                      [robot("dala1"), robot("dala2", x=5.0)], strategy="fixed_step")
        build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
        a, b = start_all(node(build, tmp_path, "nodeA"), node(build, tmp_path, "nodeB"))
        observer = Peer(server.port, "observer")
        try:
            seen = []
            while len(seen) < 300:
                nodes = observer.exchange({})["__nodes"]
                if {"nodeA", "nodeB"} <= set(nodes):
                    seen.append((nodes["nodeA"]["time"], nodes["nodeB"]["time"]))
                time.sleep(0.005)
            assert all(abs(ta - tb) <= DT + 1e-6 for ta, tb in seen), max(abs(ta - tb) for ta, tb in seen)
            assert seen[-1][0] > seen[0][0] + 0.5  # and time went on
        finally:
            observer.close()
            stop_all(a, b)


@pytest.mark.parametrize("strategy", ["best_effort", "fixed_step"])
def test_a_node_running_ahead_is_held(tmp_path, strategy):
    """nodeB is a peer written by hand, at simulated time 0.5 s: nodeA goes no further than one frame past it,
    in either time strategy, until nodeB's time moves on. nodeB's robot, sent in MORSE's format, is where
    nodeA places its ghost, and nodeA's robot comes back in the same format."""
    with hub() as server:
        scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"]},
                      [robot("dala1"), robot("dala2", x=5.0)], strategy=strategy)
        build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
        peer = Peer(server.port, "nodeB")
        dala2 = {"dala2": [[3.0, 2.0, 0.1], [0.0, 0.0, 1.0]]}
        peer.exchange(dala2, 0.5)
        with node(build, tmp_path, "nodeA") as a:
            try:
                time.sleep(1.5)  # best_effort: a second past 0.5 s; fixed_step: thousands of frames
                held = now(a)
                assert 0.5 - 1e-6 <= held <= 0.5 + DT + 1e-6
                answer = peer.exchange(dala2, 1.0)
                position, euler = answer["dala1"]
                assert len(position) == 3 and len(euler) == 3 and abs(position[2] - 0.1) < 0.02
                assert eventually(lambda: now(a) >= 1.0 - 1e-6)
                time.sleep(0.5)
                assert now(a) <= 1.0 + DT + 1e-6
                ghost = poses(a)["dala2"]
                assert ghost == pytest.approx([3.0, 2.0, 0.1], abs=1e-6)
            finally:
                peer.close()


# ------------------------------------------------------------------------------------------- a node dies
def test_a_node_killed_is_reported_and_the_others_go_on(tmp_path):
    """Three nodes; nodeB is killed after its robot moved. The server and the other nodes say so, nodeB's
    robot stays where it was last seen, and nodeA and nodeC go on."""
    with hub() as server:
        scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"], "nodeC": ["dala3"]},
                      [robot("dala1"), robot("dala2", x=5.0), robot("dala3", x=-5.0)])
        build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
        a, b, c = start_all(*(node(build, tmp_path, name) for name in ("nodeA", "nodeB", "nodeC")))
        try:
            with b.stream("dala2.motion") as motion:
                motion.send('{"v": 1.0, "w": 0.0}\n')
                assert eventually(lambda: poses(a)["dala2"][0] > 6.0), poses(a)
                os.kill(b.pid, signal.SIGKILL)
                b.wait()
            server.wait_for("node nodeB left at simulated time")
            for other in (a, c):
                assert eventually(lambda o=other: any("node nodeB left" in line and "dala2" in line
                                                      for line in o.stderr)), other.output()
            last = {sim: poses(sim)["dala2"] for sim in (a, c)}
            times = {sim: now(sim) for sim in (a, c)}
            time.sleep(1.0)
            for sim in (a, c):
                assert now(sim) > times[sim] + 0.5  # it goes on
                assert poses(sim)["dala2"] == last[sim]  # frozen where last seen
                assert last[sim][0] > 6.0
            assert last[a] == pytest.approx(last[c], abs=1e-9)
        finally:
            stop_all(a, b, c)


def test_nodes_go_on_alone_when_the_server_stops(tmp_path):
    """The server stopped: each node says so once and goes on, the other nodes' robots where last seen."""
    server = Hub(free_port())
    scene = world(server.port, {"nodeA": ["dala1"], "nodeB": ["dala2"]}, [robot("dala1"), robot("dala2", x=5.0)])
    build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
    peer = Peer(server.port, "nodeB")
    try:
        peer.exchange({"dala2": [[4.0, 1.0, 0.1], [0.0, 0.0, 0.0]]}, 0.0)
        with node(build, tmp_path, "nodeA") as a:
            assert eventually(lambda: poses(a)["dala2"] == pytest.approx([4.0, 1.0, 0.1], abs=1e-6))
            server.stop()
            assert eventually(lambda: any("multinode server at 127.0.0.1" in line and "lost" in line
                                          for line in a.stderr)), a.output()
            before = now(a)
            time.sleep(0.5)
            assert now(a) > before + 0.2
            assert poses(a)["dala2"] == pytest.approx([4.0, 1.0, 0.1], abs=1e-6)
    finally:
        peer.close()
        server.stop()


# ------------------------------------------------------------------------------------------- the server
def test_the_server_speaks_morses_wire_and_checks_poses():
    """MORSE's multinode_server: each node gets the other nodes' robots back (not its own), and a pose that
    is not three finite numbers twice is discarded."""
    with hub() as server:
        one, two = Peer(server.port, "node1"), Peer(server.port, "node2")
        try:
            first = one.exchange({"robot1": [[0, 0, 0], [0, 0, 0]]}, 0.0)
            assert set(first) == {"__time", "__nodes"}
            answer = two.exchange({"robot2": [[1, 2, 3], [0.1, 0.2, 0.3]], "robot3": [[1, 2], [0, 0, 0]]}, 0.0)
            assert answer["robot1"] == [[0, 0, 0], [0, 0, 0]] and "robot2" not in answer
            # NaN is not JSON but Python's json writes and reads it: MORSE's server refused non-finite poses
            two.sock.sendall(b'["node2", {"robot2": [[NaN, 0, 0], [0, 0, 0]], "__time": [0.0, 0.01, 0.0]}]\n')
            two.answer()
            answer = one.exchange({"robot1": [[0, 0, 0], [0, 0, 0]]}, 0.0)
            assert answer["robot2"] == [[1, 2, 3], [0.1, 0.2, 0.3]] and "robot3" not in answer
            assert answer["__nodes"]["node2"] == {"time": 0.0, "connected": True}
            server.wait_for("node2: entries that are not poses were discarded: robot3")
        finally:
            one.close()
            two.close()


def test_the_server_delay_slows_and_p_pauses_every_node():
    """`morsec multinode-server 0.2`: two answers to a node at least 0.2 s apart; p then Enter on its terminal
    holds every answer until p again (MORSE's)."""
    with hub("0.2") as server:
        peer = Peer(server.port, "node1")
        try:
            peer.exchange({}, 0.0)
            started = time.monotonic()
            peer.exchange({}, 0.01)
            peer.exchange({}, 0.02)
            assert time.monotonic() - started >= 0.4 - 0.01
            server.type("p\n")
            server.wait_for("paused")
            peer.send({}, 0.03)
            peer.sock.settimeout(1.0)
            with pytest.raises(TimeoutError):
                peer.sock.recv(1)  # (a file object cannot be read again once it timed out)
            server.type("p\n")
            server.wait_for("running")
            assert "__time" in peer.answer()
        finally:
            peer.close()


# ------------------------------------------------------------------------------------------- mistakes
def test_a_node_without_its_server_stops_in_one_line(tmp_path):
    scene = world(free_port(), {"nodeA": ["dala1"]}, [robot("dala1")])
    build = build_folder(scene_file(tmp_path, scene), tmp_path / "build")
    result = subprocess.run([str(MORSEC), "run", str(build), "--node", "nodeA", "--service-port", "0",
                             "--port-base", "0"], capture_output=True, text=True, timeout=120)
    assert result.returncode == 1, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: cannot reach the multinode server at 127.0.0.1:"), lines
    assert "morsec multinode-server" in lines[0]


def test_node_on_a_scene_that_is_not_split_is_an_error(tmp_path):
    build = build_folder(scene_file(tmp_path, {"robots": [robot("dala1")]}), tmp_path / "build")
    result = subprocess.run([str(MORSEC), "run", str(build), "--node", "nodeA"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [
        "error: --node nodeA: the scene is not split over nodes (no environment.multinode, MORSE's "
        "configure_multinode)"]


def test_a_busy_server_port_is_one_line(tmp_path):
    with hub() as server:
        result = subprocess.run([str(MORSEC), "multinode-server", "--port", str(server.port)], capture_output=True,
                                text=True, timeout=60, stdin=subprocess.DEVNULL)
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [f"error: cannot listen on 127.0.0.1:{server.port}: Address "
                                                  "already in use"]


# ------------------------------------------------------------------------------------------- the tutorial
def test_the_tutorial_scene_and_its_yaml_twin_are_the_same_scene():
    from morsec.component.catalogue import load_catalogue
    from morsec.frontends.load import load_scene
    cat = load_catalogue(TUTORIAL)
    script = load_scene(TUTORIAL / "tutorial-socket.py", cat).model_dump()
    twin = load_scene(TUTORIAL / "tutorial-socket.yaml", cat).model_dump()
    assert script == twin
    assert script["environment"]["multinode"]["distribution"] == {"nodeA": ["atrv"], "nodeB": ["atrv_001"]}


def tutorial_client() -> str:
    """The client of docs/multinode.md's tutorial (its python block)."""
    page = (REPO / "docs" / "multinode.md").read_text(encoding="utf-8")
    section = page.split("## MORSE's tutorial", 1)[1]
    block = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    return textwrap.dedent(block)


def test_morses_multinode_tutorial_runs_as_docs_multinode_prints_it(tmp_path):
    """docs/multinode.md's tutorial, in a copy of scenes/multinode: `morsec multinode-server 0.01`, then
    `export PYTHONPATH=$PYTHONPATH:.`, `export MORSE_NODE=nodeA` (then nodeB) and `morsec run tutorial-socket.py`,
    on the default ports; the page's client drives nodeA's robot two metres, and both nodes have it there."""
    folder = tmp_path / "multinode"
    shutil.copytree(TUTORIAL, folder, ignore=shutil.ignore_patterns("build", "__pycache__"))
    (folder / "drive.py").write_text(tutorial_client(), encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([os.environ.get("PYTHONPATH", ""), "."]), PYTHONUNBUFFERED="1")
    server = subprocess.Popen([str(MORSEC), "multinode-server", "0.01"], stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, text=True, start_new_session=True)
    nodes: list[Morsec] = []
    try:
        assert server.stdout.readline().startswith("MULTINODE SERVER 127.0.0.1:65000")
        for name in ("nodeA", "nodeB"):  # nodeA first: it has the service port 4000
            sim = Morsec(folder / "tutorial-socket.py", folder, cwd=folder, prebuild=False, service_port="auto")
            sim.command = [str(MORSEC), "run", "tutorial-socket.py"]
            sim.proc = subprocess.Popen(sim.command, cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                        text=True, env={**env, "MORSE_NODE": name}, start_new_session=True)
            for pipe, sink, forward in ((sim.proc.stdout, sim.stdout, True), (sim.proc.stderr, sim.stderr, False)):
                threading.Thread(target=sim._pump, args=(pipe, sink, forward), daemon=True).start()
            nodes.append(sim.wait_ready())
        a, b = nodes
        assert (a.service_port, b.service_port) == (4000, 4001)
        assert a.port("atrv.motion") == 60001 and b.port("atrv_001.motion") == 60005
        assert "atrv_001.motion" not in a.streams and "atrv.motion" not in b.streams
        result = subprocess.run([sys.executable, "drive.py"], cwd=folder, capture_output=True, text=True,
                                timeout=120)
        assert result.returncode == 0, result.stderr
        printed = dict(line.split(": ", 1) for line in result.stdout.splitlines())
        on_a, on_b = json.loads(printed["nodeA"]), json.loads(printed["nodeB"])
        assert 1.8 < on_a[0] < 2.6 and on_b == pytest.approx(on_a, abs=0.02)
    finally:
        stop_all(*nodes)
        server.terminate()
        server.wait(10)
