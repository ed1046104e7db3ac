"""armature, kuka_lwr and armature_pose: joints reached within tolerance, at the right speed, on time along
trajectories, streamed joint targets, inverse kinematics with MuJoCo's Jacobians, and the arm_pick scene."""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest

from morsec.compiler.urdf import expand_xacro
from morsec.component.catalogue import load_catalogue
from morsec.testing import simulate

ROOT = Path(__file__).resolve().parents[2]
KUKA = [f"kuka_{i}" for i in range(1, 8)]


def scene(arm: str = "kuka_lwr", extra: str = "") -> str:
    return f"""
robots:
  - name: robot
    type: fake_robot
    components:
      - name: arm
        type: {arm}
        services: [socket]
        components:
          - {{name: pose, type: armature_pose}}
{extra}"""


@pytest.fixture
def kuka(tmp_path):
    with simulate(scene(), tmp_path) as sim:
        yield sim


def state(sim) -> np.ndarray:
    joints = sim.call("robot.arm.pose", "get_state")
    return np.array([joints[j] for j in KUKA])


def test_kuka_lwr_kinematics(kuka):
    """LWR 4+: 0.31 m base to shoulder (A2), 0.40 to the elbow (A4), 0.39 to the wrist (A6), 0.078 to the
    flange (kuka_7); A1, A3, A5, A7 along the arm, A2, A4, A6 across."""
    assert kuka.call("robot.arm", "get_joints") == KUKA
    assert kuka.call("robot.arm.pose", "get_joints") == KUKA
    d, m = kuka.sim.data, kuka.sim.model
    anchor = {j: d.xanchor[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"robot.arm/{j}")] for j in KUKA}
    assert anchor["kuka_2"][2] == pytest.approx(0.31)
    assert anchor["kuka_4"][2] - anchor["kuka_2"][2] == pytest.approx(0.40)
    assert anchor["kuka_6"][2] - anchor["kuka_4"][2] == pytest.approx(0.39)
    assert kuka.body_pose("robot.arm/kuka_7")[0][2] - anchor["kuka_6"][2] == pytest.approx(0.078)
    dofs = kuka.call("robot.arm", "get_dofs")
    assert [dofs[j] for j in KUKA] == [[False, False, True], [False, True, False]] * 3 + [[False, False, True]]
    assert kuka.call("robot.arm", "get_IK_limits", "kuka_2") == pytest.approx([-2.0944, 2.0944], abs=1e-4)
    lengths = kuka.call("robot.arm.pose", "get_joints_length")
    assert [lengths[j] for j in KUKA] == pytest.approx([0.2, 0.2, 0.2, 0.2, 0.19, 0.078, 0.0])
    # arm straight up, then A2 at 90 degrees: the rest of the arm (0.868 m) lies along +x
    kuka.call("robot.arm", "set_rotation", "kuka_2", math.pi / 2)
    np.testing.assert_allclose(kuka.body_pose("robot.arm/kuka_7")[0], [0.868, 0.0, 0.31], atol=1e-9)


def test_set_rotations_reaches_the_angles(kuka):
    target = np.array([0.3, 0.5, -0.2, -1.0, 0.4, 0.6, -0.5])
    kuka.call("robot.arm", "set_rotations", list(target))
    np.testing.assert_allclose(state(kuka), target, atol=1e-9)  # at once
    kuka.run_for(0.5)
    assert np.all(np.abs(state(kuka) - target) < 0.01)  # and held there (AngleTolerance), against gravity
    assert kuka.data("robot.arm") == pytest.approx(dict(zip(KUKA, target)))
    kuka.call("robot.arm", "set_rotation", "kuka_2", 5.0)  # clamped to the joint's limit
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_2") == pytest.approx(math.radians(120))


@pytest.mark.parametrize("speed", [None, 0.4])
def test_rotate_at_the_given_speed(kuka, speed):
    client = kuka.client()
    start = kuka.time
    rid = client.send("robot.arm", "rotate", "kuka_1", 0.8, speed) if speed else \
        client.send("robot.arm", "rotate", "kuka_1", 0.8)
    kuka.run_for(0.5)
    expected_speed = speed or 0.8  # RotationSpeed
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_1") == pytest.approx(0.5 * expected_speed, abs=0.01)
    status, _, at = client.wait(rid)
    assert status == "SUCCESS"
    assert at - start == pytest.approx(0.8 / expected_speed, abs=0.08)
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_1") == pytest.approx(0.8, abs=0.01)


