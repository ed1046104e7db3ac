"""No client can stop or corrupt a simulation: every request the protocol reads is bounded (JSON depth and
size, answers queued, requests pending), every value a request puts into the physics is bounded, MuJoCo's
own alarms do not reset the world, and a text stream on a full disk stops alone. Each test runs against
a real `morsec run` and checks, from another client, that the simulation is unharmed."""

from __future__ import annotations

import json
import socket
import threading
import time
from pathlib import Path

import pytest
from runtime_helpers import (
    HOST,
    MORSEC,
    Morsec,
    build_folder,
    parse_response,
    pose_sensor,
    robot,
    run_many,
    scene,
    scene_file,
    wait_until,
)

from morsec.constants import MAX_JSON_DEPTH, MAX_PENDING_REQUESTS, MAX_QUEUED_ANSWERS

OTHER = [0.0, 3.0]  # where the robot `other` stands: nothing in this module may move it
CRATE = [3.0, 0.0]


@pytest.fixture(scope="module")
def output_dir(tmp_path_factory) -> Path:
    """The run's output folder; its full.txt is the kernel's always-full device."""
    folder = tmp_path_factory.mktemp("output")
    (folder / "full.txt").symlink_to("/dev/full")
    return folder


@pytest.fixture(scope="module")
def sim(tmp_path_factory, output_dir):
    tmp = tmp_path_factory.mktemp("limits")
    pose = pose_sensor(streams=["socket", {"middleware": "text", "file": "full.txt"},
                                {"middleware": "text", "format": "csv", "file": "logs/pose.csv"}])
    main = robot("robot", pose, {"name": "motion", "type": "motion_vw", "streams": ["socket"],
                                 "services": ["socket"]})
    other = robot("other", pose_sensor(), translate=[*OTHER, 0.0])
    fake = robot("fake", {"name": "force", "type": "external_force", "streams": ["socket"]},
                 type="quadrotor", mass=0.001, translate=[-5.0, 5.0, 0.5])  # 1 g: 1e8 N is too much for MuJoCo
    crate = {"name": "crate", "type": "box", "translate": [*CRATE, 0.25], "dynamic": True}
    with Morsec(scene_file(tmp, scene(main, other, fake, strategy="best_effort", objects=[crate])), tmp,
                args=["--output-dir", str(output_dir)]) as process:
        yield process


def position(client, name: str) -> list[float]:
    return client.ok("simulation", "get_scene_objects")[name][1]


def unharmed(sim) -> None:
    """The simulation still steps and answers another client, and `other` and the crate stayed put."""
    assert sim.alive(), sim.output()
    with sim.client() as c:
        t0 = c.ok("time", "now")
        wait_until(lambda: c.ok("time", "now") > t0 + 0.05, timeout=15, message="simulated time advancing")
        assert c.ok("simulation", "list_robots") == ["robot", "other", "fake"]
        assert position(c, "other")[:2] == pytest.approx(OTHER, abs=0.01)
        assert position(c, "crate")[:2] == pytest.approx(CRATE, abs=0.01)
    assert not [line for line in sim.stderr if "Traceback" in line], sim.output()


def failed(client, line: str) -> str:
    """Send one request line; it must be answered FAILED; the message."""
    client.send(line + "\n")
    _, status, message = parse_response(client.line())
    assert status == "FAILED", (line[:80], status, message)
    return message


# ------------------------------------------------------------------------------- JSON depth and size
def test_deep_json_on_the_service_port_gets_failed(sim):
    with sim.client() as c:
        assert "nested deeper than" in failed(c, "n1 simulation list_robots " + "[" * 2048)
        deep = "[" * (MAX_JSON_DEPTH + 1) + "]" * (MAX_JSON_DEPTH + 1)
        assert "nested deeper than" in failed(c, f"n2 simulation list_robots {deep}")
        assert c.ok("simulation", "list_robots") == ["robot", "other", "fake"]  # the same connection goes on
    unharmed(sim)


def test_deep_json_on_a_stream_is_dropped(sim):
    with sim.stream("robot.motion") as motion:
        for message in ("[" * 2048, '{"v": ' + "[" * 3000 + "1" + "]" * 3000 + ', "w": 0.0}'):
            before = len(sim.stderr)
            motion.send(message + "\n")
            wait_until(lambda before=before: any("nested deeper than" in line for line in sim.stderr[before:]),
                       timeout=10, message="a warning about the dropped message")
        motion.send('{"v": 0.0, "w": 0.0}\n')
    unharmed(sim)


