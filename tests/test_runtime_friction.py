"""MORSE's ground friction against velocity control (morsec.kits.ground_friction): an ATRV driven by
motion_vw goes a little slower than commanded, by what Bullet's Coulomb friction took between two ticks of
MORSE (the robot's friction times the ground's 0.5), and a Waypoint robot that stops slides on."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest
from runtime_helpers import Morsec, pose_sensor, robot, scene, scene_file, start_all, stop_all
from test_runtime_motion import MOTION, Recorder, at, drive, start_index

from morsec.kits import ground_friction
from morsec.testing import simulate

G = 9.81


def test_slide_is_coulomb_over_two_substeps():
    mu = ground_friction.ground_friction(None)
    assert mu == 0.25  # Blender's 0.5 for the robot and the ground, multiplied as Bullet does
    mean, end, ticks = ground_friction.slide(1.0, 0.0, mu, G, 1 / 60, 1 / 60)
    assert mean[0] == pytest.approx(1.0 - 0.75 * mu * G / 60)  # velocity first, then position, twice
    assert end[0] == pytest.approx(1.0 - mu * G / 60)
    assert ticks == pytest.approx((end[0] / mean[0],))  # what the sensors read at the tick's end
    # left alone it stops after v^2 / (2 mu g), never turned back
    speed, moved = (1.0, 0.0), 0.0
    for _ in range(120):
        mean, speed, _ = ground_friction.slide(*speed, mu, G, 1 / 60, 1 / 60)
        moved += mean[0] / 60
    assert speed == (0.0, 0.0)
    assert moved == pytest.approx(1 / (2 * mu * G), abs=0.01)
    # turning, the yaw rate loses 2 % at any speed (MORSE's vw_testing turns at 0.5, 1 and 2 m/s); on the spot nothing
    for speed in (0.5, 2.0):
        v, _, w = ground_friction.turned(speed, 0.0, -0.4, ground_friction.slide(speed, 0.0, mu, G, 1 / 60, 1 / 60).mean)
        assert v == pytest.approx(speed - 0.75 * mu * G / 60)
        assert w == pytest.approx(-0.4 * 0.98)
    assert ground_friction.turned(0.0, 0.0, 1.0, (0.0, 0.0))[2] == 1.0


def test_slide_damps_before_friction_each_substep():
    """Bullet damps the velocity (v *= (1 - d)^h), then friction takes mu g h, then the body moves: a Morsy
    (damping 0.493) set going at 1 m/s ends the tick at 0.9480 m/s (MORSE's airspeed_testing reads 0.55 Pa
    = 0.5 x 1.225 x 0.9476^2), 2 m/s at 1.9367 (2.30 Pa)."""
    mu, h = ground_friction.ground_friction(None), 1 / 120
    for start, morse_pa in ((1.0, 0.55), (2.0, 2.30)):
        slid = ground_friction.slide(0.0, start, mu, G, 1 / 60, 1 / 60, damping=0.493)
        v1 = start * 0.507 ** h - mu * G * h
        v2 = v1 * 0.507 ** h - mu * G * h
        assert slid.end[1] == pytest.approx(v2)
        assert slid.mean[1] == pytest.approx((v1 + v2) / 2)
        assert 0.5 * 1.225 * slid.end[1] ** 2 == pytest.approx(morse_pa, abs=0.005)
    # off the ground (mu 0) damping alone; a slower actuator: one share per tick of its period
    slid = ground_friction.slide(1.0, 0.0, 0.0, G, 1 / 10, 1 / 60, damping=0.5)
    assert slid.end[0] == pytest.approx(0.5 ** 0.1)
    assert len(slid.ticks) == 6 and list(slid.ticks) == sorted(slid.ticks, reverse=True)
    assert slid.ticks[-1] * slid.mean[0] == pytest.approx(slid.end[0])


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("friction")
    process = Morsec(scene_file(tmp, scene(
        robot("slippery", pose_sensor(), MOTION, translate=[0.0, -3.0, 0.0], friction=0.0),
        robot("plain", pose_sensor(), MOTION),
        robot("sticky", pose_sensor(), MOTION, translate=[0.0, 3.0, 0.0], friction=5.0),
        strategy="fixed_step")), tmp)
    start_all(process)
    try:
        yield process
    finally:
        stop_all(process)


def test_friction_slows_a_robot_driven_by_velocity(sim):
    """MORSE's friction_testing: 2 s at 1 m/s go 2.0 m at friction 0 and 1.4 m at friction 5; the
    default friction costs 3 cm/s."""
    names = ("slippery", "plain", "sticky")
    recorders = {f"{name}.pose": Recorder(sim, f"{name}.pose") for name in names}
    records = drive(sim, {name: {"v": 1.0, "w": 0.0} for name in names}, 2.0, recorders)
    gone = {}
    for name in names:
        poses = records[f"{name}.pose"]
        rest = poses[start_index(poses)]
        gone[name] = at(poses, rest["timestamp"] + 2.0)["x"] - rest["x"]
    assert gone["slippery"] == pytest.approx(2.0, abs=0.03)
    assert gone["plain"] == pytest.approx(2.0 * (1 - 0.75 * 0.25 * G / 60), abs=0.03)
    assert gone["sticky"] == pytest.approx(2.0 * (1 - 0.75 * 2.5 * G / 60), abs=0.05)
    assert gone["plain"] < gone["slippery"] - 0.03
    assert not math.isclose(gone["sticky"], gone["plain"], abs_tol=0.3)


ATRV_XYW = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: motion, type: motion_xyw}
      - {name: vel, type: velocity}
      - {name: vel_pos, type: velocity, properties: {ComputationMode: Position}}
"""


