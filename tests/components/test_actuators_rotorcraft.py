"""Rotorcraft actuators (rotorcraft_waypoint, rotorcraft_velocity, rotorcraft_attitude, stabilized_quadrotor)
flying a quadrotor that has its weight: they act through forces and torques on its base (d.xfrc_applied)
or, for stabilized_quadrotor, through MORSE's linear model. Each test checks where the robot ends up."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from morsec.component.catalogue import load_catalogue
from morsec.testing import simulate

# a 1.0 kg rigid body the size of a quadrotor, used when the catalogue has no `quadrotor` robot
TEST_QUAD = {
    "component.py": '''from morsec.component import Robot


class TestQuad(Robot):
    """A 1.0 kg quadrotor-sized rigid body (tests)."""

    short_descr = "test quadrotor"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.05


COMPONENT = TestQuad
''',
    "robot.urdf.xacro": '''<?xml version="1.0"?>
<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="name" default="testquad"/>
  <link name="base_link">
    <inertial><mass value="1.0"/><inertia ixx="0.008" ixy="0" ixz="0" iyy="0.008" iyz="0" izz="0.014"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision>
  </link>
</robot>
''',
}


@pytest.fixture(scope="module")
def quad(tmp_path_factory) -> tuple[str, Path | None]:
    """(robot type, project folder): the catalogue's quadrotor, or a test one in a project folder."""
    if "quadrotor" in load_catalogue(Path(__file__).parent).ids("robots"):
        return "quadrotor", None
    project = tmp_path_factory.mktemp("project")
    (project / "morsec.toml").write_text('[project]\ncomponents = ["components"]\n')
    folder = project / "components" / "robots" / "testquad"
    folder.mkdir(parents=True)
    for name, text in TEST_QUAD.items():
        (folder / name).write_text(text)
    return "testquad", project


def flying(quad, actuator: str, z: float = 1.0) -> tuple[str, dict]:
    robot_type, project = quad
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: quad
    type: {robot_type}
    translate: [0.0, 0.0, {z}]
    components:
      - {{name: pose, type: pose}}
      - {actuator}
