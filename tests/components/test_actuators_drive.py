"""Actuators that drive robots through their physics: motion_vw_diff (wheel speeds of a differential
robot), steer_force (a car's steering, engine and brakes), force_torque, external_force, drag (forces on
the robot's body) and quadrotor_dynamic_control (rotor speeds). Each test drives a robot and checks where
it ends up against numbers computed by hand."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from morsec.component.catalogue import load_catalogue
from morsec.testing import simulate

G = 9.81
SUB_MASS = 470.0  # the submarine floats (NoGravity): a clean body to push around
# Bullet's velocity damping of the submarine (Blender's defaults): the fraction of its velocity and turn rate
# it loses per second; as a rate, c = -ln(1 - d)
SUB_DAMPING = load_catalogue().get("robots", "submarine").damping
SUB_RATE = -math.log(1.0 - SUB_DAMPING[0])
SUB_TURN_RATE = -math.log(1.0 - SUB_DAMPING[1])


def scene(robot: str, components: list[str], z: float = 0.0, yaw: float = 0.0, properties: str = "",
          name: str = "r") -> str:
    comps = "".join(f"      - {c}\n" for c in components)
    return f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: {name}
    type: {robot}
    translate: [0.0, 0.0, {z}]
    rotate: [0.0, 0.0, {yaw}]
    {properties}
    components:
{comps}"""


def pushed(accel: float, seconds: float, rate: float) -> float:
    """How far a body starting at rest goes (or turns) in `seconds` under a constant `accel` (m/s^2 or
    rad/s^2) and a velocity damping `rate` (1/s): dv/dt = accel - rate v."""
    return accel / rate * (seconds - (1.0 - math.exp(-rate * seconds)) / rate)


def yaw_change(sim, name: str, seconds: float) -> float:
    """Run `seconds` and return the unwrapped yaw change of robot `name`."""
    yaws = [sim.yaw(name)]
    for _ in range(round(seconds * sim.sim.clock.frequency)):
        sim.step()
        yaws.append(sim.yaw(name))
    return float(np.unwrap(yaws)[-1] - yaws[0])


# ---------------------------------------------------------------- motion_vw_diff

def differential_robots() -> list[str]:
    cat = load_catalogue()
    return [rid for rid in cat.ids("robots")
            if all(hasattr(cat.get("robots", rid), a)
                   for a in ("wheel_radius", "wheel_track", "left_wheel_joints", "right_wheel_joints"))]


@pytest.mark.parametrize("robot", differential_robots())
def test_motion_vw_diff_drives_forward(robot, tmp_path):
    with simulate(scene(robot, ["{name: motion, type: motion_vw_diff}"]), tmp_path) as sim:
        sim.run_for(0.2)
        start, _ = sim.body_pose("r")
        sim.command("r.motion", v=0.5, w=0.0)
        sim.run_for(2.0)
        pos, rot = sim.body_pose("r")
        moved = pos - start
        assert moved[0] == pytest.approx(1.0, abs=0.15)
        assert abs(moved[1]) < 0.05 and abs(sim.yaw("r")) < 0.05
        assert rot[2, 2] > math.cos(math.radians(3))


@pytest.mark.parametrize("robot", differential_robots())
def test_motion_vw_diff_turns_as_commanded(robot, tmp_path):
    with simulate(scene(robot, ["{name: motion, type: motion_vw_diff}"]), tmp_path) as sim:
        sim.run_for(0.2)
        sim.command("r.motion", v=0.5, w=0.25)
        sim.run_for(0.5)  # accelerate
        left = yaw_change(sim, "r", 2.0) / 2.0
        sim.command("r.motion", v=0.5, w=-0.25)
        sim.run_for(0.5)
        right = yaw_change(sim, "r", 2.0) / 2.0
    # skid-steering slips: the rate is w's within the wheels' slip, and symmetric
    assert 0.6 * 0.25 < left < 1.3 * 0.25
    assert right == pytest.approx(-left, rel=0.1)


