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
    """MORSE's kuka_lwr model: bones 0.3105, 0.20, 0.20, 0.20, 0.19, 0.08, 0.13 m (base/armature_pose_testing.py
    reads them with get_joints_length), so the LWR 4+'s 0.40 m shoulder (A2) to elbow (A4) and 0.39 m elbow to
    wrist (A6), and the tip 1.3105 m above the base; A1, A3, A5, A7 along the arm, A2, A4, A6 across, a
    negative A2 bending the arm towards +x (base/armature_testing.py)."""
    assert kuka.call("robot.arm", "get_joints") == KUKA
    assert kuka.call("robot.arm.pose", "get_joints") == KUKA
    d, m = kuka.sim.data, kuka.sim.model
    anchor = {j: d.xanchor[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"robot.arm/{j}")] for j in KUKA}
    assert anchor["kuka_2"][2] == pytest.approx(0.3105)
    assert anchor["kuka_4"][2] - anchor["kuka_2"][2] == pytest.approx(0.40)
    assert anchor["kuka_6"][2] - anchor["kuka_4"][2] == pytest.approx(0.39)
    assert kuka.body_pose("robot.arm/kuka_7_tip")[0][2] == pytest.approx(1.3105)
    dofs = kuka.call("robot.arm", "get_dofs")
    assert [dofs[j] for j in KUKA] == [[False, False, True], [False, True, False]] * 3 + [[False, False, True]]
    assert kuka.call("robot.arm", "get_IK_limits", "kuka_2") == pytest.approx([-2.0944, 2.0944], abs=1e-4)
    lengths = kuka.call("robot.arm.pose", "get_joints_length")
    assert [lengths[j] for j in KUKA] == pytest.approx([0.3105, 0.2, 0.2, 0.2, 0.19, 0.08, 0.13])
    # arm straight up, then A2 at -90 degrees: the rest of the arm (1.0 m) lies along +x
    kuka.call("robot.arm", "set_rotation", "kuka_2", -math.pi / 2)
    np.testing.assert_allclose(kuka.body_pose("robot.arm/kuka_7_tip")[0], [1.0, 0.0, 0.3105], atol=1e-9)


def test_children_are_placed_in_the_arm_frame_and_ride_on_its_end(tmp_path):
    """MORSE places what is appended to an armature in the arm's frame and carries it on the arm's end: a
    pose sensor at z 1.3105 (the tip, arm straight up) is at x 1.0, z 0.3105, pitched 90 degrees once A2 is
    at -90 degrees (base/armature_testing.py, test_object_attach)."""
    arm = """
robots:
  - name: robot
    type: fake_robot
    components:
      - name: arm
        type: kuka_lwr
        components:
          - {name: tip_pose, type: pose, translate: [0.0, 0.0, 1.3105]}
"""
    with simulate(arm, tmp_path) as sim:
        sim.run_for(0.1)
        tip = sim.data("robot.arm.tip_pose")
        assert [tip["x"], tip["y"], tip["z"], tip["pitch"]] == pytest.approx([0.0, 0.0, 1.3105, 0.0], abs=1e-3)
        sim.call("robot.arm", "set_rotation", "kuka_2", -math.pi / 2)
        sim.run_for(0.1)
        tip = sim.data("robot.arm.tip_pose")
        assert [tip["x"], tip["y"], tip["z"], tip["pitch"]] == pytest.approx([1.0, 0.0, 0.3105, math.pi / 2],
                                                                              abs=2e-3)


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
    rid = client.send("robot.arm", "rotate", "kuka_1", 0.8, speed) if speed else \
        client.send("robot.arm", "rotate", "kuka_1", 0.8)
    kuka.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
    start = kuka.time
    kuka.run_for(0.5)
    expected_speed = speed or 0.8  # RotationSpeed
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_1") == pytest.approx(0.5 * expected_speed, abs=0.01)
    status, _, at = client.wait(rid)
    assert status == "SUCCESS"
    assert at - start == pytest.approx(0.8 / expected_speed, abs=0.08)
    assert kuka.call("robot.arm.pose", "get_joint", "kuka_1") == pytest.approx(0.8, abs=0.01)