def test_a_robot_driven_sideways_neither_rocks_nor_hops(tmp_path):
    """MORSE's velocity_testing: an ATRV driven sideways reads no roll or pitch rate and no vertical speed
    (MORSE's set the whole velocity at each tick). MuJoCo's sliding contacts lifted it: at 1 m/s sideways it
    hopped at +-0.1 m/s and rocked at +-0.3 rad/s, whatever the friction; a robot driven by velocity has no
    friction in its contacts, the ground's friction on it is MORSE's, in its servos' targets."""
    with simulate(ATRV_XYW, tmp_path) as h:
        h.run_for(0.3)
        for x, y, w in ((0.0, -1.0, 0.0), (0.0, 2.0, 0.0), (1.0, 0.0, 1.0), (0.0, 0.0, 0.0)):
            h.command("robot.motion", x=x, y=y, w=w)
            for tick in range(60):
                h.step()
                vel = h.data("robot.vel")
                up, (roll, pitch, _) = vel["linear_velocity"][2], vel["angular_velocity"]
                assert max(abs(up), abs(roll), abs(pitch)) < 0.02, (x, y, w, tick, up, roll, pitch)
            assert abs(h.body_pose("robot")[0][2] - 0.1) < 0.002  # on its wheels


def test_sensors_read_the_speed_left_at_the_end_of_the_tick(tmp_path):
    """MORSE's sensors read the body's velocity when the tick's physics had slowed it (ground friction, then
    damping): 1 - mu g / 60 of 1 m/s; the robot goes at the tick's mean speed (Position mode, poses)."""
    slid = ground_friction.slide(1.0, 0.0, ground_friction.ground_friction(None), G, 1 / 60, 1 / 60, 0.02)
    assert slid.end[0] == pytest.approx(1.0 - 0.25 * G / 60, abs=1e-3)
    with simulate(ATRV_XYW, tmp_path) as h:
        h.run_for(0.3)
        h.command("robot.motion", x=1.0, y=0.0, w=0.0)
        h.run_for(0.5)
        x0 = h.body_pose("robot")[0][0]
        h.run_for(1.0)
        assert h.body_pose("robot")[0][0] - x0 == pytest.approx(slid.mean[0], abs=0.002)
        assert h.data("robot.vel")["linear_velocity"][0] == pytest.approx(slid.end[0], abs=0.001)
        assert h.data("robot.vel")["world_linear_velocity"][0] == pytest.approx(slid.end[0], abs=0.001)
        assert h.data("robot.vel_pos")["linear_velocity"][0] == pytest.approx(slid.mean[0], abs=0.001)
        # the physics goes on at the held speed: 60 more ticks, as far again
        x1 = h.body_pose("robot")[0][0]
        h.run_for(1.0)
        assert h.body_pose("robot")[0][0] - x1 == pytest.approx(slid.mean[0], abs=0.002)


