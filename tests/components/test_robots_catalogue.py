"""The robots segwayrmp400, b21, morsy, hummer, quadrotor, quad2012, submarine and jido: each is in the catalogue under its
MORSE name, floats (NoGravity) or not by default, has the mass its README gives, and moves as the actuator
MORSE pairs it with commands. (The checks run over every robot of the catalogue — README, valid URDF and
check_urdf, standing on the ground at translate z = 0 or floating, and staying there — are in
tests/test_catalogue_components.py; the driving actuators themselves are tested in test_actuators_drive.py.)"""

from __future__ import annotations

import math

import mujoco
import pytest
from runtime_helpers import Morsec, friction_loss

from morsec.testing import simulate

# robot id -> (builder class name, mass in kg, floats by default)
ROBOTS = {
    "segwayrmp400": ("SegwayRMP400", 118.0, False),
    "b21": ("B21", 122.0, False),
    "morsy": ("Morsy", 15.0, False),
    "hummer": ("Hummer", 10.0, False),
    "quadrotor": ("Quadrotor", 1.0, False),
    "submarine": ("Submarine", 470.0, True),
    "quad2012": ("QUAD2012", 1.0, True),
    "jido": ("Jido", 150.0, False),
}
MAX_TILT = math.radians(3.0)


def scene(robot: str, z: float = 0.0, components: str = "", yaw: float = 0.0) -> str:
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: r
    type: {robot}
    translate: [0.0, 0.0, {z}]
    rotate: [0.0, 0.0, {yaw}]
