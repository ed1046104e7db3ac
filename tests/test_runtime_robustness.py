"""The loop survives whatever clients do: every bad request gets a FAILED answer where the protocol allows
one, nothing crashes, the simulation keeps stepping, other clients are unaffected, no descriptor leaks."""

from __future__ import annotations

import random
import socket
import struct
import time

import pytest
from runtime_helpers import HOST, LineSocket, Morsec, parse_response, pose_sensor, robot, scene, scene_file, wait_until


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("robustness")
    main = robot("robot", pose_sensor(),
                 {"name": "motion", "type": "motion_vw", "streams": ["socket"], "services": ["socket"]})
    heli = robot("heli", pose_sensor(translate=[0.0, 0.0, 0.0]), {"name": "motion", "type": "motion_vw",
                                                                  "streams": ["socket"]},
                 type="rmax", translate=[0.0, -4.0, 2.0])
    other = robot("other", pose_sensor(), translate=[0.0, 3.0, 0.0])
    with Morsec(scene_file(tmp, scene(main, other, heli, strategy="best_effort")), tmp) as process:
        yield process


@pytest.fixture
def client(sim):
    assert sim.alive(), sim.output()
    with sim.client() as c:
        yield c
    assert sim.alive(), sim.output()


def failed(client: LineSocket, line: bytes | str, request_id: str | None = None) -> str:
    """Send one request line; its answer must be `id FAILED "message"`; the message."""
    client.send(line)
    rid, status, message = parse_response(client.line())
    assert status == "FAILED", (line, rid, status, message)
    if request_id is not None:
        assert rid == request_id
    assert isinstance(message, str) and message
    return message


def stepping(sim) -> None:
    """The simulation still advances and answers."""
    with sim.client() as c:
        t0 = c.ok("time", "now")
        wait_until(lambda: c.ok("time", "now") > t0 + 0.05, timeout=10, message="simulated time advancing")
        assert c.ok("simulation", "list_robots") == ["robot", "other", "heli"]


def rst_close(sock: socket.socket) -> None:
    """Close with a reset (SO_LINGER 0): the peer sees ECONNRESET instead of an orderly end."""
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
    sock.close()


def test_malformed_lines(client):
    assert "malformed" in failed(client, "lonely\n", "lonely")
    assert "malformed" in failed(client, "id2 simulation\n", "id2")
    client.send("\n   \n\t\n")  # blank lines: nothing to answer
    assert "malformed" in failed(client, b"\xff\xfe\xfd simulation\n")
    assert client.ok("simulation", "list_robots") == ["robot", "other", "heli"]


def test_unknown_component_and_service(client):
    assert "has not been registered" in failed(client, "u1 nobody list_robots\n", "u1")
    assert "has not been registered" in failed(client, "u2 simulation fly_away\n", "u2")
    assert "has not been registered" in failed(client, "u3 robot.pose set_speed [1, 2]\n", "u3")


def test_wrong_arity(client):
    assert "wrong # of parameters" in failed(client, "a1 robot.motion set_speed [1.0]\n", "a1")
    assert "wrong # of parameters" in failed(client, "a2 robot.motion set_speed [1.0, 2.0, 3.0]\n", "a2")
    assert "wrong # of parameters" in failed(client, "a3 simulation list_robots [1]\n", "a3")


def test_invalid_and_non_array_parameters(client):
    assert "JSON" in failed(client, "j1 robot.motion set_speed [1.0, \n", "j1")
    assert "JSON array" in failed(client, 'j2 robot.motion set_speed {"v": 1.0}\n', "j2")
    assert "JSON array" in failed(client, "j3 robot.motion set_speed 1.0\n", "j3")
    assert "JSON" in failed(client, "j4 robot.motion set_speed [NaN, Infinity]\n", "j4")  # not JSON
    failed(client, 'j5 robot.motion set_speed ["fast", "slow"]\n', "j5")
    failed(client, 'j6 simulation set_object_position ["robot", [1, "a"]]\n', "j6")
    failed(client, 'j7 time sleep [{"t": 1}]\n', "j7")
    assert client.ok("robot.motion", "stop") is None


def test_huge_request_lines(sim, client):
    big = "h1 robot.motion set_speed [" + "1.0, " * 500_000 + "1.0]\n"  # 2.5 MB: read, parsed, refused
    assert "wrong # of parameters" in failed(client, big, "h1")
    huge = b"h2 simulation list_robots [" + b"0, " * 2_500_000 + b"0]\n"  # 7.5 MB: over the line limit
    message = failed(client, huge, "h2")
    assert "longer than" in message
    assert client.ok("simulation", "list_robots") == ["robot", "other", "heli"]  # the same connection still works
    stepping(sim)


def test_a_flood_of_requests_does_not_stall_the_others(sim):
    """200 000 bad requests in 400 kB from a client that never reads its answers: the others are served
    within seconds (handling is linear in what arrives, answers queue without quadratic copying)."""
    with socket.create_connection((HOST, sim.service_port), timeout=5) as flooder, sim.client(timeout=30) as other:
        flooder.sendall(b"a\n" * 200_000 + b"\n" * 1_000_000)
        start = time.monotonic()
        assert other.ok("time", "mode") == "Best Effort"
        assert time.monotonic() - start < 8.0
    stepping(sim)


