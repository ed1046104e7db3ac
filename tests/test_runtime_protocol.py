"""MORSE's socket protocol, byte for byte, against `morsec run` (reference §3): services on the service
port, JSON-line streams, port allocation, the supervision / time / communication services and the text
middleware."""

from __future__ import annotations

import csv
import json
import math
import socket
import statistics
import time

import pytest
from runtime_helpers import (
    LineSocket,
    Morsec,
    free_port,
    occupy,
    parse_response,
    port_free,
    pose_sensor,
    robot,
    scene,
    scene_file,
    start_all,
    wait_until,
    wrap,
)

POSE_FIELDS = ["timestamp", "x", "y", "z", "yaw", "pitch", "roll"]
ODO_FIELDS = ["timestamp", "x", "y", "z", "yaw", "pitch", "roll", "vx", "vy", "vz", "wz", "wy", "wx"]


def protocol_scene(odo_port: int) -> dict:
    main = robot("robot", pose_sensor(),
                 {"name": "motion", "type": "motion_vw", "streams": ["socket"], "services": ["socket"]},
                 {"name": "odo", "type": "odometry", "streams": [{"middleware": "socket", "port": odo_port}]})
    rover = robot("rover", pose_sensor(streams=["socket", {"middleware": "text"},
                                                {"middleware": "text", "format": "csv", "file": "logs/rover.csv"}],
                                       frequency=10),
                  translate=[3.0, 0.0, 0.0])
    objects = [{"name": "crate", "type": "box", "translate": [0.0, 5.0, 0.25], "size": [0.5, 0.5, 0.5]},
               {"name": "ball", "type": "sphere", "translate": [0.0, -5.0, 0.5], "size": [0.4, 0.4, 0.4],
                "dynamic": True, "mass": 1.0}]
    return scene(main, rover, objects=objects, strategy="best_effort")


@pytest.fixture(scope="module")
def sims(tmp_path_factory):
    """The simulation under test and a second one of the same scene beside it: default service port
    (4000 held by this test, so 4001 or the next free one) and another stream port base."""
    tmp = tmp_path_factory.mktemp("protocol")
    (tmp / "cwd").mkdir()
    odo_port = free_port()
    path = scene_file(tmp, protocol_scene(odo_port))
    main = Morsec(path, tmp, cwd=tmp / "cwd")
    main.odo_port = odo_port
    holder = occupy(4000) if port_free(4000) else None  # 4000 busy either way
    second = Morsec(path, tmp, service_port="auto", build=tmp / "build-second")
    try:
        start_all(main)  # first: the explicit port of robot.odo is its own
        start_all(second)
        yield main, second
    finally:
        main.stop()
        second.stop()
        if holder:
            holder.close()


@pytest.fixture
def sim(sims):
    main = sims[0]
    assert main.alive(), main.output()
    with main.client() as client:
        client.ok("robot.motion", "stop")
        client.ok("simulation", "restore_dynamics")
        client.ok("simulation", "reset_objects")
        for fqn in main.streams:
            client.ok("simulation", "activate", fqn)
    return main


@pytest.fixture
def client(sim):
    with sim.client() as c:
        yield c


def pose(sim, fqn: str = "robot.pose") -> dict:
    """The next message of a pose stream (on a fresh connection: only future messages)."""
    with sim.stream(fqn) as stream:
        return stream.json()


# --------------------------------------------------------------------------------------- services: bytes
def test_response_bytes(sim, client):
    client.send("a1 robot.motion set_speed [1.0, 0.0]\n")
    assert client.raw_line() == b"a1 SUCCESS\n"  # None: result left out
    client.send("a2 time set_time_scale [1.0]\n")
    assert client.raw_line() == b"a2 SUCCESS true\n"
    client.send("a3 simulation list_robots\n")
    assert client.raw_line() == b'a3 SUCCESS ["robot", "rover"]\n'  # json.dumps, default separators
    client.send("a4 simulation get_stream_port [\"robot.nothing\"]\n")
    line = client.raw_line()
    assert line.startswith(b'a4 FAILED "') and line.endswith(b'"\n')
    assert json.loads(line[len(b"a4 FAILED "):]) == "Stream unavailable for component robot.nothing"
    client.send("a5 simulation teleport_everything\n")
    _, status, message = parse_response(client.line())
    assert status == "FAILED" and "has not been registered in Socket service manager" in message