def test_trajectory_timing(kuka):
    client = kuka.client()
    start = kuka.time
    points = [{"positions": [0.4, 0.6, 0.0, -0.6], "time_from_start": 1.0},
              {"positions": [0.0, 0.3, 0.2, -1.0, 0.1, 0.2, 0.3], "time_from_start": 2.0}]
    rid = client.send("robot.arm", "trajectory", {"points": points})
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka)[:4], [0.2, 0.3, 0.0, -0.3], atol=0.02)  # half way to the first
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka)[:4], [0.4, 0.6, 0.0, -0.6], atol=0.02)  # there at 1 s
    status, _, at = client.wait(rid)
    assert status == "SUCCESS" and at - start == pytest.approx(2.0, abs=0.1)
    assert np.all(np.abs(state(kuka) - points[1]["positions"]) < 0.01)
    bad = client.send("robot.arm", "trajectory", {"points": [{"positions": [0.1]}]})
    assert client.replies[bad][0] == "FAILED" and "time_from_start" in client.replies[bad][1]


def test_trajectory_waits_for_its_start_time(kuka):
    client = kuka.client()
    now = kuka.sim.clock.now()
    rid = client.send("robot.arm", "trajectory", {"starttime": now + 1.0,
                                                  "points": [{"positions": [0.5], "time_from_start": 0.5}]})
    kuka.run_for(0.9)
    assert abs(state(kuka)[0]) < 0.01
    status, _, at = client.wait(rid)
    assert status == "SUCCESS" and at == pytest.approx(1.5, abs=0.1)


def test_streamed_joint_targets_move_the_arm(kuka):
    kuka.command("robot.arm", kuka_2=0.4, kuka_4=-0.4)  # joints left out keep their targets
    kuka.run_for(0.25)
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_2") == pytest.approx(0.2, abs=0.01)  # at 0.8 rad/s
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka), [0, 0.4, 0, -0.4, 0, 0, 0], atol=0.01)
    pose = kuka.data("robot.arm.pose")
    assert list(pose) == ["timestamp"] + KUKA and pose["kuka_2"] == pytest.approx(0.4, abs=0.01)
    kuka.command("robot.arm", kuka_1=0.3, not_a_joint=1.0)
    kuka.run_for(0.6)
    np.testing.assert_allclose(state(kuka), [0.3, 0.4, 0, -0.4, 0, 0, 0], atol=0.01)


IK_TARGET = "ik_target.robot.arm.kuka_7"


def test_place_and_move_ik_target(kuka):
    tol = 0.005  # DistanceTolerance
    assert kuka.call("robot.arm", "list_IK_targets") == [IK_TARGET]
    goal = np.array([0.5, 0.2, 0.6])
    kuka.call("robot.arm", "place_IK_target", IK_TARGET, list(goal), [0.0, math.pi, 0.0], False)  # pointing down
    kuka.run_for(0.5)
    pos, rot = kuka.body_pose("robot.arm/kuka_7")
    assert np.linalg.norm(pos - goal) < tol
    assert rot[:, 2] @ [0, 0, -1] > math.cos(0.01)

    client = kuka.client()
    start = kuka.time
    status, _, at = client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [0.0, -0.4, -0.2]))
    assert status == "SUCCESS"
    assert at - start == pytest.approx(math.hypot(0.4, 0.2) / 0.5, abs=0.2)  # IKLinearSpeed
    pos, rot = kuka.body_pose("robot.arm/kuka_7")
    assert np.linalg.norm(pos - (goal + [0.0, -0.4, -0.2])) < tol
    assert rot[:, 2] @ [0, 0, -1] > math.cos(0.01)  # no rotation asked: it kept pointing down

    status, message, _ = client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [3.0, 0.0, 0.0]))
    assert status == "FAILED" and "out of reach" in message
    with pytest.raises(ValueError, match="out of reach"):
        kuka.call("robot.arm", "place_IK_target", "kuka_7", [0.0, 0.0, 3.0], None, False)
    with pytest.raises(ValueError, match="IK target <kuka_8> does not exist for armature robot.arm .*kuka_7"):
        kuka.call("robot.arm", "place_IK_target", "kuka_8", [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="does not exist"):
        kuka.call("robot.arm", "place_IK_target", "ik_target.robot.other.kuka_7", [0.0, 0.0, 0.0])


def test_ik_targets_have_morse_names(kuka):
    """MORSE names an IK target `ik_target.<armature>.<bone>` (base/armature_testing.py); its link's name
    alone (`kuka_7`) is accepted too."""
    assert kuka.call("robot.arm", "list_IK_targets") == ["ik_target.robot.arm.kuka_7"]
    for name in ("ik_target.robot.arm.kuka_7", "kuka_7"):
        kuka.call("robot.arm", "place_IK_target", name, [0.5, 0.0, 0.6], [0.0, math.pi, 0.0], False)
        kuka.run_for(0.3)
        pos, _ = kuka.body_pose("robot.arm/kuka_7")
        assert np.linalg.norm(pos - [0.5, 0.0, 0.6]) < 0.005


def test_cancel_stops_the_arm_where_it_is(kuka):
    client = kuka.client()
    rid = client.send("robot.arm", "rotate", "kuka_1", 2.0)
    kuka.run_for(0.5)
    client.cancel(rid)
    assert client.replies[rid][0] == "PREEMPTED"
    stopped = state(kuka)
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka), stopped, atol=0.02)