def test_only_robots_driven_by_velocity_lose_their_contact_friction(build_yaml):
    """A ground robot whose velocity an actuator sets (base servos) has frictionless contacts that win over
    the ground's (priority); one pushed by forces, or driven through its wheels, keeps MuJoCo's friction."""
    out = build_yaml("""
environment: {name: empty}
robots:
  - {name: driven, type: atrv, components: [{name: motion, type: motion_vw}]}
  - {name: pushed, type: atrv, translate: [0.0, 3.0, 0.0], components: [{name: force, type: force_torque}]}
  - {name: wheeled, type: pioneer3dx, translate: [0.0, -3.0, 0.0],
     components: [{name: motion, type: motion_vw_diff}]}
""")
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    for name, frictionless in (("driven", True), ("pushed", False), ("wheeled", False)):
        root = model.body(name).id
        geoms = [g for g in range(model.ngeom)
                 if model.body_rootid[model.geom_bodyid[g]] == root and model.geom_contype[g]]
        assert geoms
        for g in geoms:
            assert bool(model.geom_condim[g] == 1 and model.geom_priority[g] == 1) is frictionless, name


def test_the_ground_check_reads_the_contacts_of_every_frame(build_yaml):
    """Simulation.touching (whether a robot rests on something: MORSE's ground friction) keeps its view of the
    contacts' geom pairs while their number stays the same (MuJoCo fills its contacts from the start of MjData's
    arena): at every frame it reads the pairs MuJoCo's contact list holds then, also when they changed and their
    number did not (the robot put from the ground onto a step, eight contacts either way)."""
    from morsec.runtime.simulation import RunOptions, Simulation

    out = build_yaml("""
environment: {name: empty, time: {strategy: fixed_step, frequency: 60}}
robots:
  - {name: robot, type: atrv, components: [{name: motion, type: motion_vw}]}
  - {name: flyer, type: atrv, translate: [0.0, 5.0, 3.0], properties: {NoGravity: true}}
objects:
  - {name: step, type: box, translate: [3.0, 0.0, 0.1], size: [2.0, 2.0, 0.2], dynamic: false}
""")
    sim = Simulation(out, RunOptions(strategy="fixed_step", service_port=0, port_base=0))
    try:
        handle, owner = sim.robots[0].handle, sim._geom_robot
        same_number_new_pairs, previous = 0, None
        for frame in range(80):
            if frame % 10 == 5:  # from the ground onto the step's top, and back
                handle.set_pose([3.0, 0.0, 0.3] if frame % 20 == 5 else [0.0, 0.0, 0.1], np.eye(3))
            sim.frame()
            sim.answer()
            pairs = sim.data.contact.geom.copy()  # asked for afresh
            sim._touching = None
            touching = sim.touching()
            assert sim._contact_view.tobytes() == pairs.tobytes(), frame  # what touching compares
            assert sim._contact_seen.tobytes() == pairs.tobytes(), frame  # ... with the pairs it looked at last
            assert touching == {owner[g] for a, b in pairs.tolist() if owner[a] != owner[b] for g in (a, b)} - {-1}
            assert touching == {0}, frame  # the robot on the ground or the step, the flyer on nothing
            if previous is not None and len(previous) == len(pairs) and previous.tobytes() != pairs.tobytes():
                same_number_new_pairs += 1
            previous = pairs
        assert same_number_new_pairs >= 6  # the view kept was read, not asked for again
    finally:
        sim.close()