def test_a_service_called_without_its_arguments_answers_morse_words(sim, client):
    """MORSE's `parameters expected for service X!` (pymorse: MorseServiceFailed), with or without `[]`;
    too few arguments given is `wrong # of parameters` (pymorse: TypeError)."""
    for line in ("p1 communication distance_and_view\n", "p2 communication distance_and_view []\n"):
        client.send(line)
        rid, status, message = parse_response(client.line())
        assert status == "FAILED", (rid, message)
        assert message.startswith("Socket service manager: parameters expected for service distance_and_view! ")
        assert "wrong # of parameters" not in message
    client.send("p3 communication distance_and_view [\"robot\"]\n")
    _, status, message = parse_response(client.line())
    assert status == "FAILED" and message.startswith("wrong # of parameters for communication.distance_and_view")
    client.send("p4 simulation list_robots []\n")  # a service without parameters is not concerned
    assert client.line() == 'p4 SUCCESS ["robot", "rover"]'


def test_falsy_results_are_left_out(sim, client):
    client.send("f1 simulation deactivate [\"robot.pose\"]\n")  # returns None
    assert client.raw_line() == b"f1 SUCCESS\n"
    client.send("f2 simulation activate [\"robot.pose\"]\n")
    assert client.raw_line() == b"f2 SUCCESS\n"


def test_cancel_answers_preempted(sim, client):
    client.send("s1 time sleep [1000]\n")
    time.sleep(0.2)
    client.send("s1 cancel\n")
    assert client.raw_line() == b"s1 PREEMPTED\n"
    client.send("s2 time sleep [0.05]\n")
    assert client.raw_line() == b"s2 SUCCESS\n"
    client.send("s3 cancel\n")  # nothing running with that id: ignored, no answer
    client.send("s4 time mode\n")
    assert client.raw_line() == b's4 SUCCESS "Best Effort"\n'


def test_any_whitespace_between_tokens(sim, client):
    client.send("  w1 \t simulation\t\t list_robots   \n")
    assert client.raw_line() == b'w1 SUCCESS ["robot", "rover"]\n'
    client.send("w2 robot.motion   set_speed\t[ 0.0 ,\t0.0 ]\r\n")
    assert client.raw_line() == b"w2 SUCCESS\n"
    client.send("w3 robot.motion stop []\n")  # an empty array: no arguments
    assert client.raw_line() == b"w3 SUCCESS\n"


def test_several_requests_in_one_write_and_one_request_in_several(sim, client):
    client.send("m1 simulation list_robots\nm2 time mode\n\nm3 simulation list_streams\n")
    assert [parse_response(client.line())[0] for _ in range(3)] == ["m1", "m2", "m3"]
    client.send("p1 simulation li")
    time.sleep(0.1)
    client.send("st_robots\n")
    assert client.line() == 'p1 SUCCESS ["robot", "rover"]'


def test_a_request_written_right_after_another_is_not_held_back_by_the_client(sim):
    """pymorse writes `rotate(...)` (from its thread pool) and `sleep(1)` back to back on one connection,
    with Nagle's algorithm on: the kernel holds the second until the first is acknowledged. morsec
    acknowledges at once (TCP_QUICKACK), not 40 ms later (a delayed acknowledgement): the sleep starts
    with the command, not 2 or 3 frames after it."""
    with socket.create_connection((sim.host, sim.service_port), timeout=10) as raw:  # Nagle's algorithm on, as pymorse's
        reader = raw.makefile("rb")
        for k in range(20):  # request, answer: the connection is past its first, always acknowledged, segments
            raw.sendall(f"w{k} time mode\n".encode())
            reader.readline()
        delays = []
        for k in range(7):
            raw.sendall(f"s{k} time sleep [60]\n".encode())  # answered in a minute: nothing goes back now
            start = time.monotonic()
            raw.sendall(f"n{k} time now\n".encode())
            assert reader.readline().startswith(f"n{k} SUCCESS".encode())
            delays.append(time.monotonic() - start)
    assert statistics.median(delays) < 0.02, delays


def test_answers_go_to_the_asking_client(sim):
    with sim.client() as a, sim.client() as b:
        a.send("same time mode\n")
        b.send("same simulation list_robots\n")
        assert a.line() == 'same SUCCESS "Best Effort"'
        assert b.line() == 'same SUCCESS ["robot", "rover"]'


