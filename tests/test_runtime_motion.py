"""Motion semantics, measured in simulated time from the streams' timestamps, in both time strategies:
motion_vw (the issue's numbers), teleport (stream and relative services), odometry at its three levels."""

from __future__ import annotations

import json
import math
import threading
import time

import pytest
from runtime_helpers import LineSocket, Morsec, pose_sensor, robot, scene, scene_file, start_all, stop_all, wrap

STRATEGIES = ["fixed_step", "best_effort"]
MOTION = {"name": "motion", "type": "motion_vw", "streams": ["socket"], "services": ["socket"]}
FRAME = [0.2, 0.0, 0.3]  # where the teleport actuator and the pose sensor reading it are mounted


def motion_scene(strategy: str) -> dict:
    odometry = [{"name": f"odo_{level}", "type": "odometry", "level": level, "streams": ["socket"]}
                for level in ("raw", "differential", "integrated")]
    return scene(
        robot("straight", pose_sensor(), MOTION),
        robot("turner", pose_sensor(), MOTION, translate=[0.0, 6.0, 0.0]),
        robot("odo", pose_sensor(), MOTION, *odometry, translate=[5.0, 3.0, 0.0], rotate=[0.0, 0.0, 1.0]),
        robot("tele", pose_sensor("frame", translate=FRAME),
              {"name": "teleport", "type": "teleport", "translate": FRAME, "streams": ["socket"], "services": ["socket"]},
              translate=[0.0, -6.0, 0.0]),
        strategy=strategy)


@pytest.fixture(scope="module")
def servers(tmp_path_factory):
    sims = {}
    for strategy in STRATEGIES:
        tmp = tmp_path_factory.mktemp(f"motion-{strategy}")
        sims[strategy] = Morsec(scene_file(tmp, motion_scene(strategy)), tmp)
    start_all(*sims.values())
    try:
        yield sims
    finally:
        stop_all(*sims.values())


@pytest.fixture(params=STRATEGIES)
def sim(request, servers):
    process = servers[request.param]
    assert process.alive(), process.output()
    return process


ODOMETRY = ("pose", "odo_raw", "odo_differential", "odo_integrated")
_driven: dict[str, dict] = {}


@pytest.fixture
def driven(sim) -> dict[str, list[dict]]:
    """One drive per simulation, for 2.5 simulated seconds: straight (v=1, w=0), turner (v=1, w=-pi/4)
    and odo (v=1, w=0.5) together; every message of their sensors, by fqn."""
    if str(sim.build) not in _driven:
        fqns = ["straight.pose", "turner.pose"] + [f"odo.{name}" for name in ODOMETRY]
        recorders = {fqn: Recorder(sim, fqn) for fqn in fqns}
        _driven[str(sim.build)] = drive(sim, {"straight": {"v": 1.0, "w": 0.0},
                                              "turner": {"v": 1.0, "w": -math.pi / 4},
                                              "odo": {"v": 1.0, "w": 0.5}}, 2.5, recorders)
    return _driven[str(sim.build)]


class Recorder:
    """Every message of a stream, from now on, read by a thread."""

    def __init__(self, sim, fqn: str):
        self.socket = LineSocket(sim.port(fqn), timeout=30)
        self.messages: list[dict] = []
        self.running = True
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self):
        while self.running:
            try:
                self.messages.append(json.loads(self.socket.raw_line(timeout=0.5)))
            except TimeoutError:
                continue
            except (ConnectionError, OSError, ValueError):
                return

    def stop(self) -> list[dict]:
        self.running = False
        self.thread.join(5)
        self.socket.close()
        return self.messages

    def wait(self, count: int = 3) -> None:
        deadline = time.monotonic() + 15
        while len(self.messages) < count:
            assert time.monotonic() < deadline, "no messages"
            time.sleep(0.01)


def drive(sim, commands: dict[str, dict], seconds: float, recorders: dict[str, Recorder]) -> dict[str, list]:
    """Send each robot's motion command, let `seconds` of simulated time pass, stop, return the records."""
    for r in recorders.values():
        r.wait()
    actuators = {name: LineSocket(sim.port(f"{name}.motion")) for name in commands}
    try:
        for name, command in commands.items():
            actuators[name].send(json.dumps(command) + "\n")
        with sim.client() as client:
            client.ok("time", "sleep", seconds, timeout=30)
        for socket in actuators.values():
            socket.send('{"v": 0.0, "w": 0.0}\n')
        with sim.client() as client:
            client.ok("time", "sleep", 0.2, timeout=30)  # the stop applied, recorded
    finally:
        for socket in actuators.values():
            socket.close()
    return {fqn: r.stop() for fqn, r in recorders.items()}


def start_index(poses: list[dict]) -> int:
    """Index of the last message before the robot started moving (the command applied next frame)."""
    x0, y0 = poses[0]["x"], poses[0]["y"]
    for i, p in enumerate(poses):
        if math.hypot(p["x"] - x0, p["y"] - y0) > 2e-3:
            assert i > 0, "the robot moved before the command"
            return i - 1
    raise AssertionError("the robot never moved")


def at(messages: list[dict], t: float) -> dict:
    """The message stamped closest to t."""
    best = min(messages, key=lambda m: abs(m["timestamp"] - t))
    assert abs(best["timestamp"] - t) < 0.02, f"no message near {t}"
    return best


def relative(origin: dict, p: dict) -> tuple[float, float, float]:
    """(x, y, yaw) of pose p in the frame of pose `origin` (2D)."""
    c, s = math.cos(origin["yaw"]), math.sin(origin["yaw"])
    dx, dy = p["x"] - origin["x"], p["y"] - origin["y"]
    return c * dx + s * dy, -s * dx + c * dy, wrap(p["yaw"] - origin["yaw"])


