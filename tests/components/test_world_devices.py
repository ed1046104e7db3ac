"""The human avatar, PatrolBot, PA10, Joystick, Sound, MocapControl and DepthCameraAggregator: each does what its
page says, measured in a running simulation; their builder classes take MORSE's arguments."""

from __future__ import annotations

import logging
import math
import os
import struct
import textwrap

import numpy as np
import pytest

from morsec.component.catalogue import load_catalogue
from morsec.frontends import load_scene
from morsec.scene.walk import walk_components
from morsec.testing import simulate


def robot_scene(robot: str, components: str, extra: str = "", translate: str = "[0.0, 0.0, 0.0]") -> str:
    return textwrap.dedent(f"""
        environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
        robots:
          - name: r
            type: {robot}
            translate: {translate}
            components:
        """) + textwrap.indent(textwrap.dedent(components).strip("\n"), "      ") + "\n" + textwrap.dedent(extra)


# ---------------------------------------------------------------- human

def test_human_walks_to_a_waypoint_swinging_its_legs_and_stands_still_after(tmp_path):
    text = robot_scene("human", """
        - {name: pose, type: pose}
        - {name: motion, type: waypoint, properties: {ControlType: Position}}
        """)
    with simulate(text, tmp_path) as sim:
        joints = lambda: sim.component("r.skeleton.joint_states").local_data  # noqa: E731
        sim.run_for(0.5)
        assert joints()["upperleg01_L"] == pytest.approx(0.0, abs=1e-3)
        sim.command("r.motion", x=3.0, y=0.0, z=0.0, tolerance=0.3, speed=1.0)
        swing = []
        for _ in range(20):
            sim.run_for(0.1)
            swing.append(joints()["upperleg01_L"])
        assert max(swing) - min(swing) > 0.3  # the legs swing while it walks (0.35 rad each way)
        sim.run_for(3.0)
        pose = sim.data("r.pose")
        assert pose["x"] == pytest.approx(2.7, abs=0.15) and abs(pose["y"]) < 0.05
        assert abs(pose["pitch"]) < 0.02 and abs(pose["roll"]) < 0.02  # it stays upright
        assert joints()["upperleg01_L"] == pytest.approx(0.0, abs=2e-3)  # back at rest when it stops


def test_human_ik_targets_put_the_hand_where_asked_and_joint_states_read_bones(tmp_path):
    text = robot_scene("human", "", translate="[1.0, 2.0, 0.0]").replace("    components:\n", "")
    with simulate(text, tmp_path) as sim:
        targets = sim.call("r.skeleton", "list_IK_targets")
        assert sorted(targets) == sorted(f"ik_target.r.skeleton.{b}" for b in
                                         ("head", "wrist_L", "wrist_R", "foot_L", "foot_R"))
        state = sim.call("r.skeleton.joint_states", "get_state")
        assert {"neck03", "upperarm02_L", "lowerleg01_R", "spine05", "head"} <= set(state)
        assert not any(":" in name for name in state)  # a bone's further axes are not channels
        # the targets ride with the human: its rest pose reads the test's rest targets, shifted by (1, 2)
        head, _ = sim.body_pose("r.skeleton/head_tail")
        assert head == pytest.approx([1.04, 2.0, 1.58], abs=2e-3)
        sim.call("r.skeleton", "place_IK_target", "ik_target.r.skeleton.wrist_L", [1.44, 2.31, 1.1],
                 [-3.0, 1.6, 1.5], False)
        sim.run_for(0.5)
        wrist, _ = sim.body_pose("r.skeleton/wrist_L_tail")
        assert wrist == pytest.approx([1.44, 2.31, 1.1], abs=0.01)
        feet, _ = sim.body_pose("r.skeleton/foot_L_tail")
        assert feet == pytest.approx([1.02, 2.10, 0.07], abs=0.01)  # the other targets hold
        assert sim.call("r.skeleton.joint_states", "get_joint", "upperarm02_L") == pytest.approx(0.33, abs=0.05)


def test_mocap_control_puts_streamed_angles_on_the_human(tmp_path):
    text = robot_scene("human", "- {name: mocap, type: mocap_control}")
    with simulate(text, tmp_path) as sim:
        sim.command("r.mocap", neck03=0.3, upperarm01_L=-0.5, nosuchbone=1.0)
        sim.run_for(0.3)
        state = sim.call("r.skeleton.joint_states", "get_state")
        assert state["neck03"] == pytest.approx(0.3, abs=1e-3)
        assert state["upperarm01_L"] == pytest.approx(-0.5, abs=1e-3)
        assert state["upperarm01_R"] == pytest.approx(0.0, abs=1e-3)


# ---------------------------------------------------------------- patrolbot, pa10