# ------------------------------------------------------------------------------- time scale
def test_time_scale_is_bounded(sim):
    with sim.client() as c:
        for absurd in (1e-12, 1e-300, 1e300, 0, -1):
            assert "time scale must be a positive number from" in failed(c, f"s time set_time_scale [{absurd}]")
        assert c.ok("time", "set_time_scale", 0.001) is True  # the slowest: a frame every 17 s
        assert c.ok("time", "set_time_scale", 1.0) is True  # and back at once, not after that frame
    unharmed(sim)


# ------------------------------------------------------------------------------- values for the physics
def test_absurd_positions_and_speeds_are_refused(sim):
    with sim.client() as c:
        for args in (["crate", [1e300, 0, 0]], ["crate", [1e9, 0, 0]], ["other", [0, 0, 0], [1e300, 0, 0]]):
            message = failed(c, f"p simulation set_object_position {json.dumps(args)}")
            assert "must be finite and within" in message, message
    with sim.stream("robot.motion") as motion:
        motion.send('{"v": 1e300, "w": 0.0}\n')
        wait_until(lambda: any("linear speed" in line and "within" in line for line in sim.stderr), timeout=10,
                   message="the actuator's refusal in the log")
        motion.send('{"v": 0.0, "w": 0.0}\n')
    assert not [line for line in sim.stderr if "Nan, Inf or huge value" in line]
    unharmed(sim)


def test_mujoco_alarm_puts_back_only_the_unstable_robot(sim):
    """1e8 N is within what a request may ask, but on a 1 g robot MuJoCo finds its acceleration huge: that
    robot is put back where it was, the others (`other`, the crate) keep their state, no world reset."""
    with sim.client() as c:
        start = position(c, "fake")
    with sim.stream("fake.force") as force:
        force.send('{"force": [1e8, 0.0, 0.0], "torque": [0.0, 0.0, 0.0]}\n')
        wait_until(lambda: any("fake: its state became unstable" in line for line in sim.stderr), timeout=15,
                   message="the recovery in the log")
        force.send('{"force": [0.0, 0.0, 0.0], "torque": [0.0, 0.0, 0.0]}\n')
    with sim.client() as c:
        assert position(c, "fake")[:2] == pytest.approx(start[:2], abs=1.0)
    unharmed(sim)


# ------------------------------------------------------------------------------- answers and pending requests
def vm_rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


def test_a_client_that_never_reads_its_answers_is_dropped(sim):
    """It pipelines `simulation details` and never reads: its answers pile up to MAX_QUEUED_ANSWERS, then
    it is dropped; meanwhile another client is answered and the simulator's memory stays bounded."""
    rss_before = vm_rss_mb(sim.pid)
    outcome: dict = {}

    def flood() -> None:
        sock = socket.create_connection((HOST, sim.service_port), timeout=60)
        batch = b"".join(b"d%d simulation details\n" % i for i in range(1000))
        deadline = time.monotonic() + 60
        try:
            while time.monotonic() < deadline:
                sock.sendall(batch)
        except OSError as err:  # reset by the simulator
            outcome["dropped"] = err
        finally:
            sock.close()

    flooder = threading.Thread(target=flood, daemon=True)
    flooder.start()
    slowest = 0.0
    rss_peak = rss_before
    with sim.client(timeout=30) as other:
        while flooder.is_alive():
            start = time.monotonic()
            other.ok("time", "now")
            slowest = max(slowest, time.monotonic() - start)
            rss_peak = max(rss_peak, vm_rss_mb(sim.pid))
            time.sleep(0.05)
    flooder.join()
    assert "dropped" in outcome, "the client that does not read was not dropped within 60 s"
    assert any("does not read its answers" in line for line in sim.stderr)
    assert slowest < 5.0, f"another client waited {slowest:.1f} s for `time now`"
    assert rss_peak - rss_before < 4 * MAX_QUEUED_ANSWERS / 2**20 + 50, (rss_before, rss_peak)
    unharmed(sim)


def sleepers(c, count: int, seconds: float, prefix: str) -> None:
    c.send("".join(f"{prefix}{i} time sleep [{seconds}]\n" for i in range(count)))


def test_pending_requests_per_client_are_bounded(sim):
    with sim.client() as c, sim.client() as probe:
        sleepers(c, MAX_PENDING_REQUESTS + 3, 1000, "z")
        for _ in range(3):  # the last three: one too many each
            rid, status, message = parse_response(c.line())
            assert status == "FAILED" and "too many requests pending" in message, (rid, status, message)
        assert probe.ok("time", "statistics")["sleeping_requests"] >= MAX_PENDING_REQUESTS
        c.send("z0 cancel\n")
        assert c.line() == "z0 PREEMPTED"
        c.send("again time sleep [0.01]\n")  # a place is free again
        assert c.line() == "again SUCCESS"
    with sim.client() as probe:  # the client left: its sleeping requests went with it
        wait_until(lambda: probe.ok("time", "statistics")["sleeping_requests"] == 0, timeout=10,
                   message="sleeping requests forgotten")
    unharmed(sim)