def test_motion_vw_issue_numbers(sim, driven):
    for name, (ex, ey, eyaw) in {"straight": (2.0, 0.0, 0.0),
                                 "turner": (4 / math.pi, -4 / math.pi, -math.pi / 2)}.items():
        poses = driven[f"{name}.pose"]
        rest = poses[start_index(poses)]
        x, y, yaw = relative(rest, at(poses, rest["timestamp"] + 2.0))
        assert (x, y, yaw) == pytest.approx((ex, ey, eyaw), abs=0.1), (name, sim.command)
        assert abs(rest["z"]) < 0.02 and abs(at(poses, rest["timestamp"] + 2.0)["z"]) < 0.02  # on the ground


def test_teleport(sim):
    with LineSocket(sim.port("tele.frame")) as frame, LineSocket(sim.port("tele.teleport")) as teleport, \
            sim.client() as client:

        def settled() -> dict:
            client.ok("time", "sleep", 0.1, timeout=30)  # the command applied
            frame.drain()
            return frame.json()

        teleport.send('{"x": 1.0, "y": -5.0, "z": 1.0, "roll": 0.1, "pitch": 0.0, "yaw": 0.7}\n')
        p = settled()
        assert [p[k] for k in ("x", "y", "z", "roll", "pitch", "yaw")] == \
            pytest.approx([1.0, -5.0, 1.0, 0.1, 0.0, 0.7], abs=0.01)
        client.ok("time", "sleep", 0.5, timeout=30)
        p = settled()
        assert p["z"] == pytest.approx(1.0, abs=0.01)  # held there every tick: it does not fall
        client.ok("tele.teleport", "translate", 0.5, 0.25, 0.0)
        client.ok("tele.teleport", "rotate", -0.1, 0.0, 0.3)
        p = settled()
        assert [p[k] for k in ("x", "y", "z", "roll", "pitch", "yaw")] == \
            pytest.approx([1.5, -4.75, 1.0, 0.0, 0.0, 1.0], abs=0.01)
        client.ok("tele.teleport", "translate", -1.3, -1.25, -0.6)  # back to where it started, on the ground
        client.ok("tele.teleport", "rotate", 0.0, 0.0, -1.0)
        p = settled()
        assert [p[k] for k in ("x", "y", "z", "yaw")] == pytest.approx([0.2, -6.0, 0.4, 0.0], abs=0.01)


def test_odometry_levels(sim, driven):
    poses, raw, diff, integ = (driven[f"odo.{name}"] for name in ODOMETRY)
    assert list(integ[0])[:4] == ["timestamp", "x", "y", "z"] and "dS" in raw[0] and "dyaw" in diff[0]
    # the integrated level starts at 0 whatever the robot's start pose (5, 3, yaw 1)
    assert poses[0]["x"] == pytest.approx(5.0, abs=0.02) and poses[0]["yaw"] == pytest.approx(1.0, abs=0.02)
    assert (integ[0]["x"], integ[0]["y"], integ[0]["yaw"]) == pytest.approx((0, 0, 0), abs=0.01)
    # after 2 s at v=1, w=0.5: an arc in the start frame
    rest = poses[start_index(poses)]
    t_end = rest["timestamp"] + 2.0
    end = at(integ, t_end)
    assert (end["x"], end["y"], end["yaw"]) == pytest.approx((2 * math.sin(1.0), 2 * (1 - math.cos(1.0)), 1.0), abs=0.1)
    assert (end["vx"], end["vy"], end["wz"]) == pytest.approx((1.0, 0.0, 0.5), abs=0.1)
    # integrated == the pose sensor's pose relative to the start pose, at every common stamp
    origin = poses[0]
    by_stamp = {round(p["timestamp"], 4): p for p in poses}
    compared = 0
    for m in integ:
        p = by_stamp.get(round(m["timestamp"], 4))
        if p is not None:
            assert (m["x"], m["y"], m["yaw"]) == pytest.approx(relative(origin, p), abs=0.01)
            compared += 1
    assert compared > 50
    # differential: the deltas add up to the integrated pose; raw: the distances add up to the path length
    t_first = integ[0]["timestamp"]
    window = [m for m in diff if t_first < m["timestamp"] <= t_end]
    assert sum(m["dx"] for m in window) == pytest.approx(end["x"], abs=0.02)
    assert sum(m["dy"] for m in window) == pytest.approx(end["y"], abs=0.02)
    assert sum(m["dyaw"] for m in window) == pytest.approx(end["yaw"], abs=0.02)
    path = [p for p in poses if t_first <= p["timestamp"] <= t_end]
    length = sum(math.dist((a["x"], a["y"], a["z"]), (b["x"], b["y"], b["z"])) for a, b in zip(path, path[1:]))
    travelled = sum(m["dS"] for m in raw if t_first < m["timestamp"] <= t_end)
    assert travelled == pytest.approx(length, rel=0.03)
    assert travelled == pytest.approx(2.0, abs=0.1)


def test_reset_objects_also_resets_teleport_targets(tmp_path):
    """After `simulation reset_objects` a teleport does not drag its robot back to the old command."""
    from morsec.testing import simulate
    scene_text = ("robots:\n  - name: r\n    type: atrv\n    components:\n"
                  "      - {name: tele, type: teleport}\n      - {name: pose, type: pose}\n")
    with simulate(scene_text, tmp_path) as sim:
        sim.step(2)
        sim.call("r.tele", "translate", 3.0, 0.0, 0.0)
        sim.step(5)
        assert sim.data("r.pose")["x"] > 2.9
        sim.sim.reset()
        sim.step(5)
        assert abs(sim.data("r.pose")["x"]) < 0.05
