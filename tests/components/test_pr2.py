"""BasePR2 (robot pr2) and its parts: pr2_torso, pr2_head, pr2_l_arm, pr2_r_arm, pr2_joint_state and
pr2_posture. A MORSE builder script (BasePR2(), add_interface / add_stream) driven over real sockets as
MORSE's PR2 tests drive it; the PR2's joints, limits and kinematics; the head and arms riding on the torso."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest
from runtime_helpers import Morsec

from morsec.compiler.urdf import expand_xacro
from morsec.component.catalogue import load_catalogue
from morsec.testing import simulate

ROOT = Path(__file__).resolve().parents[2]
ARM = ("shoulder_pan", "shoulder_lift", "upper_arm_roll", "elbow_flex", "forearm_roll", "wrist_flex", "wrist_roll")
ARMATURE_JOINTS = (["torso_lift_joint", "head_pan_joint", "head_tilt_joint"]
                   + [f"{side}_{j}_joint" for side in "lr" for j in ARM])

SCRIPT = """
from morse.builder import *
from morse.builder.robots import BasePR2

pr2 = BasePR2()
pr2.{call}('socket')
env = Environment('empty', fastmode=True)
"""


def pr2_script(tmp_path: Path, call: str = "add_interface") -> Path:
    path = tmp_path / "pr2_scene.py"
    path.write_text(SCRIPT.format(call=call))
    return path


def latest(stream) -> dict:
    stream.drain()
    return stream.json()


def test_builder_pr2_over_sockets(tmp_path):
    """MORSE's BasePR2 with add_interface('socket'): its components by MORSE's names, the joint state of the
    PR2's 45 joints streamed, the torso translated at a speed and set at once (clamped to 0.31 m), the head
    turned by its short joint name, the posture read by short names."""
    with Morsec(pr2_script(tmp_path), tmp_path, prebuild=False, strategy="fixed_step") as sim:
        client = sim.client()
        details = client.ok("simulation", "details")
        components = set(details["robots"][0]["components"])
        assert components == {"pr2.torso", "pr2.torso.pose", "pr2.head", "pr2.head.pose", "pr2.l_arm",
                              "pr2.l_arm.pose", "pr2.r_arm", "pr2.r_arm.pose", "pr2.joint_state", "pr2.posture"}
        with sim.stream("pr2.joint_state") as joints, sim.stream("pr2.posture") as posture:
            state = joints.json()
            assert len(state) == 46 and "timestamp" in state and set(ARMATURE_JOINTS) <= set(state)
            assert state["fl_caster_rotation_joint"] == 0.0 and state["torso_lift_joint"] == pytest.approx(0, abs=1e-3)

            rid = client.send_request("pr2.torso", "translate", "torso_lift_joint", 0.2, 0.1)
            client.ok("time", "sleep", 1.0)
            assert latest(joints)["torso_lift_joint"] == pytest.approx(0.1, abs=0.01)
            assert client.response(rid, timeout=30)[1] == "SUCCESS"
            assert latest(joints)["torso_lift_joint"] == pytest.approx(0.2, abs=0.005)

            client.ok("pr2.torso", "set_translation", "torso_lift_joint", 1.0)
            client.ok("time", "sleep", 0.1)
            assert latest(joints)["torso_lift_joint"] == pytest.approx(0.31, abs=5e-4)

            assert client.call("pr2.head", "rotate", "head_pan", 1.0, 1.0, timeout=30) == ("SUCCESS", None)
            now = latest(posture)
            assert now["head_pan"] == pytest.approx(1.0, abs=0.01)
            assert set(now) == {"timestamp"} | {j.removesuffix("_joint") for j in ARMATURE_JOINTS}
            assert latest(joints)["head_pan_joint"] == pytest.approx(1.0, abs=0.01)

            status, message = client.call("pr2.head", "set_rotation", "no_such_joint", 0.3)
            assert status == "FAILED" and "head_pan_joint" in message


def test_add_stream_on_the_robot_streams_posture_and_serves_the_armatures(tmp_path):
    """`pr2.add_stream('socket')` (MORSE's older PR2 scripts): the same interfaces as add_interface."""
    with Morsec(pr2_script(tmp_path, "add_stream"), tmp_path, prebuild=False, strategy="fixed_step") as sim:
        assert {"pr2.joint_state", "pr2.posture"} <= set(sim.streams)
        client = sim.client()
        assert client.ok("pr2.l_arm", "get_joints") == [f"l_{j}_joint" for j in ARM]


PR2_YAML = """
environment: {name: empty, time: {strategy: fixed_step}}
robots:
  - {name: pr2, type: BasePR2, translate: [1.0, 2.0, 0.0], default_interface: socket}
"""


@pytest.fixture(scope="module")
def pr2(tmp_path_factory):
    with simulate(PR2_YAML, tmp_path_factory.mktemp("pr2")) as sim:
        sim.run_for(0.2)
        yield sim


def anchor(sim, joint: str) -> np.ndarray:
    m = sim.sim.model
    return sim.sim.data.xanchor[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, joint)].copy()