"""
    return text + (f"    components:\n{components}" if components else "")


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_robot_is_in_the_catalogue_under_its_morse_name(robot, tmp_path):
    from morsec.component.catalogue import load_catalogue
    cat = load_catalogue(tmp_path)
    cls = cat.get("robots", ROBOTS[robot][0])
    assert cls.id == robot and cls.builder_name == ROBOTS[robot][0]
    assert cls.Properties().NoGravity is ROBOTS[robot][2]


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_robot_mass_is_the_one_its_readme_gives(robot, build_yaml):
    model = mujoco.MjModel.from_xml_path(str(build_yaml(scene(robot)) / "scene.xml"))
    assert model.body_subtreemass[model.body("r").id] == pytest.approx(ROBOTS[robot][1])


def test_submarine_without_no_gravity_sinks_to_the_ground(build_yaml):
    out = build_yaml(scene("submarine", 1.0).replace("    rotate:", "    properties: {NoGravity: false}\n    rotate:"))
    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=round(2.0 / model.opt.timestep))
    # resting on its hull: the origin one hull radius (0.25 m) above the ground
    assert data.xpos[model.body("r").id][2] == pytest.approx(0.25, abs=0.005)


@pytest.mark.parametrize("robot", ["b21", "morsy"])
def test_round_robots_drive_with_motion_vw(robot, tmp_path):
    with simulate(scene(robot, components="      - {name: motion, type: motion_vw}\n"), tmp_path) as sim:
        sim.command("r.motion", v=0.5, w=0.0)
        sim.run_for(2.0)
        pos, rot = sim.body_pose("r")
        assert pos[0] == pytest.approx(2.0 * (0.5 - friction_loss()), abs=0.02)  # MORSE's ground friction
        assert abs(pos[1]) < 0.02 and rot[2, 2] > math.cos(MAX_TILT)
        yaw0 = sim.yaw("r")
        sim.command("r.motion", v=0.0, w=0.5)
        sim.run_for(1.0)
        assert sim.yaw("r") - yaw0 == pytest.approx(0.5, abs=0.05)


def test_segway_drives_through_its_wheels(tmp_path):
    with simulate(scene("segwayrmp400", components="      - {name: motion, type: motion_vw_diff}\n"),
                  tmp_path) as sim:
        sim.command("r.motion", v=0.5, w=0.0)
        sim.run_for(2.0)
        pos, _ = sim.body_pose("r")
        assert pos[0] == pytest.approx(1.0, abs=0.15) and abs(pos[1]) < 0.05
        # the wheels turn at v / R
        wheel = sim.sim.model.joint("r/wheel_left_joint")
        assert sim.sim.data.qvel[wheel.dofadr[0]] == pytest.approx(0.5 / 0.2667, rel=0.05)


def test_hummer_drives_with_steer_force(tmp_path):
    with simulate(scene("hummer", components="      - {name: sf, type: steer_force}\n"), tmp_path) as sim:
        sim.command("r.sf", force=-20.0)  # MORSE's forces: the Hummer weighs 10 kg
        sim.run_for(2.0)
        pos, _ = sim.body_pose("r")
        assert pos[0] > 2.0 and abs(pos[1]) < 0.05


def test_quadrotor_flies_with_its_rotors(tmp_path):
    comps = "      - {name: engines, type: quadrotor_dynamic_control}\n"
    with simulate(scene("quadrotor", components=comps), tmp_path) as sim:
        hover = math.sqrt(1.0 * 9.81 / (4 * 9.169e-6))
        sim.command("r.engines", engines=[1.1 * hover] * 4)
        sim.run_for(1.0)
        pos, rot = sim.body_pose("r")
        assert pos[2] > 0.11 + 0.5 and rot[2, 2] > math.cos(MAX_TILT)


def test_submarine_moves_with_force_torque(tmp_path):
    comps = "      - {name: thrust, type: force_torque, properties: {RobotFrame: true}}\n"
    with simulate(scene("submarine", 2.0, components=comps), tmp_path) as sim:
        sim.command("r.thrust", force=[470.0, 0.0, 0.0])
        sim.run_for(1.0)
        pos, _ = sim.body_pose("r")
        assert pos == pytest.approx([0.5, 0.0, 2.0], abs=0.01)  # it floats where it was put, as MORSE's


def test_quad2012_flies_with_stabilized_quadrotor(tmp_path):
    """MORSE's QUAD2012 + StabilizedQuadrotor: from the ground to h_c = 10 m in 3 s, then theta_c = 0.1
    accelerates it along x (MORSE's linear model: 0.39 m in the first second) with no roll at all."""
    comps = ("      - {name: pose, type: pose}\n"
             "      - {name: motion, type: stabilized_quadrotor}\n")
    with simulate(scene("QUAD2012", components=comps), tmp_path) as sim:
        assert sim.body_pose("r")[0][2] == pytest.approx(0.0, abs=1e-6)  # floating where it is put
        sim.command("r.motion", theta_c=0.0, phi_c=0.0, psi_c=0.0, h_c=10.0)
        sim.run_for(3.0)
        assert sim.body_pose("r")[0] == pytest.approx([0.0, 0.0, 10.0], abs=0.05)
        sim.command("r.motion", theta_c=0.1, phi_c=0.0, psi_c=0.0, h_c=10.0)
        sim.run_for(1.0)
        pose = sim.data("r.pose")
        assert pose["x"] == pytest.approx(0.39, abs=0.02) and pose["y"] == pytest.approx(0.0, abs=1e-6)
        assert pose["roll"] == 0.0 and pose["pitch"] == pytest.approx(0.1, abs=0.02)


def test_jido_is_listed_by_list_robots(tmp_path):
    """MORSE's base_testing: Jido() and ATRVs named four ways, listed over the socket."""
    script = tmp_path / "robots.py"
    script.write_text("from morse.builder import *\n\njido = Jido()\nrobot2 = ATRV('mana')\n"
                      "env = Environment('empty', fastmode=True)\n")
    with Morsec(script, tmp_path, prebuild=False, strategy="fixed_step") as sim:
        status, robots = sim.client().call("simulation", "list_robots")
        assert status == "SUCCESS" and sorted(robots) == ["jido", "mana"]