def test_generic_armature_revolute_and_prismatic_joints(tmp_path):
    with simulate(scene("armature"), tmp_path) as sim:
        assert sim.call("robot.arm", "get_joints") == ["shoulder_yaw", "shoulder_pitch", "elbow", "extension"]
        assert sim.call("robot.arm", "get_IK_limits", "extension") == pytest.approx([0.0, 0.2])
        client = sim.client()
        start = sim.time
        status, _, at = client.wait(client.send("robot.arm", "translate", "extension", 0.1))
        # at LinearSpeed, done once within DistanceTolerance (0.005 m) of the target
        assert status == "SUCCESS" and at - start == pytest.approx((0.1 - 0.005) / 0.05, abs=0.1)
        assert sim.call("robot.arm.pose", "get_joint", "extension") == pytest.approx(0.1, abs=0.005)
        sim.call("robot.arm", "set_translation", "extension", 0.5)  # clamped to the slider's length
        assert sim.call("robot.arm.pose", "get_joint", "extension") == pytest.approx(0.2)
        with pytest.raises(ValueError, match="not a revolute joint"):
            sim.call("robot.arm", "set_rotations", [0.1, 0.2, 0.3, 0.4])
        with pytest.raises(ValueError, match="not a prismatic joint"):
            sim.call("robot.arm", "translate", "elbow", 0.1)
        with pytest.raises(ValueError, match="does not exist"):
            sim.call("robot.arm", "rotate", "wrist", 0.1)
        sim.call("robot.arm", "set_rotations", [0.5, 0.3, 0.6])
        sim.run_for(0.3)
        np.testing.assert_allclose(list(sim.call("robot.arm.pose", "get_state").values()), [0.5, 0.3, 0.6, 0.2],
                                   atol=0.005)
        # IK on a 4-joint arm: the position only
        tip = sim.body_pose("robot.arm/extension")[0]
        sim.call("robot.arm", "place_IK_target", "extension", [0.05, -0.05, -0.1])
        sim.run_for(0.3)
        assert np.linalg.norm(sim.body_pose("robot.arm/extension")[0] - (tip + [0.05, -0.05, -0.1])) < 0.005


@pytest.mark.parametrize("xacro", ["actuators/armature/armature.urdf.xacro", "actuators/kuka_lwr/kuka_lwr.urdf.xacro"])
def test_arm_xacro_is_valid_urdf(xacro, tmp_path):
    cat = load_catalogue(ROOT)
    path = cat.roots[0] / xacro
    urdf = tmp_path / "arm.urdf"
    urdf.write_text(expand_xacro(path, {}))
    assert shutil.which("check_urdf"), "check_urdf (liburdfdom-tools) is required: apt-get install liburdfdom-tools"
    result = subprocess.run(["check_urdf", str(urdf)], capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr


def test_arm_pick_scene_picks_the_box_and_puts_it_down(tmp_path):
    """The example scene: the gripper on the KUKA's flange, placed above the box by IK, grabs it, carries
    it 0.3 m to the side and lets it go on the table."""
    with simulate((ROOT / "scenes" / "arm_pick.yaml").read_text(), tmp_path) as sim:
        client = sim.client()
        sim.run_for(0.2)
        sim.call("robot.arm", "place_IK_target", "kuka_7", [0.9, 0.0, 0.65], [0.0, math.pi, 0.0], False)
        assert client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [0.0, 0.0, -0.15]))[0] == "SUCCESS"
        assert sim.call("robot.arm.gripper", "grab") == "box"
        assert client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [0.0, 0.3, 0.15]))[0] == "SUCCESS"
        sim.run_for(0.3)
        assert sim.body_pose("box")[0][2] > 0.55  # lifted
        assert client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [0.0, 0.0, -0.14]))[0] == "SUCCESS"
        assert sim.call("robot.arm.gripper", "release") is True
        sim.run_for(1.0)
        np.testing.assert_allclose(sim.body_pose("box")[0], [0.9, 0.3, 0.43], atol=0.01)  # on the table
        assert abs(sim.data("robot.pose")["x"]) < 0.01  # the rover stood still
