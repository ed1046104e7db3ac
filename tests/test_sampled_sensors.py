"""SampledSensor (the pose, odometry, IMU, GPS and laser scanner sensors): a tick only samples, local_data is computed
when read, and whatever reads it, whenever, gets what computing it at every tick would have given, to the bit; Gaussian
noise (a deferrable modifier) draws at every tick and is added when the data is read."""

from __future__ import annotations

import math
import socket
from pathlib import Path
from types import SimpleNamespace

import mujoco
import numpy as np
import pytest

from morsec.app.project import build_scene
from morsec.component import SampledSensor
from morsec.kits.geometry import euler_of_xmat
from morsec.runtime.simulation import RunOptions, Simulation

SCENE = """\
environment:
  name: indoors-1/boxes
  time: {strategy: fixed_step, frequency: 60, relative: true}
  properties: {longitude: 1.4437, latitude: 43.6045, altitude: 146.0}
  seed: 3
robots:
  - name: robot
    type: atrv
    rotate: [0.0, 0.0, 0.7]
    components:
      - {name: pose, type: pose, translate: [0.2, 0.1, 0.3], streams: [socket]}
      - {name: noisy_pose, type: pose, streams: [socket], modifiers: [{name: noise}, {name: ned}]}
      - {name: imu, type: imu, translate: [0.3, 0.1, 0.2], streams: [socket], modifiers: [{name: noise}]}
      - {name: imu_pos, type: imu, properties: {ComputationMode: Position}, streams: [socket],
         modifiers: [{name: imunoise, gyro_std: 0.1}]}
      - {name: gps, type: gps, streams: [socket], modifiers: [{name: noise}]}
      - {name: gps_raw, type: gps, level: raw, frequency: 30, streams: [socket], modifiers: [{name: noise}]}
      - {name: gps_ext, type: gps, level: extended, streams: [socket]}
      - {name: odo_raw, type: odometry, level: raw, streams: [socket]}
      - {name: odo_diff, type: odometry, level: differential, streams: [socket]}
      - {name: odo_int, type: odometry, level: integrated, streams: [socket], modifiers: [{name: noise}]}
      - {name: sick, type: sick, translate: [0.5, 0.0, 0.4], frequency: 20, streams: [socket]}
      - {name: rssi, type: sick, level: rssi, translate: [0.5, 0.0, 0.4], frequency: 20, streams: [socket]}
      - {name: velodyne, type: velodyne_ray_cast, translate: [0.0, 0.0, 0.6], streams: [socket]}
      - {name: motion, type: motion_vw, streams: [socket]}
  - name: other
    type: atrv
    translate: [2.5, 1.5, 0.0]
    components:
      - {name: motion, type: motion_vw, streams: [socket]}
"""
SENSORS = ("robot.pose", "robot.noisy_pose", "robot.imu", "robot.imu_pos", "robot.gps", "robot.gps_raw", "robot.gps_ext",
           "robot.odo_raw", "robot.odo_diff", "robot.odo_int", "robot.sick", "robot.rssi", "robot.velodyne")
# frame: (v, w) of the robot carrying the sensors, and of the other one, which drives through the lasers' view
COMMANDS = {5: (1.0, 0.4), 60: (-0.5, -1.0), 120: (1.5, 0.0), 150: (0.0, 2.0)}
OTHER = {0: (0.8, 0.6), 90: (-1.0, -0.4)}


@pytest.fixture(scope="module")
def build(tmp_path_factory) -> Path:
    tmp = tmp_path_factory.mktemp("sampled")
    (tmp / "scene.yaml").write_text(SCENE)
    return build_scene(tmp / "scene.yaml", tmp / "build")