def test_joint_moves_at_exactly_its_speed(kuka):
    """MORSE steps a joint by speed / frequency each tick: after 1 s at 0.5 rad/s it is at 0.5 rad
    (base/armature_testing.py allows 0.02 after a client's sleep(1)). The servos aim at the middle of each
    tick's step: the joint is neither ahead (the setpoint held for a tick while the velocity feed-forward
    pushes on) nor behind."""
    client = kuka.client()
    client.send("robot.arm", "rotate", "kuka_2", 1.0, 0.5)
    kuka.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
    for t in (0.5, 1.0, 1.5):
        kuka.run_for(0.5)
        assert kuka.call("robot.arm.pose", "get_joint", "kuka_2") == pytest.approx(0.5 * t, abs=0.002)


def test_trajectory_timing(kuka):
    client = kuka.client()
    points = [{"positions": [0.4, 0.6, 0.0, -0.6], "time_from_start": 1.0},
              {"positions": [0.0, 0.3, 0.2, -1.0, 0.1, 0.2, 0.3], "time_from_start": 2.0}]
    rid = client.send("robot.arm", "trajectory", {"points": points})
    kuka.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
    start = kuka.time
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka)[:4], [0.2, 0.3, 0.0, -0.3], atol=0.02)  # half way to the first
    kuka.run_for(0.5)
    np.testing.assert_allclose(state(kuka)[:4], [0.4, 0.6, 0.0, -0.6], atol=0.02)  # there at 1 s
    status, _, at = client.wait(rid)
    assert status == "SUCCESS" and at - start == pytest.approx(2.0, abs=0.1)
    assert np.all(np.abs(state(kuka) - points[1]["positions"]) < 0.01)
    bad = client.send("robot.arm", "trajectory", {"points": [{"positions": [0.1]}]})
    kuka.step()
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
DOWN = [-math.pi / 2, 0.0, 0.0]  # MORSE's IK target frame (Blender's bone: y along the arm) pointing down


def tip(sim):
    return sim.body_pose("robot.arm/kuka_7_tip")