# --------------------------------------------------------------------------------------- streams
def test_stream_lines_are_json_dumps_of_the_declared_fields(sim):
    with sim.stream("robot.pose") as stream:
        raw = stream.raw_line()
        odo = LineSocket(sim.odo_port)
        raw_odo = odo.raw_line()
        odo.close()
    message = json.loads(raw)
    manifest = json.loads((sim.build / "manifest.json").read_text())
    declared = {c["fqn"]: c["data_fields"] for c in manifest["components"]}
    assert list(message) == declared["robot.pose"] == POSE_FIELDS
    assert raw == (json.dumps(message) + "\n").encode()  # default separators ", " and ": "
    assert b'"timestamp": ' in raw and b', "x": ' in raw
    assert list(json.loads(raw_odo)) == declared["robot.odo"] == ODO_FIELDS  # integrated level by default
    assert raw_odo == (json.dumps(json.loads(raw_odo)) + "\n").encode()


def test_new_clients_get_only_future_messages(sim, client):
    with sim.stream("robot.pose") as early:
        early.line()
        time.sleep(0.3)  # messages pile up for `early`
        now = client.ok("time", "now")
        with sim.stream("robot.pose") as late:
            first = late.json()
        assert first["timestamp"] >= now - 1e-9  # no replay of what was sent before it connected
        assert early.json()["timestamp"] < now  # the first client did get the older ones


def test_several_clients_per_stream(sim):
    with sim.stream("robot.pose") as a, sim.stream("robot.pose") as b, sim.stream("robot.pose") as c:
        lines = [{s.raw_line() for _ in range(20)} for s in (a, b, c)]
    common = lines[0] & lines[1] & lines[2]
    assert len(common) >= 10, "the same messages reach every client"


def test_actuator_applies_only_the_last_line_of_a_read(sim):
    with sim.stream("robot.motion") as motion:
        motion.send('{"v": 3.0, "w": 0.0}\n{"v": 0.0, "w": 1.0}\n')
        time.sleep(0.7)
        p = pose(sim)
        motion.send('{"v": 0.0, "w": 0.0}\n')
    assert abs(p["x"]) < 0.05 and abs(p["y"]) < 0.05, p  # the first line was not applied
    assert p["yaw"] > 0.3, p


def test_actuator_message_replaces_the_whole_dict(sim):
    with sim.stream("robot.motion") as motion:
        motion.send('{"v": 1.0, "w": 0.0}\n')
        wait_until(lambda: pose(sim)["x"] > 0.3, message="robot moving forward")
        motion.send('{"w": 0.8}\n')  # v is not sent: back to its default, 0
        time.sleep(0.3)
        x1 = pose(sim)
        time.sleep(0.5)
        x2 = pose(sim)
        motion.send('{"v": 0.0, "w": 0.0}\n')
    distance = math.hypot(x2["x"] - x1["x"], x2["y"] - x1["y"])
    assert distance < 0.05, (x1, x2)
    assert wrap(x2["yaw"] - x1["yaw"]) > 0.2


def test_actuator_waits_for_the_newline(sim):
    with sim.stream("robot.motion") as motion:
        motion.send('{"v": 1.0, ')
        time.sleep(0.4)
        assert abs(pose(sim)["x"]) < 0.02
        motion.send('"w": 0.0}\n')
        wait_until(lambda: pose(sim)["x"] > 0.2, message="the completed line applied")
        motion.send('{"v": 0.0, "w": 0.0}\n')


# --------------------------------------------------------------------------------------- ports
def test_ports_in_alphabetical_order_from_the_base(sims):
    main, second = sims
    for sim in (main, second):
        moved = sorted(fqn for fqn in sim.streams if fqn != "robot.odo")
        assert [sim.port(fqn) for fqn in moved] == [sim.port_base + i for i in range(len(moved))], sim.output()
    assert main.port("robot.odo") == main.odo_port  # explicit: kept, whatever the base
    assert second.port("robot.odo") not in (main.odo_port, second.port_base)  # a hint: the next free one


def test_build_assigns_ports_from_60000(sims):
    main, _ = sims
    middleware = json.loads((main.build / "middleware.json").read_text())
    socket_streams = [s for s in middleware["streams"] if s["middleware"] == "socket"]
    assert [s["component"] for s in socket_streams] == sorted(s["component"] for s in socket_streams)
    assert [s["port"] for s in socket_streams if not s["explicit_port"]] == [60000, 60001, 60002]
    assert middleware["services"]["socket"]["port"] == 4000