def test_patrolbot_drives_and_turns_through_its_wheels(tmp_path):
    text = robot_scene("patrolbot", """
        - {name: pose, type: pose}
        - {name: motion, type: motion_vw_diff}
        """)
    with simulate(text, tmp_path) as sim:
        sim.run_for(0.5)
        assert sim.data("r.pose")["z"] == pytest.approx(0.10, abs=0.005)  # its origin 0.10 m up
        sim.command("r.motion", v=0.5, w=0.0)
        sim.run_for(1.0)
        x0 = sim.data("r.pose")["x"]
        sim.run_for(2.0)
        assert (sim.data("r.pose")["x"] - x0) / 2.0 == pytest.approx(0.5, rel=0.03)
        sim.command("r.motion", v=0.0, w=0.5)
        sim.run_for(1.0)
        yaw0 = sim.data("r.pose")["yaw"]
        sim.run_for(2.0)
        assert (sim.data("r.pose")["yaw"] - yaw0) / 2.0 == pytest.approx(0.5, rel=0.03)
        pose = sim.data("r.pose")
        assert abs(pose["pitch"]) < 0.01 and abs(pose["roll"]) < 0.01


def test_pa10_turns_its_six_joints_at_its_speed(tmp_path):
    text = robot_scene("fake_robot", """
        - name: arm
          type: pa10
          components:
            - {name: joints, type: armature_pose}
        """)
    with simulate(text, tmp_path) as sim:
        assert sim.call("r.arm", "get_joints") == [f"seg{i}" for i in range(6)]
        assert sim.body_pose("r.arm/pa10_tip")[0][2] == pytest.approx(1.317)
        sim.call("r.arm", "set_rotation_array", 0.5, -0.5, 1.0, 0.0, 0.3, -0.2)
        sim.run_for(0.5)
        half = sim.call("r.arm.joints", "get_state")
        assert half["seg2"] == pytest.approx(0.5, abs=0.03)  # 1 rad/s (Speed)
        assert half["seg0"] == pytest.approx(0.5, abs=0.01)  # already there
        sim.run_for(1.0)
        state = sim.call("r.arm.joints", "get_state")
        assert [state[f"seg{i}"] for i in range(6)] == pytest.approx([0.5, -0.5, 1.0, 0.0, 0.3, -0.2], abs=1e-3)
        sim.command("r.arm", seg1=-3.0)  # beyond the shoulder's 94 degrees: stops at its limit
        sim.run_for(3.0)
        assert sim.call("r.arm.joints", "get_joint", "seg1") == pytest.approx(-math.radians(94), abs=1e-3)


# ---------------------------------------------------------------- joystick, sound

def test_joystick_device_events_drive_the_robot(tmp_path):
    fifo = tmp_path / "js0"
    os.mkfifo(fifo)
    keep = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # so that the writer's open does not wait
    writer = os.open(fifo, os.O_WRONLY)
    text = robot_scene("atrv", f"""
        - {{name: pose, type: pose}}
        - {{name: stick, type: joystick, properties: {{device: "{fifo}", Speed: 2.0}}}}
        """)
    try:
        with simulate(text, tmp_path) as sim:
            os.close(keep)
            # the kernel's initial state (JS_EVENT_INIT | AXIS), then the stick pushed fully forward
            os.write(writer, struct.pack("<IhBB", 0, 0, 0x82, 0) + struct.pack("<IhBB", 10, -32767, 0x02, 1))
            sim.run_for(1.0)
            assert sim.data("r.pose")["x"] == pytest.approx(2.0, abs=0.1)
            os.write(writer, struct.pack("<IhBB", 20, 0, 0x02, 1) + struct.pack("<IhBB", 30, -32767, 0x02, 0))
            sim.run_for(0.2)
            yaw0 = sim.data("r.pose")["yaw"]
            sim.run_for(1.0)
            assert sim.data("r.pose")["yaw"] - yaw0 == pytest.approx(1.0, abs=0.05)  # stick left: Speed / 2
    finally:
        os.close(writer)


def test_joystick_without_a_device_warns_once_and_does_nothing(tmp_path, caplog):
    text = robot_scene("atrv", """
        - {name: pose, type: pose}
        - {name: stick, type: joystick, properties: {device: /nonexistent/js0}}
        """)
    with caplog.at_level(logging.WARNING, logger="morsec.actuators.joystick"), simulate(text, tmp_path) as sim:
        sim.run_for(1.0)
        assert abs(sim.data("r.pose")["x"]) < 1e-3
    warnings = [r.getMessage() for r in caplog.records if "no joystick" in r.getMessage()]
    assert warnings == ["r.stick: no joystick at /nonexistent/js0 (No such file or directory): the joystick does "
                        "nothing"]