def drive(build: Path, read_every: int) -> dict[int, dict[str, dict]]:
    """Drive both robots for 180 frames; every `read_every` frames, the sensors' local_data, by frame."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        read = {}
        for frame in range(180):
            if frame in COMMANDS:
                v, w = COMMANDS[frame]
                sim.receive(sim.by_name["robot.motion"], {"v": v, "w": w})
            if frame in OTHER:
                v, w = OTHER[frame]
                sim.receive(sim.by_name["other.motion"], {"v": v, "w": w})
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
    # every field changes, noise included (but the UTC date and time, in 3 s, and the remissions: the boxes room's
    # walls all have MuJoCo's default material)
    for fqn in SENSORS:
        for key in set(every_tick[0][fqn]) - {"date", "time", "remission_list"}:
            assert len({repr(data[fqn][key]) for data in every_tick.values()}) > 10, (fqn, key)
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


def test_poses_read_from_the_frames_copy_are_mjdatas_at_the_tick(build):
    """The pose, odometry and GPS sensors sample the loop's copy of the bodies' poses (Simulation.body_poses): what
    they give is MjData's pose of their body at their tick, to the bit, also for a sensor ticking at every other
    frame (its previous pose is its previous tick's, not the last frame's)."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        pose, odometry = sim.by_name["robot.pose"].instance, sim.by_name["robot.odo_raw"].instance
        gps_raw = sim.by_name["robot.gps_raw"].instance  # 30 Hz: a tick every other frame
        positions = {}  # frame -> MjData's positions of the bodies, after the frame (its sensors' ticks)
        for frame in range(1, 41):
            if frame == 5:
                sim.receive(sim.by_name["robot.motion"], {"v": 1.0, "w": 0.4})
            sim.frame()
            sim.answer()
            positions[frame] = sim.data.xpos.copy()
            data = pose.local_data
            assert (data["x"], data["y"], data["z"]) == tuple(positions[frame][pose.body_id].tolist())
            roll, pitch, yaw = euler_of_xmat(sim.data.xmat[pose.body_id].tolist())
            assert (data["roll"], data["pitch"], data["yaw"]) == (roll, pitch, yaw)
            if frame > 1:
                moved = math.dist(positions[frame][odometry.body_id].tolist(),
                                  positions[frame - 1][odometry.body_id].tolist())
                assert odometry.local_data["dS"] == moved
            if frame % 2 == 0 and frame > 2:  # gps_raw ticked at this frame and two frames before
                enu = gps_raw.geo.to_enu(positions[frame][gps_raw.body_id].tolist())
                before = gps_raw.geo.to_enu(positions[frame - 2][gps_raw.body_id].tolist())
                assert gps_raw.local_data["velocity"] == ((enu - before) * gps_raw.frequency).tolist()
        assert moved > 0.01  # the robot drove: poses that change from frame to frame
    finally:
        sim.close()


def test_a_sensor_that_moves_its_robot_is_seen_by_the_poses_that_tick_after_it(build):
    """A component that moves bodies during the sensors' ticks (a MORSE sensor setting worldPosition, a teleport
    through the simulation's or the robot's API): the sensors ticking after it in the frame read the poses it set,
    as they read MjData's."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        imu, pose = sim.by_name["robot.imu"].instance, sim.by_name["robot.pose"].instance
        assert [c.fqn for c in sim.sensors].index("robot.imu") < [c.fqn for c in sim.sensors].index("robot.pose")
        robot = imu.robot
        tick = imu.default_action
        moves = iter([lambda p, r: sim.place_body(robot.body_id, p, r), robot.set_pose] * 3)

        def moving_tick():
            tick()
            position, rotation = robot.pose()
            next(moves)(position + [0.5, 0.0, 0.0], rotation)

        imu.default_action = moving_tick  # type: ignore[method-assign]
        for _ in range(6):
            sim.frame()
            sim.answer()
            data = pose.local_data
            assert (data["x"], data["y"], data["z"]) == tuple(sim.data.xpos[pose.body_id].tolist())
        # moved between frames (a service, an actuator's teleport): no copy then, the next sensors take their own
        copied = sim.body_poses
        position, rotation = robot.pose()
        robot.set_pose(position + [0.5, 0.0, 0.0], rotation)
        sim.place_body(robot.body_id, position, rotation)
        assert sim.body_poses is copied
    finally:
        sim.close()


def test_gaussian_noise_draws_at_every_tick_and_is_added_when_read(build):
    """The IMU's noise, a deferrable modifier, draws its row at every tick (the same draws whether the data is
    read or not) and computes nothing; a read computes the last tick's data and adds that tick's noise."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        imu = sim.by_name["robot.imu"]
        noise = imu.modifiers[0]
        rows = sim.rng_for("robot.imu", 0, "noise").normal(0.0, noise.stds, size=(512, 6)).tolist()  # its stream's
        computed = []
        compute = imu.instance.compute
        imu.instance.compute = lambda *sample: (computed.append(sample), compute(*sample))  # type: ignore[method-assign]
        for _ in range(10):
            sim.frame()
            sim.answer()
        assert computed == [] and len(noise._rows) == 512 - 10  # ten rows drawn, nothing computed
        drawn = imu.instance._deferred[0][1]
        assert drawn == rows[9]  # the tenth tick's row, for the tenth tick's data
        read = imu.instance.local_data["angular_velocity"]
        assert len(computed) == 1 and imu.instance._deferred is None
        imu.instance.compute(*computed[0])  # the same tick's data without its noise
        clean = imu.instance.local_dict["angular_velocity"]
        assert read == [c + n for c, n in zip(clean, rows[9][:3])]
    finally:
        sim.close()