def test_binary_garbage_everywhere(sim):
    rng = random.Random(7)
    garbage = bytes(rng.getrandbits(8) for _ in range(200_000))
    with sim.stream("robot.pose") as watcher:  # an innocent client of a stream
        watcher.line()
        for port in [sim.service_port] + [port for _, port in sim.streams.values()]:
            with socket.create_connection((HOST, port), timeout=5) as sock:
                sock.sendall(garbage)
                sock.sendall(b"\x00\n\xff{\"v\": 1e999}\n[1, 2]\n\"text\"\n{\"v\": \"fast\"}\n")
                time.sleep(0.05)
        watcher.drain()
        assert watcher.json(timeout=5)["timestamp"] > 0
    with sim.stream("robot.pose") as pose:
        p = pose.json()
    assert abs(p["x"]) < 0.05 and abs(p["y"]) < 0.05, "garbage on the actuator port moved the robot"
    stepping(sim)


def test_non_finite_actuator_input_is_ignored(sim):
    """NaN or Infinity in a flying robot's command would reach MuJoCo's state, and MuJoCo would reset the
    whole world (every robot back to its initial pose): such a line is not JSON and is ignored."""
    with sim.client() as c:
        c.ok("simulation", "set_object_position", "other", [0.0, 4.0, 0.1])
    with sim.stream("heli.motion") as heli, sim.stream("robot.motion") as motion, \
            sim.stream("other.pose") as other:
        assert other.json()["y"] == pytest.approx(4.0, abs=0.01)
        for actuator in (heli, motion):
            actuator.send('{"v": Infinity, "w": NaN}\n')
            time.sleep(0.3)
            actuator.send('{"v": 1e999, "w": 0.0}\n')
            time.sleep(0.3)
            actuator.send('{"v": 0.0, "w": 0.0}\n')
        other.drain()
        assert other.json()["y"] == pytest.approx(4.0, abs=0.01)
    with sim.client() as c:
        c.ok("simulation", "reset_objects")
    assert not [line for line in sim.stderr if "Nan, Inf or huge value" in line]
    stepping(sim)


def test_clients_vanishing_mid_message(sim):
    for i in range(20):
        sock = socket.create_connection((HOST, sim.service_port), timeout=5)
        sock.sendall(f"v{i} simulation list_ro".encode())
        (rst_close if i % 2 else socket.socket.close)(sock)
        sock = socket.create_connection((HOST, sim.service_port), timeout=5)
        sock.sendall(f"d{i} simulation details\n".encode())  # its answer goes to a closed socket
        (rst_close if i % 2 else socket.socket.close)(sock)
        sock = socket.create_connection((HOST, sim.port("robot.motion")), timeout=5)
        sock.sendall(b'{"v": 0.0, "w"')
        (rst_close if i % 2 else socket.socket.close)(sock)
        sock = socket.create_connection((HOST, sim.port("robot.pose")), timeout=5)
        rst_close(sock)
    stepping(sim)


def test_a_hundred_clients_at_once(sim):
    clients = [LineSocket(sim.service_port, timeout=20) for _ in range(100)]
    try:
        for i, c in enumerate(clients):
            c.send(f"c{i} simulation list_robots\n")
        for i, c in enumerate(clients):
            assert c.line() == f'c{i} SUCCESS ["robot", "other", "heli"]'
        streams = [LineSocket(sim.port("robot.pose"), timeout=20) for _ in range(100)]
        try:
            assert all(s.json()["timestamp"] > 0 for s in streams)
        finally:
            for s in streams:
                s.close()
    finally:
        for c in clients:
            c.close()
    stepping(sim)


def test_async_request_of_a_vanished_client(sim):
    with sim.client() as doomed:
        doomed.send("z1 time sleep [0.2]\nz2 time sleep [1000]\n")
        time.sleep(0.1)
    time.sleep(0.4)  # z1 completes for nobody; z2 still sleeps for nobody
    with sim.client() as other:
        other.send("z2 cancel\n")  # not its request: ignored
        other.send("z3 time sleep [0.1]\n")
        assert other.line() == "z3 SUCCESS"
    stepping(sim)


def test_no_descriptor_leak(sim):
    stepping(sim)
    time.sleep(0.3)
    before = sim.fd_count()
    ports = [sim.service_port] + [port for _, port in sim.streams.values()]
    for i in range(200):
        sock = socket.create_connection((HOST, ports[i % len(ports)]), timeout=5)
        if i % 3 == 0:
            sock.sendall(b"x1 simulation list_robots\n" if ports[i % len(ports)] == sim.service_port else b"{")
        if i % 2:
            rst_close(sock)
        else:
            sock.close()
    with sim.client() as c:
        c.ok("simulation", "list_robots")
    wait_until(lambda: sim.fd_count() <= before + 2, timeout=10, message=f"descriptors back to {before}")
    assert sim.fd_count() >= before - 2