def test_motion_vw_diff_wheel_speeds_and_services(tmp_path):
    """Wheel speeds are MORSE's, (v -+ e w) / R with e half of FixTurningSpeed, on a robot that turns at w (the
    Pioneer); stop() holds the wheels."""
    with simulate(scene("pioneer3dx", ["{name: motion, type: motion_vw_diff}"],
                        properties="properties: {FixTurningSpeed: 1.0}"), tmp_path) as sim:
        m, d = sim.sim.model, sim.sim.data
        sim.call("r.motion", "set_speed", 0.4, 0.2)
        sim.step()
        radius = 0.0975
        wheels = [m.joint(f"r/{joint}").dofadr[0] for joint in ("wheel_left_joint", "wheel_right_joint")]
        for joint, side in (("wheel_left_joint", 1), ("wheel_right_joint", -1)):
            act = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, f"r.motion/{joint}")
            assert m.actuator_trnid[act][0] == m.joint(f"r/{joint}").id
            assert d.ctrl[act] == pytest.approx((0.4 - side * 0.5 * 0.2) / radius)
        sim.call("r.motion", "stop")
        assert sim.data("r.motion") == {"v": 0.0, "w": 0.0}
        sim.run_for(1.5)
        assert np.abs(d.qvel[wheels]).max() * radius < 0.02  # rim speed, m/s
        assert np.linalg.norm(d.qvel[:3]) < 0.02


def test_motion_vw_diff_skid_steering_wheel_speeds(tmp_path):
    """A skid-steering Segway turns at (v_right - v_left) / 1.2 m of MORSE's wheel speeds, here
    FixTurningSpeed 1.0 * w / 1.2; the four wheels are asked that rate through the model's own effective
    track on MuJoCo (1.6 m), the two of a side at the same speed; stop() holds the wheels."""
    with simulate(scene("segwayrmp400", ["{name: motion, type: motion_vw_diff}"],
                        properties="properties: {FixTurningSpeed: 1.0}"), tmp_path) as sim:
        m, d = sim.sim.model, sim.sim.data
        sim.call("r.motion", "set_speed", 0.4, 0.2)
        sim.step()
        radius, turn = 0.2667, 0.2 * 1.0 / 1.2
        for joint, side in (("wheel_left_joint", 1), ("wheel_rear_left_joint", 1),
                            ("wheel_right_joint", -1), ("wheel_rear_right_joint", -1)):
            act = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, f"r.motion/{joint}")
            assert m.actuator_trnid[act][0] == m.joint(f"r/{joint}").id
            assert d.ctrl[act] == pytest.approx((0.4 - side * 1.6 / 2 * turn) / radius)
        sim.call("r.motion", "stop")
        sim.run_for(1.5)
        assert np.abs(d.qvel[6:10]).max() < 0.05
        assert np.linalg.norm(d.qvel[:3]) < 0.02


def gradual(sim, name: str, v: float, w: float, t: float) -> float:
    """MORSE's segway tests' command profile: a quarter, then half of (v, w), (v, w) for 0.9 t, half, a quarter,
    stop, and a second to settle. Returns what w adds up to (1.025 t w)."""
    tic = t / 20.0
    for share, tics in ((0.25, 2), (0.5, 1), (1.0, 18), (0.5, 2), (0.25, 2)):
        sim.command(f"{name}.motion", v=share * v, w=share * w)
        sim.run_for(tics * tic)
    sim.command(f"{name}.motion", v=0.0, w=0.0)
    sim.run_for(1.0)
    return 1.025 * t * w