"""
    return text, {"project": project}


def pose(h) -> dict:
    return h.data("quad.pose")


def position(h) -> np.ndarray:
    p = pose(h)
    return np.array([p["x"], p["y"], p["z"]])


def velocity(h, fqn: str = "quad.motion") -> np.ndarray:
    return h.component(fqn).robot.velocity()[0]


# ------------------------------------------------------------------------------------------- rotorcraft_waypoint
def test_rotorcraft_waypoint_holds_its_initial_point(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_waypoint}")
    with simulate(text, tmp_path, **kw) as h:
        wp = h.component("quad.motion")
        assert list(h.data("quad.motion")) == ["x", "y", "z", "yaw", "tolerance"]
        props = wp.properties.model_dump()
        assert props["HorizontalPgain"] == pytest.approx(math.radians(6))
        assert props["MaxBankAngle"] == pytest.approx(math.radians(30))
        assert (props["VerticalPgain"], props["RollPitchPgain"], props["RemainAtDestination"], props["Target"]) == \
            (8.0, 9.7, True, "wp_target")
        start = h.body_pose("quad")[0]
        h.run_for(3.0)
        assert h.body_pose("quad")[0] == pytest.approx(start, abs=0.02)  # it carries its weight
        assert wp.get_status() == "Arrived"


def test_rotorcraft_waypoint_target_marker_does_not_push_the_robot(quad, tmp_path):
    """MORSE's rotorcraft_waypoint_testing: a `Sphere('wp_target')` is the default Target; the actuator puts
    it on its goal, the robot's own position at first. MORSE's marker had NO_COLLISION; a colliding one
    pushed the quadrotor up (2.1 m then 48 m for 1.81 m). It is made visual only: no contact, no ray."""
    import mujoco

    text, kw = flying(quad, "{name: motion, type: rotorcraft_waypoint}", z=1.81)
    text += "objects:\n  - {name: wp_target, type: sphere, size: [1.0, 1.0, 1.0]}\n"
    with simulate(text, tmp_path, **kw) as h:
        start = h.body_pose("quad")[0]
        h.run_for(2.0)
        assert h.body_pose("quad")[0] == pytest.approx(start, abs=0.02)
        assert h.body_pose("wp_target")[0] == pytest.approx(start, abs=1e-6)  # on the goal
        m, d = h.sim.model, h.sim.data
        marker = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "wp_target")
        geoms = [g for g in range(m.ngeom) if m.geom_bodyid[g] == marker]
        assert geoms and all(m.geom_contype[g] == 0 and m.geom_conaffinity[g] == 0 for g in geoms)
        hit = np.array([-1], dtype=np.int32)
        seen = np.array([0 if g in (2, 5) else 1 for g in range(mujoco.mjNGROUP)], dtype=np.uint8)  # as a laser
        mujoco.mj_ray(m, d, start + [3.0, 0.0, 0.0], np.array([-1.0, 0.0, 0.0]), seen, 1, -1, hit)
        assert hit[0] not in geoms  # rays see through it, as through MORSE's NO_COLLISION objects


def test_rotorcraft_waypoint_flies_to_a_point_and_heading(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_waypoint}")
    with simulate(text, tmp_path, **kw) as h:
        wp = h.component("quad.motion")
        h.command("quad.motion", x=2.0, y=1.0, z=3.0, yaw=1.0, tolerance=0.2)
        h.step()
        assert wp.get_status() == "Transit"
        h.run_for(8.0)
        assert np.linalg.norm(position(h) - [2.0, 1.0, 3.0]) <= 0.2
        assert pose(h)["yaw"] == pytest.approx(1.0, abs=0.05)
        assert wp.get_status() == "Arrived"


def test_rotorcraft_waypoint_goto_answers_arrived_and_can_be_preempted(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_waypoint, services: [socket]}")
    with simulate(text, tmp_path, **kw) as h:
        client = h.client()
        first = client.send("quad.motion", "goto", 5.0, 0.0, 2.0, 0.0)
        h.run_for(0.5)
        second = client.send("quad.motion", "goto", -1.0, 1.0, 2.0, 0.0, 0.3)
        h.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
        assert client.replies[first] == ("PREEMPTED", None)
        h.run_for(10.0)
        assert client.replies[second] == ("SUCCESS", "Arrived")
        assert np.linalg.norm(position(h) - [-1.0, 1.0, 2.0]) <= 0.3
        rid = client.send("quad.motion", "setdest", -1.0, 1.0, 2.0, 0.0, 0.3)
        assert client.replies[rid] == ("SUCCESS", False)  # already there


# ------------------------------------------------------------------------------------------- rotorcraft_velocity
def test_rotorcraft_velocity_holds_the_commanded_velocity(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_velocity}", z=2.0)
    with simulate(text, tmp_path, **kw) as h:
        assert list(h.data("quad.motion")) == ["vx", "vy", "vz", "vyaw", "tolerance"]
        h.run_for(1.0)
        assert np.linalg.norm(velocity(h)) < 0.02  # hovers
        h.command("quad.motion", vx=0.0, vy=0.0, vz=0.5, vyaw=0.0)
        h.run_for(2.0)
        assert velocity(h) == pytest.approx([0.0, 0.0, 0.5], abs=0.05)
        h.command("quad.motion", vx=1.0, vy=0.0, vz=0.0, vyaw=0.0)
        h.run_for(15.0)
        assert velocity(h) == pytest.approx([1.0, 0.0, 0.0], abs=0.1)
        x, z = pose(h)["x"], pose(h)["z"]
        h.run_for(1.0)
        assert pose(h)["x"] - x == pytest.approx(1.0, abs=0.1)
        assert pose(h)["z"] == pytest.approx(z, abs=0.05)  # holds its height
        assert pose(h)["yaw"] == pytest.approx(0.0, abs=0.02)


def test_rotorcraft_velocity_yaw_rate_and_setvel(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_velocity}", z=2.0)
    with simulate(text, tmp_path, **kw) as h:
        assert h.call("quad.motion", "setvel", 0.0, 0.0, 0.0, 0.0) is False  # already still
        assert h.call("quad.motion", "setvel", 0.0, 0.0, 0.0, 0.5) is True
        h.run_for(2.0)
        assert pose(h)["yaw"] == pytest.approx(1.0, abs=0.1)  # counter-clockwise
        assert np.linalg.norm(velocity(h)) < 0.05


# ------------------------------------------------------------------------------------------- rotorcraft_attitude
def test_rotorcraft_attitude_hovers_and_tilts_in_ned(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_attitude}", z=2.0)
    with simulate(text, tmp_path, **kw) as h:
        assert list(h.data("quad.motion")) == ["roll", "pitch", "yaw", "thrust"]
        robot = h.component("quad.motion").robot
        hover = robot.weight() / 40.0  # ThrustFactor 40 N at full thrust
        start = h.body_pose("quad")[0]
        h.command("quad.motion", roll=0.0, pitch=0.0, yaw=0.0, thrust=hover)
        h.run_for(1.0)
        assert h.body_pose("quad")[0] == pytest.approx(start, abs=0.05)
        # NED pitch 0.1: nose up, the thrust pulls backwards (-x); the height is about kept
        h.command("quad.motion", roll=0.0, pitch=0.1, yaw=0.0, thrust=hover / math.cos(0.1))
        h.run_for(1.0)
        assert pose(h)["pitch"] == pytest.approx(-0.1, abs=0.02)
        assert velocity(h)[0] < -0.7 and abs(velocity(h)[1]) < 0.05
        # NED roll 0.1: right side down, it goes right (-y)
        h.command("quad.motion", roll=0.1, pitch=0.0, yaw=0.0, thrust=hover / math.cos(0.1))
        h.run_for(1.0)
        assert pose(h)["roll"] == pytest.approx(0.1, abs=0.02)
        assert velocity(h)[1] < -0.7
        # thrust 0: released, it falls
        h.command("quad.motion", roll=0.0, pitch=0.0, yaw=0.0, thrust=0.0)
        h.run_for(0.3)
        assert velocity(h)[2] < -2.0


def test_rotorcraft_attitude_yaw_rate_is_clockwise(quad, tmp_path):
    text, kw = flying(quad, "{name: motion, type: rotorcraft_attitude}", z=2.0)
    with simulate(text, tmp_path, **kw) as h:
        hover = h.component("quad.motion").robot.weight() / 40.0
        h.command("quad.motion", roll=0.0, pitch=0.0, yaw=0.5, thrust=hover)
        h.run_for(2.0)
        assert pose(h)["yaw"] == pytest.approx(-1.0, abs=0.3)  # NED yaw rate: clockwise seen from above


# ------------------------------------------------------------------------------------------- stabilized_quadrotor
def test_stabilized_quadrotor_follows_morse_linear_model(quad, tmp_path):
    """The numbers of MORSE's stabilized_quadrirotor_testing.py."""
    text, kw = flying(quad, "{name: motion, type: stabilized_quadrotor, services: [socket]}")
    with simulate(text, tmp_path, **kw) as h:
        assert list(h.data("quad.motion")) == ["theta_c", "phi_c", "psi_c", "h_c"]
        h.command("quad.motion", theta_c=0.0, phi_c=0.0, psi_c=0.0, h_c=10.0)
        h.run_for(3.0)
        assert position(h) == pytest.approx([0.0, 0.0, 10.0], abs=0.2)
        h.command("quad.motion", theta_c=0.1, phi_c=0.0, psi_c=0.0, h_c=10.0)
        h.run_for(1.0)
        p1 = pose(h)
        assert (p1["x"], p1["y"], p1["z"]) == pytest.approx((0.4, 0.0, 10.0), abs=0.2)
        assert p1["pitch"] == pytest.approx(0.1, abs=0.1)
        h.run_for(1.0)
        assert pose(h)["x"] == pytest.approx(0.4 + 1.4, abs=0.2)
        h.command("quad.motion", theta_c=0.0, phi_c=0.0, psi_c=0.0, h_c=10.0)
        h.run_for(1.0)
        x3 = pose(h)["x"]
        assert x3 == pytest.approx(0.4 + 1.4 + 2.0, abs=0.2)
        h.run_for(1.0)
        assert pose(h)["x"] == pytest.approx(x3 + 2.0, abs=0.2)  # no drag: the velocity stays
        client = h.client()
        client.send("quad.motion", "stop")
        h.run_for(1.0)
        assert pose(h)["x"] == pytest.approx(x3 + 2.0, abs=0.2)
        # psi_c: a yaw rate of about -psi_c * 10 / 1.4
        h.command("quad.motion", theta_c=0.0, phi_c=0.0, psi_c=0.1, h_c=12.0)
        h.run_for(1.0)
        assert pose(h)["yaw"] == pytest.approx(-0.69, abs=0.1)
        h.run_for(1.0)
        assert pose(h)["yaw"] == pytest.approx(-1.38, abs=0.1)
        assert pose(h)["z"] == pytest.approx(12.0, abs=0.2)
        # phi_c: acceleration towards -y
        h.command("quad.motion", theta_c=0.0, phi_c=0.1, psi_c=0.0, h_c=12.0)
        client.send("quad.motion", "stop")
        h.command("quad.motion", theta_c=0.0, phi_c=0.1, psi_c=0.0, h_c=12.0)
        y0, yaw = pose(h)["y"], pose(h)["yaw"]
        h.run_for(1.0)
        moved = np.array([pose(h)["x"] - (x3 + 2.0), pose(h)["y"] - y0])
        # 0.4 m in the direction of the robot's -y axis (it faces `yaw`)
        assert moved == pytest.approx(0.4 * np.array([math.sin(yaw), -math.cos(yaw)]), abs=0.2)