def test_service_port_falls_back_when_4000_is_busy(sims):
    main, second = sims
    assert 4001 <= second.service_port <= 4010, second.output()
    with second.client() as client:
        assert client.ok("simulation", "list_robots") == ["robot", "rover"]


def test_two_simulations_side_by_side(sims):
    main, second = sims
    assert set(main.streams) == set(second.streams)
    assert not {p for _, p in main.streams.values()} & {p for _, p in second.streams.values()}
    with main.client() as a, second.client() as b:
        a.ok("robot.motion", "set_speed", 1.0, 0.0)
        b.ok("robot.motion", "stop")
        time.sleep(0.6)
        with main.stream("robot.pose") as sa, second.stream("robot.pose") as sb:
            assert sa.json()["x"] > 0.2
            assert abs(sb.json()["x"]) < 0.02
        a.ok("robot.motion", "stop")


# --------------------------------------------------------------------------------------- supervision
def test_list_robots_details_and_streams(sim, client):
    assert client.ok("simulation", "list_robots") == ["robot", "rover"]
    details = client.ok("simulation", "details")
    assert set(details) == {"robots", "environment"} and details["environment"] == "empty"
    assert [r["name"] for r in details["robots"]] == ["robot", "rover"]
    main = details["robots"][0]
    assert main["type"] == "ATRV"
    components = main["components"]
    assert set(components) == {"robot.pose", "robot.motion", "robot.odo"}
    assert components["robot.pose"]["type"] == "Pose"
    assert components["robot.pose"]["stream_interfaces"] == [[components["robot.pose"]["stream_interfaces"][0][0], "OUT"]]
    motion = components["robot.motion"]
    assert motion["stream_interfaces"][0][1] == "IN"
    assert {"set_speed", "stop", "get_properties", "set_property", "get_configurations"} <= set(motion["services"])
    assert isinstance(motion["service_interfaces"], list)
    assert "services" not in components["robot.pose"]  # no service middleware asked for
    ports = client.ok("simulation", "get_all_stream_ports")
    assert ports == {fqn: port for fqn, (_, port) in sim.streams.items()}
    assert client.ok("simulation", "list_streams") == sorted(sim.streams)
    assert client.ok("simulation", "get_stream_port", "robot.odo") == sim.odo_port


def test_deactivate_stops_a_sensor(sim, client):
    with sim.stream("robot.pose") as stream:
        stream.line()
        client.ok("simulation", "deactivate", "robot.pose")
        time.sleep(0.2)
        stream.drain()
        with pytest.raises(TimeoutError):
            stream.line(timeout=0.5)
        client.ok("simulation", "activate", "robot.pose")
        assert stream.json(timeout=5)["timestamp"] > 0
    status, message = client.call("simulation", "deactivate", "robot.nothing")
    assert status == "FAILED" and "robot.nothing" in message


def test_set_object_position_and_reset(sim, client):
    client.ok("simulation", "set_object_position", "robot", [1.0, 2.0, 0.1], [0.0, 0.0, 1.0])
    p = pose(sim)
    assert p["x"] == pytest.approx(1.0, abs=0.05) and p["y"] == pytest.approx(2.0, abs=0.05)
    assert p["yaw"] == pytest.approx(1.0, abs=0.05)
    client.ok("simulation", "set_object_position", "crate", [2.0, 3.0, 0.25])
    objects = client.ok("simulation", "get_scene_objects")
    assert objects["crate"][1] == pytest.approx([2.0, 3.0, 0.25], abs=1e-6)
    client.ok("simulation", "set_object_position", "ball", [1.0, -3.0, 0.2])
    objects = client.ok("simulation", "get_scene_objects")
    assert objects["ball"][1][:2] == pytest.approx([1.0, -3.0], abs=0.05)
    assert client.ok("simulation", "reset_objects") == "Objects restored to initial position"
    p = pose(sim)
    assert abs(p["x"]) < 0.05 and abs(p["y"]) < 0.05 and abs(p["yaw"]) < 0.05
    objects = client.ok("simulation", "get_scene_objects")
    assert objects["crate"][1] == pytest.approx([0.0, 5.0, 0.25], abs=1e-6)
    status, message = client.call("simulation", "set_object_position", "nobody", [0, 0, 0])
    assert status == "FAILED" and "nobody" in message