def test_many_sleeping_requests_do_not_stall_the_loop(sim):
    """20 clients with 1000 sleeps each: scheduled and woken in log time, not by scanning them all."""
    clients = [sim.client(timeout=60) for _ in range(20)]
    try:
        for i, c in enumerate(clients):
            sleepers(c, MAX_PENDING_REQUESTS, 0.5, f"c{i}.")
        with sim.client() as probe:
            start = time.monotonic()
            probe.ok("time", "now")
            assert time.monotonic() - start < 5.0
        for c in clients:
            answers = [c.line() for _ in range(MAX_PENDING_REQUESTS)]
            assert all(a.endswith(" SUCCESS") for a in answers), [a for a in answers if not a.endswith("SUCCESS")][:3]
    finally:
        for c in clients:
            c.close()
    unharmed(sim)


# ------------------------------------------------------------------------------- text streams
def test_a_full_disk_stops_the_text_stream_only(sim, output_dir):
    csv = output_dir / "logs" / "pose.csv"
    assert ("robot.pose", csv) in [(fqn, path) for fqn, path in sim.text_files]
    size = csv.stat().st_size
    wait_until(lambda: csv.stat().st_size > size, timeout=10, message="the other text stream writing on")
    warnings = [line for line in sim.stderr if "text stream stopped" in line]
    assert len(warnings) == 1 and "full.txt" in warnings[0], sim.output()
    unharmed(sim)


# ------------------------------------------------------------------------------- command line
@pytest.fixture(scope="module")
def bad_runs(tmp_path_factory):
    """`morsec run` with values out of range, side by side: {case: CompletedProcess}."""
    tmp = tmp_path_factory.mktemp("bad_runs")
    built = build_folder(scene_file(tmp, scene()), tmp / "build")
    escaping = build_folder(scene_file(tmp, scene(robot("robot", pose_sensor(streams=["text"]))), "text"),
                            tmp / "escaping")
    manifest = json.loads((escaping / "manifest.json").read_text())
    manifest["streams"][0]["endpoint"]["file"] = "../outside.txt"  # a build folder edited by hand
    (escaping / "manifest.json").write_text(json.dumps(manifest))
    cases = {
        "--time-scale 1e-300": [built, "--time-scale", "1e-300"],
        "--port-base 65535": [built, "--port-base", "65535"],
        "--service-port 70000": [built, "--service-port", "70000"],
        "--view-port 70000": [built, "--view-port", "70000"],
        "--seed -1": [built, "--seed", "-1"],
        "file outside": [escaping, "--duration", "1"],
    }
    commands = [[str(MORSEC), "run", *map(str, args), "--duration", "1"] for args in cases.values()]
    for command in commands:
        if "--service-port" not in command:
            command += ["--service-port", "0"]
    results = dict(zip(cases, run_many(commands, cwd=tmp)))
    results["tmp"] = tmp
    return results


@pytest.mark.parametrize("case, code, message", [
    ("--time-scale 1e-300", 2, "--time-scale must be between 0.001 and 1000, got 1e-300"),
    ("--port-base 65535", 2, "--port-base 65535 puts the stream of robot.pose on port 65536, beyond 65535: "
                             "choose a lower --port-base"),
    ("--service-port 70000", 2, "--service-port must be a port number from 0 to 65535, got 70000"),
    ("--view-port 70000", 2, "--view-port must be a port number from 0 to 65535, got 70000"),
    ("--seed -1", 2, "--seed must be 0 or more, got -1"),
    ("file outside", 1, "robot.pose: text stream file '../outside.txt': a text stream's file must be a relative "
                        "path inside the run's output folder (not absolute, no '..'); choose the folder with "
                        "morsec run --output-dir; rebuild the scene"),
])
def test_out_of_range_run_options_exit_in_one_line(bad_runs, case, code, message):
    result = bad_runs[case]
    assert result.returncode == code, (result.returncode, result.stdout, result.stderr)
    assert result.stderr == f"error: {message}\n"
    assert "SCENE INITIALIZED" not in result.stdout
    assert not (bad_runs["tmp"] / "outside.txt").exists()
