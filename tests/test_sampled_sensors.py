"""SampledSensor (the pose, odometry and laser scanner sensors): a tick only samples, local_data is computed when read,
and whatever reads it, whenever, gets what computing it at every tick would have given, to the bit."""

from __future__ import annotations

import socket
from pathlib import Path

import numpy as np
import pytest

from morsec.app.project import build_scene
from morsec.component import SampledSensor
from morsec.runtime.simulation import RunOptions, Simulation

SCENE = """\
environment:
  name: indoors-1/boxes
  time: {strategy: fixed_step, frequency: 60, relative: true}
robots:
  - name: robot
    type: atrv
    rotate: [0.0, 0.0, 0.7]
    components:
      - {name: pose, type: pose, translate: [0.2, 0.1, 0.3], streams: [socket]}
      - {name: odo_raw, type: odometry, level: raw, streams: [socket]}
      - {name: odo_diff, type: odometry, level: differential, streams: [socket]}
      - {name: odo_int, type: odometry, level: integrated, streams: [socket]}
      - {name: sick, type: sick, translate: [0.5, 0.0, 0.4], frequency: 20, streams: [socket]}
      - {name: rssi, type: sick, level: rssi, translate: [0.5, 0.0, 0.4], frequency: 20, streams: [socket]}
      - {name: motion, type: motion_vw, streams: [socket]}
"""
SENSORS = ("robot.pose", "robot.odo_raw", "robot.odo_diff", "robot.odo_int", "robot.sick", "robot.rssi")
COMMANDS = {5: (1.0, 0.4), 60: (-0.5, -1.0), 120: (1.5, 0.0), 150: (0.0, 2.0)}  # frame: (v, w)


@pytest.fixture(scope="module")
def build(tmp_path_factory) -> Path:
    tmp = tmp_path_factory.mktemp("sampled")
    (tmp / "scene.yaml").write_text(SCENE)
    return build_scene(tmp / "scene.yaml", tmp / "build")


def drive(build: Path, read_every: int) -> dict[int, dict[str, dict]]:
    """Drive the robot for 180 frames; every `read_every` frames, the sensors' local_data, by frame."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        read = {}
        for frame in range(180):
            if frame in COMMANDS:
                v, w = COMMANDS[frame]
                sim.receive(sim.by_name["robot.motion"], {"v": v, "w": w})
            sim.frame()
            sim.answer()
            if frame % read_every == 0:
                read[frame] = {fqn: {key: value.tolist() if isinstance(value, np.ndarray) else value
                                     for key, value in sim.by_name[fqn].instance.local_data.items()}
                               for fqn in SENSORS}
        return read
    finally:
        sim.close()


def test_data_read_now_and_then_is_the_data_computed_at_every_tick(build):
    every_tick = drive(build, 1)
    now_and_then = drive(build, 7)
    assert set(now_and_then) == set(range(0, 180, 7))
    for frame, data in now_and_then.items():
        assert data == every_tick[frame], frame  # ==: the same floats
    moved = every_tick[179]["robot.odo_int"]
    assert abs(moved["x"]) > 0.5 and abs(moved["yaw"]) > 0.1  # the robot drove and turned: data that changes
    ranges = [data["robot.sick"]["range_list"] for data in every_tick.values()]
    assert min(map(min, ranges)) < 30.0 and len({tuple(r) for r in ranges}) > 10  # walls seen, scans that differ


def test_a_tick_nobody_reads_computes_nothing(build):
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        pose = sim.by_name["robot.pose"].instance
        assert isinstance(pose, SampledSensor)
        computed = []
        compute = pose.compute
        pose.compute = lambda *sample: (computed.append(sample), compute(*sample))  # type: ignore[method-assign]
        for _ in range(10):
            sim.frame()
            sim.answer()
        assert computed == []  # no client, no service, no modifier: ten ticks sampled, none computed
        assert pose.local_dict["timestamp"] == pytest.approx(10 / 60)  # the loop still stamps the tick
        x = pose.local_data["x"]  # a read computes the last tick's sample, once
        assert len(computed) == 1 and x == pose.local_data["x"] and len(computed) == 1
        assert x == pytest.approx(sim.data.xpos[pose.body_id][0])
    finally:
        sim.close()


def test_a_failing_computation_is_the_sensors_error_not_the_runs(build, caplog):
    """A SampledSensor computes when its message is built, after its tick: an error there is reported once
    for the sensor, as one in its tick is, and the loop goes on (the other sensors' messages still leave)."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        pose = sim.by_name["robot.pose"]
        odometry = sim.by_name["robot.odo_raw"]

        def broken(*sample):
            raise ValueError("no pose today")

        pose.instance.compute = broken  # type: ignore[method-assign]
        readers = [socket.create_connection(("127.0.0.1", comp.out_streams[0].port), timeout=10)
                   for comp in (pose, odometry)]
        sim.poller.poll(0.1)
        sim.poller.poll(0.1)
        assert pose.out_streams[0].listening and odometry.out_streams[0].listening
        for _ in range(5):
            sim.frame()
            sim.answer()
        assert [r.message for r in caplog.records].count("robot.pose: ValueError: no pose today") == 1
        readers[1].settimeout(10)
        lines = readers[1].makefile().readline()
        assert "timestamp" in lines  # the odometry's messages left
        for reader in readers:
            reader.close()
    finally:
        sim.close()