def test_get_scene_objects_shape(sim, client):
    objects = client.ok("simulation", "get_scene_objects")
    assert {"robot", "rover", "crate", "ball"} <= set(objects)
    children, position, quaternion = objects["rover"]
    assert position[:2] == pytest.approx([3.0, 0.0], abs=0.05)
    assert len(quaternion) == 4 and quaternion[3] == pytest.approx(1.0, abs=0.01)  # [qx, qy, qz, qw]
    assert "rover.pose" in children and len(children["rover.pose"]) == 3


def test_suspend_and_restore_dynamics(sim, client):
    client.ok("simulation", "suspend_dynamics")
    client.ok("robot.motion", "set_speed", 1.0, 0.0)
    time.sleep(0.5)
    assert abs(pose(sim)["x"]) < 0.02
    client.ok("simulation", "restore_dynamics")
    wait_until(lambda: pose(sim)["x"] > 0.2, message="robot moving again")
    client.ok("robot.motion", "stop")


def test_distance_and_view(sim, client):
    distance, visible = client.ok("communication", "distance_and_view", "robot", "rover")
    assert distance == pytest.approx(3.0, abs=0.05) and visible is True
    client.ok("simulation", "set_object_position", "crate", [1.5, 0.0, 0.25])  # between the two
    distance, visible = client.ok("communication", "distance_and_view", "robot", "rover")
    assert distance == pytest.approx(3.0, abs=0.05) and visible is False
    status, message = client.call("communication", "distance_and_view", "robot", "nobody")
    assert status == "FAILED" and "nobody" in message


def test_time_services(sim, client):
    assert client.ok("time", "mode") == "Best Effort"
    now = client.ok("time", "now")
    assert abs(now - time.time()) < 5.0  # epoch-based, following the wall clock
    stats = client.ok("time", "statistics")
    assert {"mean_time", "variance_time", "mean_frame_by_sec", "real_time_factor"} <= set(stats)
    assert stats["mean_frame_by_sec"] == pytest.approx(60.0, rel=0.3)
    assert client.ok("time", "set_time_scale", 2.0) is True
    t0, w0 = client.ok("time", "now"), time.monotonic()
    time.sleep(0.5)
    t1, w1 = client.ok("time", "now"), time.monotonic()
    assert client.ok("time", "set_time_scale", 1.0) is True
    assert (t1 - t0) / (w1 - w0) == pytest.approx(2.0, rel=0.35)
    status, message = client.call("time", "set_time_scale", 0)
    assert status == "FAILED" and "positive" in message


def test_component_services(sim, client):
    assert client.ok("robot.motion", "get_properties") == {"ControlType": "Velocity"}
    config = client.ok("robot.motion", "get_configurations")
    assert config["frequency"] == 60.0
    status, message = client.call("robot.motion", "set_property", "ControlTyp", "Position")
    assert status == "FAILED" and "ControlType" in message


# --------------------------------------------------------------------------------------- text middleware
def test_text_middleware_files(sim):
    text = sim.cwd / "rover.pose.txt"
    assert sorted(sim.text_files) == [("rover.pose", sim.cwd / "logs" / "rover.csv"), ("rover.pose", text)]
    time.sleep(0.3)
    blocks = [b for b in text.read_text().split("\n\n") if b.strip()]
    assert len(blocks) >= 2
    lines = blocks[-1].splitlines()
    assert "rover.pose" in lines[0]
    pairs = dict(line.split(" = ", 1) for line in lines[1:])
    assert list(pairs) == POSE_FIELDS
    assert float(pairs["x"]) == pytest.approx(3.0, abs=0.05)
    with open(sim.cwd / "logs" / "rover.csv", newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == POSE_FIELDS
    assert len(rows) >= 3
    values = [[float(v) for v in row] for row in rows[1:] if len(row) == len(POSE_FIELDS)]
    assert all(b[0] > a[0] for a, b in zip(values, values[1:]))
    assert values[-1][0] - values[-2][0] == pytest.approx(0.1, abs=0.02)  # frequency 10
    assert values[-1][1] == pytest.approx(3.0, abs=0.05)


def test_port_base_zero_lets_the_os_pick_every_stream_port(tmp_path):
    """`--port-base 0`: no stream lands on a fixed (or a low, privileged) port; the table says where."""
    path = scene_file(tmp_path, scene(robot("robot", pose_sensor(), pose_sensor("second"))))
    with Morsec(path, tmp_path, port_base=0) as sim:
        ports = sim.client().ok("simulation", "get_all_stream_ports")
        assert sorted(ports) == ["robot.pose", "robot.second"]
        assert all(port >= 1024 for port in ports.values()) and len(set(ports.values())) == 2