def test_place_and_move_ik_target(kuka):
    tol = 0.005  # DistanceTolerance
    assert kuka.call("robot.arm", "list_IK_targets") == [IK_TARGET]
    goal = np.array([0.5, 0.2, 0.6])
    kuka.call("robot.arm", "place_IK_target", IK_TARGET, list(goal), DOWN, False)
    kuka.run_for(0.5)
    pos, rot = tip(kuka)
    assert np.linalg.norm(pos - goal) < tol
    assert rot[:, 1] @ [0, 0, -1] > math.cos(0.01)  # the arm's end points down

    client = kuka.client()
    start = kuka.time
    status, _, at = client.wait(client.send("robot.arm", "move_IK_target", "kuka_7", [0.0, -0.4, -0.2]))
    assert status == "SUCCESS"
    # MORSE moves the target along each axis at IKLinearSpeed (0.5 m/s): 0.8 s for the 0.4 m of y
    assert at - start == pytest.approx(0.4 / 0.5, abs=0.2)
    pos, rot = tip(kuka)
    assert np.linalg.norm(pos - (goal + [0.0, -0.4, -0.2])) < tol
    assert rot[:, 1] @ [0, 0, -1] > math.cos(0.01)  # no rotation asked: it kept pointing down

    with pytest.raises(ValueError, match="IK target <kuka_8> does not exist for armature robot.arm .*kuka_7"):
        kuka.call("robot.arm", "place_IK_target", "kuka_8", [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="does not exist"):
        kuka.call("robot.arm", "place_IK_target", "ik_target.robot.other.kuka_7", [0.0, 0.0, 0.0])


def test_ik_target_out_of_reach_leaves_the_arm_at_morse_compromise(kuka):
    """MORSE's IK goes as near as it can and the services succeed; the target itself is where it was put,
    and relative moves are relative to it (base/armature_testing.py: test_ik_immediate, test_ik_motion)."""
    def tip_pose():
        pos, rot = tip(kuka)
        return [*pos, math.atan2(rot[0, 1], rot[2, 1])]  # the arm's pitch from vertical, towards +x

    kuka.call("robot.arm", "place_IK_target", IK_TARGET, [0, 0, 2], None, False)  # above: straight up
    kuka.run_for(0.5)
    assert tip_pose() == pytest.approx([0.0, 0.0, 1.3105, 0.0], abs=1e-3)
    # 1 m away at shoulder height, kept pointing up: the least-squares compromise, MORSE's numbers
    kuka.call("robot.arm", "place_IK_target", IK_TARGET, [1, 0, 0.3105], None, False)
    kuka.run_for(0.5)
    assert tip_pose()[:3] == pytest.approx([0.778, 0.0, 0.363], abs=0.008)
    assert tip_pose()[3] == pytest.approx(0.02, abs=0.003)  # tilted towards the target, as MORSE's
    # the same place, the arm horizontal: exactly reachable, the arm stretched along +x
    kuka.call("robot.arm", "place_IK_target", IK_TARGET, [1, 0, 0.3105], [math.pi / 2, -math.pi / 2, -math.pi],
              False)
    kuka.run_for(0.5)
    assert tip_pose() == pytest.approx([1.0, 0.0, 0.3105, math.pi / 2], abs=2e-3)
    client = kuka.client()
    status, _, _ = client.wait(client.send("robot.arm", "move_IK_target", IK_TARGET, [0, 0, 2],
                                           [math.pi / 2, 0.0, -math.pi], False))
    assert status == "SUCCESS"  # out of reach, still a success, as MORSE's
    assert tip_pose() == pytest.approx([0.0, 0.0, 1.3105, 0.0], abs=5e-3)
    # relative to the target (at z 2), not to the arm's tip (at z 1.31)
    status, _, _ = client.wait(client.send("robot.arm", "move_IK_target", IK_TARGET, [-1, 0, -1.6895]))
    assert status == "SUCCESS"
    assert tip_pose() == pytest.approx([-0.778, 0.0, 0.363, -0.02], abs=0.008)
    status, _, _ = client.wait(client.send("robot.arm", "move_IK_target", IK_TARGET, [0, 0, 0],
                                           [0, -math.pi / 2, 0]))  # a relative rotation, world frame
    assert status == "SUCCESS"
    assert tip_pose() == pytest.approx([-1.0, 0.0, 0.3105, -math.pi / 2], abs=5e-3)


def test_ik_targets_have_morse_names(kuka):
    """MORSE names an IK target `ik_target.<armature>.<bone>` (base/armature_testing.py); its bone's name
    alone (`kuka_7`) is accepted too."""
    assert kuka.call("robot.arm", "list_IK_targets") == ["ik_target.robot.arm.kuka_7"]
    for name in ("ik_target.robot.arm.kuka_7", "kuka_7"):
        kuka.call("robot.arm", "place_IK_target", name, [0.5, 0.0, 0.6], DOWN, False)
        kuka.run_for(0.3)
        assert np.linalg.norm(tip(kuka)[0] - [0.5, 0.0, 0.6]) < 0.005


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
        rest = sim.body_pose("robot.arm/extension")[0]
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
        # IK on a 4-joint arm: the position only; relative to the target, which is where the arm's end was
        # at rest (the joint commands above did not move it), as MORSE's
        sim.call("robot.arm", "place_IK_target", "extension", [0.1, -0.05, -0.2])
        sim.run_for(0.3)
        assert np.linalg.norm(sim.body_pose("robot.arm/extension")[0] - (rest + [0.1, -0.05, -0.2])) < 0.005


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
    """The example scene: the gripper at the KUKA's tip, placed above the box by IK, grabs it, carries it
    0.3 m to the side and lets it go on the table."""
    with simulate((ROOT / "scenes" / "arm_pick.yaml").read_text(), tmp_path) as sim:
        client = sim.client()
        sim.run_for(0.2)
        sim.call("robot.arm", "place_IK_target", "kuka_7", [0.9, 0.0, 0.65], DOWN, False)
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
