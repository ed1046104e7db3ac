"""Sensors that look at other things in the scene: proximity, radar altimeter, collision, and the
compound sensor that merges other sensors' data."""

from __future__ import annotations

import json
import math

import pytest
from runtime_helpers import read_lines, stream_client

from morsec.errors import RuntimeFailure
from morsec.middleware.socket_streams import encode
from morsec.testing import simulate


def test_proximity_tracks_tagged_objects_within_range(tmp_path):
    """Distances are from the robot's origin (not the sensor's), the robot itself is left out."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: prox, type: proximity, translate: [5.0, 0.0, 0.0]}
  - {name: near, type: fake_robot, translate: [3.0, 4.0, 0.0]}
  - {name: far, type: fake_robot, translate: [40.0, 0.0, 0.0]}
objects:
  - {name: survivor, type: box, translate: [0.0, -6.0, 0.0], properties: {Victim: true}}
  - {name: statue, type: box, translate: [0.0, 2.0, 0.0], properties: {Type: Victim}}
  - {name: crate, type: box, translate: [1.0, 0.0, 0.0]}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        data = h.data("r.prox")
        assert list(data) == ["timestamp", "near_objects", "near_robots"]
        assert data["near_objects"] == {"near": pytest.approx(5.0)}  # default Range 30 m
        assert data["near_robots"] == data["near_objects"]
        h.call("r.prox", "set_range", 50)
        h.step(5)  # 12 Hz: one tick every 5 frames
        assert h.data("r.prox")["near_objects"] == {"near": pytest.approx(5.0), "far": pytest.approx(40.0)}
        h.call("r.prox", "set_tracked_tag", "Victim")
        h.step(5)
        assert h.data("r.prox")["near_objects"] == {"survivor": pytest.approx(6.0), "statue": pytest.approx(2.0)}
        assert h.call("r.prox", "get_properties") == {"Range": 50.0, "Track": "Victim"}
        assert h.sim.component("r.prox").schedule.period == pytest.approx(1 / 12)


def test_radar_altimeter_measures_straight_down(tmp_path):
    """A helicopter 3 m up (its origin there: it floats, as MORSE's): the ray passes through the helicopter's own
    skids; above a 1 m crate it reads 1 m less; beyond MaxRange it reads inf."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 3.0]
    rotate: [0.2, 0.0, 0.0]
    components:
      - {name: alt, type: radar_altimeter}
      - {name: short, type: radar_altimeter, properties: {MaxRange: 2.0}}
      - {name: tp, type: teleport}
objects:
  - {name: crate, type: box, translate: [10.0, 0.0, 0.5], size: [2.0, 2.0, 1.0]}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        origin, _ = h.body_pose("heli")
        assert origin[2] == pytest.approx(3.0, abs=1e-3)
        assert h.data("heli.alt")["z"] == pytest.approx(origin[2], abs=1e-6)  # straight down whatever the roll
        assert h.data("heli.short")["z"] == math.inf
        h.command("heli.tp", x=10.0, y=0.0, z=3.0, roll=0.2)
        h.step(2)
        assert h.data("heli.alt")["z"] == pytest.approx(2.0, abs=1e-6)
        assert h.data("heli.short")["z"] == pytest.approx(2.0, abs=1e-6)


def test_collision_reports_what_the_robot_touches(tmp_path):
    """An ATRV driven into a crate: nothing while it drives on the ground (the ground plane does not
    count), then the crate; a sensor filtered on a property the crate lacks stays silent."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: atrv
    components:
      - {name: bumper, type: collision}
      - {name: fire_only, type: collision, properties: {only_objects_with_property: Fire}}
      - {name: obstacles, type: collision, properties: {only_objects_with_property: Obstacle}}
      - {name: motion, type: motion_vw}
objects:
  - {name: crate, type: box, translate: [1.5, 0.0, 0.5], size: [1.0, 2.0, 1.0], properties: {Obstacle: true}}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.5)
        assert h.data("r.bumper") == {"timestamp": pytest.approx(0.5), "collision": False, "objects": ""}
        h.command("r.motion", v=0.5, w=0.0)
        seen = []
        for _ in range(30):  # the wheels reach the crate's face after about 1 s
            h.step(6)
            seen.append((h.data("r.bumper")["objects"], h.data("r.obstacles")["objects"], h.data("r.fire_only")))
            if seen[-1][0]:
                break
        bumper, obstacles, fire_only = seen[-1]
        assert bumper == "crate" and obstacles == "crate"
        assert fire_only == {"timestamp": pytest.approx(h.time), "collision": False, "objects": ""}
        assert h.data("r.bumper")["collision"] is True
        assert 0.8 < h.time - 0.5 < 1.5


def test_collision_stream_is_silent_until_a_contact(tmp_path):
    """As MORSE's, the collision stream sends nothing while the robot touches nothing (a client waiting
    for a message times out), then a message per tick while it touches: MORSE's collision_testing waits
    0.1 s for a message and expects none before the robot reaches the obstacle."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: atrv
    components:
      - {name: bumper, type: collision, streams: [socket]}
      - {name: motion, type: motion_vw}