def morse_stabilized_quadrotor(commands: list[tuple[float, float, float, float]], z0: float) -> np.ndarray:
    """MORSE's StabilizedQuadrotor replayed, one row per tick (theta_c, phi_c, psi_c, h_c): its Filt2 filters
    (their own integration), the XYZ Euler attitude, the thrust law, and the position moved by dt * v."""

    class Filt2:
        def __init__(self, wn, ksi):
            self.wn, self.ksi, self.x, self.xn = wn, ksi, [0.0] * 4, [0.0, 0.0]

        def simulate(self, u, dt):
            x, wn, ksi = self.x, self.wn, self.ksi
            self.xn[0] = x[0] + (x[3] + x[1]) * dt / 2.0
            self.xn[1] = self.xn[1] + (x[2] + wn * wn * (u - x[0]) - 2.0 * ksi * wn * x[1]) * dt / 2.0
            x[2] = wn * wn * (u - x[0]) - 2.0 * ksi * wn * x[1]
            x[3], x[0], x[1] = x[1], self.xn[0], self.xn[1]

    dt = 1.0 / 60
    f_phi, f_theta, f_psi, f_h = Filt2(10.0, 0.7), Filt2(10.0, 0.7), Filt2(10.0, 0.7), Filt2(3.0, 0.5)
    pos, v = np.array([0.0, 0.0, z0]), np.zeros(3)
    out = []
    for theta_c, phi_c, psi_c, h_c in commands:
        f_phi.simulate(phi_c, dt)
        f_theta.simulate(theta_c, dt)
        f_psi.simulate(f_psi.x[0] - psi_c, dt)
        f_h.simulate(h_c, dt)
        (cx, sx), (cy, sy), (cz, sz) = ((math.cos(a), math.sin(a)) for a in (f_phi.x[0], f_theta.x[0], f_psi.x[0]))
        rot = (np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
               @ np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]]))
        acc = rot @ np.array([0.0, 0.0, 10.0 + 9.0 * (h_c - pos[2]) - 2.0 * 0.7 * 3.0 * v[2]])
        v = v + dt * (acc - np.array([0.0, 0.0, 10.0]))
        pos = pos + dt * v
        out.append(pos)
    return np.array(out)


def test_stabilized_quadrotor_is_morse_model_tick_by_tick(tmp_path):
    """Every tick, the robot is where MORSE's own model puts it: climb, pitch, roll and turn commands in turn."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: quad
    type: quad2012
    translate: [0.0, 0.0, 1.0]
    components:
      - {name: pose, type: pose}
      - {name: motion, type: stabilized_quadrotor}
"""
    commands = ([(0.0, 0.0, 0.0, 3.0)] * 40 + [(0.1, 0.0, 0.0, 3.0)] * 40 + [(0.0, -0.1, 0.0, 3.0)] * 40
                + [(0.05, 0.0, 0.1, 2.0)] * 40)
    expected = morse_stabilized_quadrotor(commands, z0=1.0)
    with simulate(text, tmp_path) as h:
        got = []
        for theta_c, phi_c, psi_c, h_c in commands:
            h.command("quad.motion", theta_c=theta_c, phi_c=phi_c, psi_c=psi_c, h_c=h_c)
            h.step()
            got.append([h.data("quad.pose")[k] for k in "xyz"])
    assert np.abs(np.array(got) - expected).max() < 1e-6
    assert np.ptp(expected, axis=0).min() > 0.4  # not a robot at rest: it moved along x, y and z