@pytest.mark.parametrize(("fix", "yaw"), [(None, 0.0), (0.0, math.pi / 2)])
def test_segway_turns_as_morses(fix, yaw, tmp_path):
    """MORSE's Segway skid-steered as if its wheels were 1.2 m apart: it turned at (v_right - v_left) / 1.2 m.
    With FixTurningSpeed 1.16 (MORSE's default) w = -pi/4 at 1 m/s for 2 s (w adding up to 1.61 rad) turns
    it 1.61 * 1.16 / 1.2 = 1.56 rad, along the arc of that rate; with FixTurningSpeed 0 (the 0.62 m track)
    it turns 0.83 rad, and a Segway set off facing y ends where MORSE's did in its rotated_segway test
    (recorded with that track): x 0.75, y 1.75, yaw 0.75."""
    properties = "" if fix is None else f"properties: {{FixTurningSpeed: {fix}}}"
    with simulate(scene("segwayrmp400", ["{name: motion, type: motion_vw_diff}"], yaw=yaw,
                        properties=properties), tmp_path) as sim:
        sim.run_for(0.3)
        start, rot = sim.body_pose("r")
        yaws = [sim.yaw("r")]
        commanded = gradual(sim, "r", 1.0, -math.pi / 4, 2.0)
        yaws.append(sim.yaw("r"))
        end, _ = sim.body_pose("r")
    turned = float(np.unwrap(yaws)[-1] - yaws[0])
    moved = (rot.T @ (end - start))[:2]
    k = (1.16 if fix is None else fix or 0.62) / 1.2  # the wheel speeds' track over the skid track
    assert turned == pytest.approx(k * commanded, abs=0.025)  # turning at w would be 0.05 more
    r = 1.0 / (k * math.pi / 4)  # the arc: v over the rate
    assert moved == pytest.approx([r * math.sin(-turned), -r * (1 - math.cos(turned))], abs=0.1)
    if fix == 0.0:
        assert (end - start)[:2] == pytest.approx([0.75, 1.75], abs=0.15)
        assert yaws[-1] == pytest.approx(0.75, abs=0.1)


def test_motion_vw_diff_services_are_declared():
    cls = load_catalogue().get("actuators", "MotionVWDiff")
    assert {"set_speed", "stop"} <= set(cls.services())
    assert [f.name for f in cls.data] == ["v", "w"]


# ---------------------------------------------------------------- steer_force

BULLET_DAMPING = -math.log(1.0 - 0.42)  # the Hummer's linear damping, per second


def test_steer_force_drives_brakes_and_steers_a_car(tmp_path):
    with simulate(scene("hummer", ["{name: sf, type: steer_force}"]), tmp_path) as sim:
        d = sim.sim.data
        # MORSE's Hummer faces +x, its frame turned -pi/2 (its y axis is the car's forward)
        assert sim.yaw("r") == pytest.approx(-math.pi / 2, abs=1e-6)
        sim.run_for(2.0)  # settles on its suspension: 4 springs of 15 /s^2 per kg sag by g / 60 on average, the
        # front ones (1.6 m ahead, against 2.3 m behind) more: the origin 0.5 + 0.5 + 0.3 - 0.1635 m up, less
        # the nose's dip at the origin, 0.1635 (2 x 2.3 - 3.9) / 3.9 x 2.3 / 3.9 = 0.0058 m
        start, _ = sim.body_pose("r")
        assert start[2] == pytest.approx(1.1365 - 0.0058, abs=0.002)
        # forward: negative force, as MORSE; 4 x 0.4 x 20 N on 10 kg slowed by Bullet's damping c:
        # v = a / c (1 - exp(-c t)), x = a / c (t - (1 - exp(-c t)) / c)
        sim.command("r.sf", steer=0.0, force=-20.0, brake=0.0)
        sim.run_for(3.0)
        pos, _ = sim.body_pose("r")
        a, c, t = 4 * 0.4 * 20.0 / 10.0, BULLET_DAMPING, 3.0
        assert pos[0] - start[0] == pytest.approx(a / c * (t - (1 - math.exp(-c * t)) / c), rel=0.03)
        assert d.qvel[0] == pytest.approx(a / c * (1 - math.exp(-c * t)), rel=0.03)
        assert abs(pos[1] - start[1]) < 0.01
        # the wheels roll with the ground: v / R about their axles (negative: the axle points right)
        spin = sim.sim.model.joint("r/wheel_rear_left_joint")
        before = d.qpos[spin.qposadr[0]]
        sim.step()
        rolled = math.remainder(d.qpos[spin.qposadr[0]] - before, 2 * math.pi) * 60.0
        assert rolled == pytest.approx(-d.qvel[0] / 0.5, rel=0.05)
        # brake: it stops within a few steps, and stays stopped
        sim.command("r.sf", brake=10.0)
        sim.run_for(0.5)
        assert np.linalg.norm(d.qvel[:3]) < 0.05
        sim.run_for(1.0)
        assert np.linalg.norm(d.qvel[:3]) < 0.05
        stopped, _ = sim.body_pose("r")
        # steer left (positive): the car turns counter-clockwise, towards +y; the front wheels show the angle
        yaw0 = sim.yaw("r")
        sim.command("r.sf", steer=0.3, force=-10.0)
        sim.run_for(3.0)
        pos, _ = sim.body_pose("r")
        assert sim.yaw("r") - yaw0 > 0.3 and pos[1] - stopped[1] > 0.5
        steer = sim.sim.model.joint("r/steer_left_joint")
        assert d.qpos[steer.qposadr[0]] == pytest.approx(0.3, abs=1e-3)
        # steer right: clockwise
        yaw1 = sim.yaw("r")
        sim.command("r.sf", steer=-0.3, force=-10.0)
        sim.run_for(3.0)
        assert sim.yaw("r") - yaw1 < -0.3