objects:
  - {name: crate, type: box, translate: [1.5, 0.0, 0.5], size: [1.0, 2.0, 1.0]}
"""
    with simulate(text, tmp_path) as h:
        client = stream_client(h, "r.bumper")
        h.run_for(0.5)
        assert h.data("r.bumper")["collision"] is False  # computed, not sent
        client.settimeout(0.2)
        with pytest.raises(TimeoutError):
            client.recv(1 << 16)
        h.command("r.motion", v=0.5, w=0.0)
        for _ in range(60):
            h.step(6)
            if h.data("r.bumper")["collision"]:
                break
        h.step(3)
        messages = [json.loads(line) for line in read_lines(client)]
        assert len(messages) >= 3 and all(m["collision"] and m["objects"] == "crate" for m in messages)


def test_collision_box_ahead_of_the_robot_touches_first(tmp_path):
    """MORSE's collision sensor is a small box of its own: mounted 0.7 m ahead of an ATRV (as MORSE's
    collision_testing mounts it), it reports the robot standing before it while the robot's own body is
    still 6 cm away; a sensor at the robot's origin reports nothing."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: atrv
    components:
      - {name: ahead, type: collision, translate: [0.7, 0.0, 0.2]}
      - {name: inside, type: collision}
  - {name: dala, type: atrv, translate: [1.1, 0.0, 0.0]}
"""
    with simulate(text, tmp_path) as h:
        h.step(3)
        assert h.data("r.ahead")["objects"] == "dala"
        assert h.data("r.inside")["collision"] is False


def test_compound_merges_sensors_by_full_name(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: quad
    type: rmax
    translate: [0.0, 0.0, 2.0]
    components:
      - {name: imu, type: imu}
      - {name: pose, type: pose}
      - {name: clock, type: clock, frequency: 10}
      - {name: aaa, type: compound, properties: {sensors: "quad.pose, quad.imu,quad.clock"}}
"""
    with simulate(text, tmp_path) as h:
        h.step(3)
        data = h.data("quad.aaa")
        line = encode(h.component("quad.aaa").local_data)
    assert list(data) == ["timestamp", "quad.pose", "quad.imu", "quad.clock"]
    message = json.loads(line)
    assert list(message) == ["timestamp", "quad.pose", "quad.imu", "quad.clock"]
    assert line.endswith(b"\n") and line.count(b"\n") == 1
    # ticked after the sensors it gathers (its name sorts first): each part is from this very frame
    assert message["timestamp"] == pytest.approx(3 / 60)
    assert message["quad.pose"]["timestamp"] == message["timestamp"]
    assert message["quad.imu"]["timestamp"] == message["timestamp"]
    assert message["quad.clock"]["timestamp"] == pytest.approx(1 / 60)  # 10 Hz: last ticked at frame 1
    assert message["quad.pose"]["z"] == pytest.approx(2.0, abs=1e-3)
    assert message["quad.imu"]["linear_acceleration"] == pytest.approx([0.0, 0.0, 9.81], abs=0.05)
    assert list(message["quad.pose"]) == ["timestamp", "x", "y", "z", "yaw", "pitch", "roll"]


def test_compound_names_an_unknown_sensor(tmp_path):
    text = """
environment: {name: empty}
robots:
  - name: quad
    type: fake_robot
    components:
      - {name: pose, type: pose}
      - {name: sitl, type: compound, properties: {sensors: "quad.pose,quad.poes"}}
"""
    with pytest.raises(RuntimeFailure, match=r"quad\.sitl: compound sensor quad\.sitl: no sensor named "
                                             r"'quad\.poes'; did you mean 'quad\.pose'\?"):
        with simulate(text, tmp_path):
            pass


SENSORS = ("gps", "imu", "accelerometer", "gyroscope", "velocity", "attitude", "barometer", "magnetometer",
           "clock", "battery", "thermometer", "proximity", "radar_altimeter", "collision")


def test_every_sensor_sends_plain_json(tmp_path):
    """Values on the wire are Python floats, lists, dicts, strings and bools (no numpy types): the
    standard json module serialises them without help, and each message starts with the timestamp."""
    components = "\n".join(f"      - {{name: {s}, type: {s}}}" for s in SENSORS)
    text = f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: 1.4333, latitude: 43.6, altitude: 135.0}}
robots:
  - name: r
    type: atrv
    components:
{components}
      - {{name: gps_x, type: gps, level: extended}}
      - {{name: all, type: compound, properties: {{sensors: "r.gps,r.gps_x,r.imu,r.proximity"}}}}
  - {{name: other, type: atrv, translate: [4.0, 0.0, 0.0]}}
objects:
  - {{name: fire, type: box, translate: [0.0, 3.0, 0.25], properties: {{Fire: true}}}}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.25)
        for name in [f"r.{s}" for s in SENSORS] + ["r.gps_x", "r.all"]:
            data = h.component(name).local_data
            assert next(iter(data)) == "timestamp"
            decoded = json.loads(json.dumps(data))
            assert decoded == json.loads(encode(data)), name
    assert decoded["r.proximity"]["near_objects"] == {"other": pytest.approx(4.0, abs=0.01)}