def test_sound_plays_pauses_and_stops(tmp_path):
    text = robot_scene("atrv", "- {name: sound, type: sound, properties: {file: /sounds/alarm.wav}}")
    with simulate(text, tmp_path) as sim:
        sim.run_for(1.0)
        assert sim.call("r.sound", "get_status") == {"mode": "play", "file": "/sounds/alarm.wav", "played": 1.0}
        sim.call("r.sound", "pause")
        sim.run_for(0.5)
        assert sim.call("r.sound", "get_status")["played"] == pytest.approx(1.0, abs=0.02)
        sim.command("r.sound", mode="stop")
        sim.run_for(0.1)
        assert sim.call("r.sound", "get_status") == {"mode": "stop", "file": "/sounds/alarm.wav", "played": 0.0}


# ---------------------------------------------------------------- depth camera aggregator

def test_aggregator_merges_its_cameras_in_the_master_frame(tmp_path):
    """Two cameras, one turned 0.4 rad to the left, both seeing a wall 3 m ahead of the master: every point,
    in the master's optical frame, lies on the wall's plane (z = its distance), whichever camera saw it."""
    text = robot_scene("fake_robot", """
        - name: agg
          type: depth_camera_aggregator
          translate: [0.0, 0.0, 1.0]
          properties: {master_camera: front}
          components:
            - {name: left, type: depth_camera, rotate: [0.0, 0.0, 0.4], properties: {cam_width: 64, cam_height: 32}}
            - {name: front, type: depth_camera, translate: [0.2, 0.0, 0.0], properties: {cam_width: 64, cam_height: 32}}
        """, extra="""
        objects:
          - {name: wall, type: box, translate: [3.3, 0.0, 1.0], size: [0.2, 20.0, 4.0]}
        """)
    with simulate(text, tmp_path) as sim:
        sim.run_for(0.2)
        agg = sim.component("r.agg")
        left, front = sim.component("r.agg.left"), sim.component("r.agg.front")
        points = np.asarray(agg.local_data["points"])
        assert agg.local_data["nb_points"] == len(points) == left.local_data["nb_points"] + front.local_data["nb_points"]
        assert left.local_data["nb_points"] > 1000 and front.local_data["nb_points"] > 1000
        assert points[:, 2] == pytest.approx(3.0, abs=0.02)  # the wall's face is 3.0 m ahead of the master
        # the left camera's points come first and lie to the master's left (x < 0 in the optical frame)
        first = points[:left.local_data["nb_points"]]
        assert np.mean(first[:, 0]) < -0.5
        assert abs(np.mean(points[len(first):, 0])) < 0.5


# ---------------------------------------------------------------- builder classes

def test_builder_classes_take_morses_arguments(tmp_path):
    (tmp_path / "alarm.wav").write_bytes(b"RIFF")
    path = tmp_path / "sim.py"
    path.write_text(textwrap.dedent(f"""
        from morse.builder import *
        robot = PatrolBot()
        stick = Joystick(index=2)
        robot.append(stick)
        sound = Sound()
        sound.open({str(tmp_path / "alarm.wav")!r})
        robot.append(sound)
        arm = PA10()
        robot.append(arm)
        lidar = DepthCameraAggregator()
        for i in range(2):
            cam = DepthCamera("cam%i" % i)
            lidar.append(cam)
        lidar.set_master(1)
        robot.append(lidar)
        human = Human()
        human.translate(x=3)
        mocap = MocapControl()
        human.append(mocap)
        keyboard = Keyboard()
        human.append(keyboard)
        human.add_interface('socket')
        env = Environment('empty')
        """))
    scene = load_scene(path, load_catalogue(tmp_path))
    placed = {p.fqn: p.component for p in walk_components(scene)}
    assert placed["robot.stick"].properties.index == 2
    assert placed["robot.sound"].properties.file == str(tmp_path / "alarm.wav")
    assert placed["robot.lidar"].properties.master_camera == "1"
    assert {"robot.arm", "human.mocap", "human.keyboard", "human.skeleton", "human.skeleton.joint_states"} <= set(placed)
    assert placed["human.skeleton.joint_states"].streams and placed["human.skeleton"].services


def test_sound_open_of_a_missing_file_stops_the_script(tmp_path):
    path = tmp_path / "sim.py"
    path.write_text("from morse.builder import *\nrobot = ATRV()\nsound = Sound()\nsound.open('nowhere.wav')\n"
                    "robot.append(sound)\nenv = Environment('empty')\n")
    with pytest.raises(Exception) as err:
        load_scene(path, load_catalogue(tmp_path))
    assert "nowhere.wav" in str(err.value) and "sim.py:4" in str(err.value)