def test_steer_force_reverses_and_steers_as_far_as_told(tmp_path):
    """Positive force drives backwards; Bullet's steering has no stop: 1 rad turns the wheels 1 rad and the
    car about a point on its rear axle's line (MORSE's steer_force test: a U-turn within 8 m)."""
    with simulate(scene("hummer", ["{name: sf, type: steer_force}"]), tmp_path) as sim:
        sim.command("r.sf", steer=0.0, force=10.0)
        sim.run_for(1.5)
        pos, _ = sim.body_pose("r")
        assert pos[0] < -0.3 and abs(pos[1]) < 0.01
        sim.command("r.sf", steer=0.0, force=0.0, brake=10.0)
        sim.run_for(1.0)
        start, _ = sim.body_pose("r")
        sim.command("r.sf", steer=-1.0, force=-10.0, brake=0.0)
        sim.run_for(1.0)
        steer = sim.sim.model.joint("r/steer_right_joint")
        assert sim.sim.data.qpos[steer.qposadr[0]] == pytest.approx(-1.0, abs=1e-3)
        turned = yaw_change(sim, "r", 6.0)
        pos, _ = sim.body_pose("r")
        assert turned < -1.2  # to the right, and tightly
        assert np.hypot(*(pos - start)[:2]) < 8.0


def test_hummer_stands_on_its_wheels_without_steer_force(tmp_path):
    """No steer_force, no suspension: the Hummer rests on its wheels, its origin as high as on its springs."""
    with simulate(scene("hummer", ["{name: pose, type: pose}"]), tmp_path) as sim:
        sim.run_for(1.0)
        pos, _ = sim.body_pose("r")
        assert pos[2] == pytest.approx(1.1365, abs=1e-3)


# ---------------------------------------------------------------- force_torque, external_force, drag

def submarine(components: list[str], yaw: float = 0.0) -> str:
    return scene("submarine", components, z=2.0, yaw=yaw)


