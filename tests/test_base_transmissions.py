"""The base servos and dampers the compiler gives a robot (morsec/compiler/mjcf.py): rates about the base's axes act
on its free joint's rotational dofs (a joint transmission, whose cost does not grow with the model), the others
through sites; and the joint transmissions move the robot as the site transmissions they replace did."""

from __future__ import annotations

import re
from pathlib import Path

import mujoco
import numpy as np

from morsec.app.project import build_scene

ATRV = """
environment: {{name: empty, time: {{strategy: fixed_step}}}}
robots:
  - name: robot
    type: atrv
    {extra}
    components:
      - {{name: motion, type: motion_vw}}
"""


def build(tmp_path: Path, extra: str = "") -> Path:
    source = tmp_path / "scene.yaml"
    source.write_text(ATRV.format(extra=extra))
    return build_scene(source, tmp_path / "build") / "scene.xml"


def transmission(model, name: str) -> tuple[str, str]:
    actuator = model.actuator(name)
    kind = mujoco.mjtTrn(int(actuator.trntype[0])).name
    target = mujoco.mjtObj.mjOBJ_JOINT if kind == "mjTRN_JOINT" else mujoco.mjtObj.mjOBJ_SITE
    return kind, mujoco.mj_id2name(model, target, int(actuator.trnid[0]))


def test_rates_about_the_base_axes_act_on_the_free_joint(tmp_path):
    model = mujoco.MjModel.from_xml_path(str(build(tmp_path)))
    assert transmission(model, "robot/wz") == ("mjTRN_JOINT", "robot")
    for axis in ("rx", "ry", "rz"):
        assert transmission(model, f"robot/damping_{axis}") == ("mjTRN_JOINT", "robot")
    assert transmission(model, "robot/vx") == ("mjTRN_SITE", "robot")
    assert transmission(model, "robot/vy") == ("mjTRN_SITE", "robot")
    for axis in ("x", "y", "z"):
        assert transmission(model, f"robot/damping_{axis}") == ("mjTRN_SITE", "robot/centre_of_mass")


def test_a_static_robot_keeps_its_yaw_servo_on_its_site(tmp_path):
    """A static robot has no free joint to act on (its servo moves nothing either way): the model compiles."""
    model = mujoco.MjModel.from_xml_path(str(build(tmp_path, extra="physics_type: static")))
    assert transmission(model, "robot/wz") == ("mjTRN_SITE", "robot")


def test_the_joint_transmissions_drive_as_the_site_ones(tmp_path):
    """The same robot, its rates about its axes given through sites as before: driven forward while turning,
    then pushed into a roll and let go, both go the same way to the rounding."""
    scene_xml = build(tmp_path)
    text = scene_xml.read_text()
    through_sites = re.sub(r'(name="robot/wz") joint="robot"', r'\1 site="robot"', text)
    through_sites = re.sub(r'(name="robot/damping_r[xyz]") joint="robot"', r'\1 site="robot/centre_of_mass"',
                           through_sites)
    assert through_sites.count('joint="robot"') == 0 and text.count('joint="robot"') == 4
    sites_xml = scene_xml.with_name("through_sites.xml")  # beside it: its meshes' paths are relative
    sites_xml.write_text(through_sites)
    states = []
    for path in (scene_xml, sites_xml):
        model = mujoco.MjModel.from_xml_path(str(path))
        data = mujoco.MjData(model)
        base = model.body("robot").id
        data.ctrl[model.actuator("robot/vx").id] = 1.0
        data.ctrl[model.actuator("robot/wz").id] = 0.2
        for step in range(4000):
            data.xfrc_applied[base, 3:] = [30.0, 20.0, 0.0] if 2000 <= step < 2100 else 0.0
            mujoco.mj_step(model, data)
        states.append((data.qpos.copy(), data.qvel.copy()))
    (qpos, qvel), (qpos_sites, qvel_sites) = states
    assert np.linalg.norm(qpos[:2]) > 3.0  # it went somewhere
    assert np.allclose(qpos, qpos_sites, rtol=0.0, atol=1e-9)
    assert np.allclose(qvel, qvel_sites, rtol=0.0, atol=1e-9)