def test_every_sampled_sensor_computes_all_its_fields(build):
    """A new sample drops the noise deferred for data nobody read: right only because compute() rewrites every
    field (but the timestamp), so nothing of an earlier tick's data, or noise, stays."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        samples: dict = {}  # a tick's sample of each
        for fqn in SENSORS:
            sample = sim.by_name[fqn].instance.sample

            def keep(fqn=fqn, sample=sample):
                taken = sample()
                if taken is not None:
                    samples[fqn] = taken
                return taken

            sim.by_name[fqn].instance.sample = keep
        for _ in range(6):  # the slowest, the rssi Sick, ticks at 20 Hz
            sim.frame()
            sim.answer()
        assert set(samples) == set(SENSORS)
        for fqn, sample in samples.items():
            sensor = sim.by_name[fqn].instance
            assert isinstance(sensor, SampledSensor), fqn
            stale = object()
            for key in sensor.local_dict:
                if key != "timestamp":  # the loop's (the extended GPS reads it)
                    sensor.local_dict[key] = stale
            sensor.compute(*sample)
            assert [key for key, value in sensor.local_dict.items() if value is stale] == [], fqn
    finally:
        sim.close()


def test_a_cast_reads_of_mjdata_only_what_a_scan_copies(build):
    """The laser scanners' deferred cast rests on this: the installed MuJoCo's mj_multiRay reads from MjData only
    the poses a scan copies (geoms', bodies' inertial frames). Cast on an MjData whose every other
    float is NaN, each scan of a drive where the other robot crosses the rays hits the same geoms at the same
    distances, to the bit."""
    sim = Simulation(build, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        m = sim.model
        poisoned = mujoco.MjData(m)
        for name in dir(poisoned):
            value = getattr(poisoned, name, None)
            if isinstance(value, np.ndarray) and value.dtype.kind == "f":
                value[...] = np.nan
        world = ("geom_xpos", "geom_xmat", "xipos", "ximat")
        roots_hit = set()
        scans = 0
        for frame in range(180):
            for commands, robot in ((COMMANDS, "robot"), (OTHER, "other")):
                if frame in commands:
                    v, w = commands[frame]
                    sim.receive(sim.by_name[f"{robot}.motion"], {"v": v, "w": w})
            sim.frame()
            sim.answer()
            for fqn in ("robot.sick", "robot.velodyne"):
                laser = sim.by_name[fqn].instance
                if laser._sample is None:
                    continue  # no scan at this frame
                scans += 1
                assert len(laser.local_data["range_list"]) == laser.nray  # the cast, in the live MjData
                dist, geomid = laser._dist.copy(), laser._geomid.copy()
                for name in world:
                    getattr(poisoned, name)[...] = getattr(sim.data, name)
                laser.sim = SimpleNamespace(model=m, data=poisoned)
                try:
                    in_poisoned = laser.cast(laser._from, float(laser.properties.laser_range))
                finally:
                    laser.sim = sim
                assert dist.tobytes() == in_poisoned[0].tobytes() and (geomid == in_poisoned[1]).all(), (fqn, frame)
                roots_hit |= set(m.body_rootid[m.geom_bodyid[geomid[geomid >= 0]]].tolist())
        own = m.body_rootid[sim.by_name["robot.sick"].instance.body_id]
        assert scans > 200 and roots_hit - {0, own}  # the other robot seen
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
        for _ in range(20):  # the loop notices them leaving when it reads their sockets
            sim.poller.poll(0.05)
            if not (pose.out_streams[0].listening or odometry.out_streams[0].listening):
                break
        assert not pose.out_streams[0].listening and not odometry.out_streams[0].listening
    finally:
        sim.close()