@pytest.mark.parametrize("yaw", [0.0, math.pi / 2])
def test_force_torque_in_the_robot_frame(yaw, tmp_path):
    comps = ["{name: ft, type: force_torque, properties: {RobotFrame: true}}"]
    with simulate(submarine(comps, yaw), tmp_path) as sim:
        start, _ = sim.body_pose("r")
        sim.command("r.ft", force=[100.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.run_for(2.0)
        pos, _ = sim.body_pose("r")
        expected = pushed(100.0 / SUB_MASS, 2.0, SUB_RATE)
        heading = np.array([math.cos(yaw), math.sin(yaw), 0.0])
        assert pos - start == pytest.approx(expected * heading, abs=0.01 * expected + 1e-3)
        assert abs(sim.yaw("r") - yaw) < 1e-3


def test_force_torque_torque_spins_the_robot(tmp_path):
    comps = ["{name: ft, type: force_torque, properties: {RobotFrame: true}}"]
    with simulate(submarine(comps), tmp_path) as sim:
        izz = sim.sim.robots[0].handle.inertia()[2, 2]
        sim.command("r.ft", force=[0.0, 0.0, 0.0], torque=[0.0, 0.0, 10.0])
        turned = yaw_change(sim, "r", 1.0)
        assert turned == pytest.approx(pushed(10.0 / izz, 1.0, SUB_TURN_RATE), rel=0.02)


def test_force_torque_in_the_actuator_frame_adds_the_lever_arm(tmp_path):
    """An actuator 1 m to the left pushing forward drives the robot forward and yaws it clockwise; an
    actuator turned 90 degrees pushes along its own x axis (the robot's y)."""
    comps = ["{name: ft, type: force_torque, translate: [0.0, 1.0, 0.0]}"]
    with simulate(submarine(comps), tmp_path) as sim:
        sim.command("r.ft", force=[100.0, 0.0, 0.0])
        turned = yaw_change(sim, "r", 1.0)
        pos, _ = sim.body_pose("r")
        assert turned < -0.005 and pos[0] > 0.05
    comps = ["{name: ft, type: force_torque, rotate: [0.0, 0.0, 1.5708]}"]
    with simulate(submarine(comps), tmp_path, name="turned") as sim:
        start, _ = sim.body_pose("r")
        sim.command("r.ft", force=[100.0, 0.0, 0.0])
        sim.run_for(1.0)
        moved = sim.body_pose("r")[0] - start
        assert moved[1] == pytest.approx(pushed(100.0 / SUB_MASS, 1.0, SUB_RATE), rel=0.02) and abs(moved[0]) < 1e-3


def test_force_torque_at_the_origin_does_not_turn_the_robot(tmp_path):
    """MORSE measures the lever arm from the robot's origin (Blender's centre of mass of the body): a
    ForceTorque at an ATRV's origin, whose centre of mass is 0.2 m above it, pushes it without pitching
    it (MORSE's drag and external_force tests: an ATRV held at z = 1 speeds up along x only)."""
    comps = ["{name: ft, type: force_torque}"]
    with simulate(scene("atrv", comps, z=1.0, properties="properties: {NoGravity: true}"), tmp_path) as sim:
        _, start_rot = sim.body_pose("r")
        sim.command("r.ft", force=[100.0, 0.0, 0.0])
        sim.run_for(1.0)
        _, rot = sim.body_pose("r")
        linear, angular = sim.sim.robots[0].handle.velocity()
        assert np.allclose(rot, start_rot, atol=1e-6) and np.allclose(angular, 0.0, atol=1e-6)
        assert linear[0] > 1.0 and abs(linear[2]) < 1e-6


def test_a_pushed_atrv_coasts_slowed_by_its_damping(tmp_path):
    """MORSE's drag and external_force tests: an ATRV held at z = 1 (lock_location_z) and pushed by 100 N
    speeds up at 5 m/s^2 (MORSE's ATRV weighs 20 kg); let go, it coasts, losing 2 % of its speed per
    second (its Bullet damping), 4 % for a robot with Blender's default damping."""
    comps = ["{name: ft, type: force_torque}"]
    atrv = scene("atrv", comps, z=1.0, properties="locks: [location_z]")
    damping = load_catalogue().get("robots", "atrv").damping[0]
    assert damping == pytest.approx(0.02)
    with simulate(atrv, tmp_path) as sim:
        assert sim.sim.robots[0].handle.mass == pytest.approx(20.0)
        sim.command("r.ft", force=[100.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.run_for(1.0)
        rate = -math.log(1.0 - damping)
        v = sim.sim.data.qvel[0]
        assert v == pytest.approx(5.0 / rate * (1.0 - math.exp(-rate)), rel=1e-3)
        sim.command("r.ft", force=[0.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.run_for(2.0)
        assert sim.sim.data.qvel[0] / v == pytest.approx((1.0 - damping) ** 2, rel=1e-3)
        _, rot = sim.body_pose("r")
        assert np.allclose(rot, np.eye(3), atol=1e-6)  # pushed and held through its centre of mass
    with simulate(submarine(["{name: ft, type: force_torque, properties: {RobotFrame: true}}"]), tmp_path,
                  name="default") as sim:
        sim.command("r.ft", force=[470.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.run_for(0.5)
        sim.command("r.ft", force=[0.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.step()
        v = sim.sim.data.qvel[0]
        sim.run_for(1.0)
        assert SUB_DAMPING == (0.04, 0.1)
        assert sim.sim.data.qvel[0] / v == pytest.approx(0.96, rel=1e-3)


def test_a_locked_robot_is_held_at_its_centre_of_mass(tmp_path):
    """Bullet's lock_location_z holds a body's centre of mass (a Blender robot's origin); held at its origin,
    0.2 m below its centre of mass, a tilted ATRV held up in the air would balance on a point and topple."""
    atrv = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - {name: r, type: atrv, translate: [0.0, 0.0, 1.0], rotate: [0.0, 0.1, 0.0], locks: [location_z]}
"""
    with simulate(atrv, tmp_path) as sim:
        pitch = -math.asin(sim.body_pose("r")[1][2, 0])
        assert pitch == pytest.approx(0.1, abs=1e-6)
        sim.run_for(2.0)
        pos, rot = sim.body_pose("r")
        assert -math.asin(rot[2, 0]) == pytest.approx(0.1, abs=1e-3) and pos[2] == pytest.approx(1.0, abs=1e-3)


def test_external_force_is_in_the_world_frame_and_adds_up(tmp_path):
    comps = ["{name: wind, type: external_force}",
             "{name: ft, type: force_torque, properties: {RobotFrame: true}}"]
    with simulate(submarine(comps, yaw=math.pi / 2), tmp_path) as sim:
        start, _ = sim.body_pose("r")
        sim.command("r.wind", force=[100.0, 0.0, 0.0], torque=[0.0, 0.0, 0.0])
        sim.run_for(1.0)
        moved = sim.body_pose("r")[0] - start
        assert moved == pytest.approx([pushed(100.0 / SUB_MASS, 1.0, SUB_RATE), 0.0, 0.0], abs=2e-3)
        # the robot's own thrusters push along its x axis (world y) while the wind pushes along world x:
        # against a wind along world -y of the same size, the two cancel
        sim.command("r.wind", force=[0.0, -100.0, 0.0])
        sim.command("r.ft", force=[100.0, 0.0, 0.0])
        sim.step()
        assert sim.sim.data.xfrc_applied[sim.sim.robots[0].handle.body_id] == pytest.approx(np.zeros(6), abs=1e-6)


def test_drag_gives_a_terminal_velocity(tmp_path):
    comps = ["{name: ft, type: force_torque, properties: {RobotFrame: true}}",
             "{name: water, type: drag, properties: {DragCoeffX: 100.0}}"]
    with simulate(submarine(comps), tmp_path) as sim:
        sim.command("r.ft", force=[100.0, 0.0, 0.0])
        sim.run_for(12.0)
        v = sim.sim.data.qvel[0]
        # thrust = drag + damping: 100 = 100 v^2 + m c v
        damping = SUB_MASS * SUB_RATE
        terminal = (-damping + math.sqrt(damping ** 2 + 4 * 100.0 * 100.0)) / (2 * 100.0)
        assert v == pytest.approx(terminal, rel=0.03)
        # cut the thrust: drag and damping slow it down, dv/dt = -a v^2 - c v (a = C / m), which gives
        # v(t) = c / ((c / v0 + a) exp(c t) - a)
        sim.command("r.ft", force=[0.0, 0.0, 0.0])
        sim.run_for(2.0)
        a, c = 100.0 / SUB_MASS, SUB_RATE
        expected = c / ((c / v + a) * math.exp(c * 2.0) - a)
        assert sim.sim.data.qvel[0] == pytest.approx(expected, rel=0.03)


def test_drag_is_not_exportable():
    cls = load_catalogue().get("actuators", "Drag")
    assert cls.exportable is False and not cls.data
    assert cls.Properties().model_dump() == {"DragCoeffX": 0.09, "DragCoeffY": 0.09, "DragCoeffZ": 0.5}


# ---------------------------------------------------------------- quadrotor_dynamic_control

def quadrotor(configuration: str = "+") -> str:
    return scene("quadrotor", [f"{{name: engines, type: quadrotor_dynamic_control, "
                               f"properties: {{Configuration: '{configuration}'}}}}"], z=1.0)


def hover_speed(mass: float) -> float:
    return math.sqrt(mass * G / (4 * 9.169e-6))


def test_quadrotor_hovers_then_climbs(tmp_path):
    with simulate(quadrotor(), tmp_path) as sim:
        mass = sim.sim.robots[0].handle.mass
        w = hover_speed(mass)
        sim.command("r.engines", engines=[w] * 4)
        start, _ = sim.body_pose("r")
        sim.run_for(2.0)
        pos, rot = sim.body_pose("r")
        assert np.linalg.norm(pos - start) < 0.02 and rot[2, 2] > 0.9999
        sim.command("r.engines", engines=[1.05 * w] * 4)
        sim.run_for(1.0)
        climbed = sim.body_pose("r")[0][2] - pos[2]
        assert climbed == pytest.approx(0.5 * G * (1.05 ** 2 - 1) * 1.0 ** 2, rel=0.03)


@pytest.mark.parametrize("configuration, rotor, axis, sign", [
    ("+", 2, 0, +1),   # rotor 3 (+x) faster: nose up, negative pitch
    ("+", 3, 1, +1),   # rotor 4 (+y) faster: positive roll
    ("x", 0, 1, +1),   # rotor 1 (front left) faster: positive roll, negative pitch
])
def test_quadrotor_rotor_torques(configuration, rotor, axis, sign, tmp_path):
    from morsec.kits.geometry import matrix_to_euler
    with simulate(quadrotor(configuration), tmp_path) as sim:
        w = hover_speed(sim.sim.robots[0].handle.mass)
        engines = [w] * 4
        engines[rotor] *= 1.01
        sim.command("r.engines", engines=engines)
        sim.run_for(0.3)
        roll, pitch, yaw = matrix_to_euler(sim.body_pose("r")[1])
        if (configuration, rotor) == ("+", 2):
            assert pitch < -0.01 and abs(roll) < 1e-3
        elif (configuration, rotor) == ("+", 3):
            assert roll > 0.01 and abs(pitch) < 1e-3
        else:
            assert roll > 0.005 and pitch < -0.005
        # rotors 1 and 3 turn clockwise: their drag yaws the body clockwise
        assert (yaw < 0) == (rotor in (0, 2))


def test_quadrotor_dynamic_control_declares_morse_properties():
    cls = load_catalogue().get("actuators", "QuadrotorDynamicControl")
    assert cls.Properties().model_dump() == {"ThrustFactor": 9.169e-6, "DragFactor": 2.4e-7, "Lever": 0.18,
                                             "Configuration": "+"}
    assert [(f.name, f.default) for f in cls.data] == [("engines", [0.0, 0.0, 0.0, 0.0])]


def test_wheel_actuator_on_a_robot_without_wheels_is_a_scene_error(tmp_path):
    from morsec.app.project import build_scene
    from morsec.errors import SceneError
    source = tmp_path / "s.yaml"
    source.write_text("robots:\n  - name: r\n    type: atrv\n    components:\n      - {name: m, type: motion_vw_diff}\n")
    with pytest.raises(SceneError) as err:
        build_scene(source, tmp_path / "b")
    assert str(err.value) == (f"{source}:5:25: robots[0].components[0].type: 'motion_vw_diff' needs a robot declaring "
                              "wheel_radius, wheel_track, left_wheel_joints, right_wheel_joints; robot type 'atrv' "
                              "does not (these do: patrolbot, pioneer3dx, segwayrmp400)")
    assert not (tmp_path / "b").exists()