def test_pr2_kinematics_and_limits(pr2):
    """The PR2 URDF's joint places and limits: torso 0.790675 m up and 0.05 m back from the origin, head pan
    0.38145 m above the shoulders, shoulders 0.188 m to each side, 0.1 m to the shoulder lift, 0.4 m to the
    elbow, 0.321 m to the wrist; mirrored limits for the two arms."""
    base = np.array([1.0, 2.0, 0.0])
    assert anchor(pr2, "pr2.torso/torso_lift_joint") == pytest.approx(base + [-0.05, 0, 0.790675], abs=2e-3)
    torso = anchor(pr2, "pr2.torso/torso_lift_joint")
    assert anchor(pr2, "pr2.head/head_pan_joint") - torso == pytest.approx([-0.01707, 0, 0.38145], abs=1e-3)
    assert anchor(pr2, "pr2.head/head_tilt_joint") - anchor(pr2, "pr2.head/head_pan_joint") == \
        pytest.approx([0.068, 0, 0], abs=1e-3)
    for side, y in (("l", 0.188), ("r", -0.188)):
        shoulder = anchor(pr2, f"pr2.{side}_arm/{side}_shoulder_pan_joint")
        assert shoulder - torso == pytest.approx([0, y, 0], abs=1e-3)
        forward = {"shoulder_lift": 0.1, "elbow_flex": 0.5, "wrist_flex": 0.821}
        for joint, x in forward.items():
            assert anchor(pr2, f"pr2.{side}_arm/{side}_{joint}_joint") - shoulder == pytest.approx([x, 0, 0], abs=1e-3)
    assert pr2.call("pr2.torso", "get_IK_limits", "torso_lift_joint") == pytest.approx([0.0, 0.31])
    assert pr2.call("pr2.head", "get_IK_limits", "head_tilt") == pytest.approx([-0.471238, 1.39626])
    assert pr2.call("pr2.l_arm", "get_IK_limits", "l_shoulder_pan_joint") == pytest.approx([-0.714602, 2.285398])
    assert pr2.call("pr2.r_arm", "get_IK_limits", "r_shoulder_pan_joint") == pytest.approx([-2.285398, 0.714602])
    assert pr2.call("pr2.r_arm", "get_IK_limits", "r_upper_arm_roll_joint") == pytest.approx([-3.75, 0.65])
    assert pr2.call("pr2.l_arm", "get_IK_limits", "l_forearm_roll_joint") is None  # continuous


def test_head_and_arms_ride_on_the_torso_lift(pr2):
    head = pr2.body_pose("pr2.head/head_tilt_link")[0]
    wrist = pr2.body_pose("pr2.l_arm/l_wrist_roll_link")[0]
    pr2.call("pr2.torso", "set_translation", "torso_lift", 0.3)
    pr2.run_for(0.2)
    assert pr2.body_pose("pr2.head/head_tilt_link")[0] - head == pytest.approx([0, 0, 0.3], abs=2e-3)
    assert pr2.body_pose("pr2.l_arm/l_wrist_roll_link")[0] - wrist == pytest.approx([0, 0, 0.3], abs=2e-3)
    pr2.call("pr2.torso", "set_translation", "torso_lift_joint", 0.0)
    pr2.run_for(0.2)
    assert pr2.body_pose("pr2.head/head_tilt_link")[0] == pytest.approx(head, abs=2e-3)


def test_arm_holds_a_pose_and_reaches_by_inverse_kinematics(pr2):
    """The arms carry their weight: set straight out, they stay; the wrist goes where IK puts it."""
    pr2.call("pr2.r_arm", "set_rotations", [-0.5, 0.3, 0.0, -1.0, 0.0, -0.5, 0.0])
    pr2.run_for(1.0)
    state = pr2.data("pr2.r_arm.pose")
    assert [state[f"r_{j}_joint"] for j in ARM] == pytest.approx([-0.5, 0.3, 0.0, -1.0, 0.0, -0.5, 0.0], abs=0.01)
    target = pr2.body_pose("pr2.r_arm/r_wrist_roll_link")[0] + [0.05, -0.05, 0.05]
    pr2.call("pr2.r_arm", "place_IK_target", "ik_target.pr2.r_arm.r_wrist_roll_link", list(target), None, False)
    pr2.run_for(0.3)
    assert np.linalg.norm(pr2.body_pose("pr2.r_arm/r_wrist_roll_link")[0] - target) < 0.01


def test_base_stands_on_the_floor(pr2):
    pos, rot = pr2.body_pose("pr2")
    assert pos == pytest.approx([1.0, 2.0, 0.0], abs=2e-3)
    assert rot[2, 2] == pytest.approx(1.0, abs=1e-4)


@pytest.mark.parametrize("xacro", ["robots/pr2/robot.urdf.xacro", "actuators/pr2_torso/pr2_torso.urdf.xacro",
                                   "actuators/pr2_head/pr2_head.urdf.xacro",
                                   "actuators/pr2_l_arm/pr2_l_arm.urdf.xacro",
                                   "actuators/pr2_r_arm/pr2_r_arm.urdf.xacro"])
def test_pr2_xacro_is_valid_urdf(xacro, tmp_path):
    cat = load_catalogue(ROOT)
    urdf = tmp_path / "pr2.urdf"
    urdf.write_text(expand_xacro(cat.roots[0] / xacro, {"name": "pr2"}))
    assert shutil.which("check_urdf"), "check_urdf (liburdfdom-tools) is required: apt-get install liburdfdom-tools"
    result = subprocess.run(["check_urdf", str(urdf)], capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr


def test_joint_state_message_schema_names_the_pr2_joints():
    cat = load_catalogue(ROOT)
    cls = cat.get("sensors", "PR2JointState")
    assert len(cls.defaults) == 45 and len(set(cls.defaults)) == 45
    assert json.dumps(cls.message_schema())  # documented like every component
