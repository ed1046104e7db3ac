"""Motion sensors (accelerometer, velocity, attitude, gyroscope) on a robot whose motion is known: a
floating helicopter driven by motion_vw (v forward, w about z: a circle of radius v / w), and fixed
robots at known orientations."""

from __future__ import annotations

import math

import pytest

from morsec.testing import simulate

V, W = 1.0, 0.5
MODES = ("Velocity", "Position")


@pytest.fixture(scope="module")
def circling(tmp_path_factory):
    """Data of every motion sensor, in both computation modes, on a helicopter circling at (V, W)."""
    parts = []
    for mode in MODES:
        props = f"properties: {{ComputationMode: {mode}}}"
        parts += [f"      - {{name: acc_{mode}, type: accelerometer, {props}}}",
                  f"      - {{name: vel_{mode}, type: velocity, {props}}}",
                  f"      - {{name: att_{mode}, type: attitude, {props}}}"]
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 5.0]
    components:
{chr(10).join(parts)}
      - {{name: gyro, type: gyroscope}}
      - {{name: motion, type: motion_vw}}
"""
    with simulate(text, tmp_path_factory.mktemp("circling")) as h:
        h.run_for(0.5)
        at_rest = {name: h.data(name) for name in h.sim.by_name}
        h.command("heli.motion", v=V, w=W)
        h.run_for(3.0)
        moving = {name: h.data(name) for name in h.sim.by_name}
        yaw = h.yaw("heli")
    return at_rest, moving, yaw


@pytest.mark.parametrize("mode", MODES)
def test_accelerometer_excludes_gravity_and_feels_the_turn(circling, mode):
    at_rest, moving, _ = circling
    rest = at_rest[f"heli.acc_{mode}"]
    assert list(rest) == ["timestamp", "distance", "velocity", "acceleration", "angular_acceleration"]
    assert rest["acceleration"] == pytest.approx([0.0, 0.0, 0.0], abs=0.02)  # gravity not included
    assert rest["distance"] == pytest.approx(0.0, abs=1e-6)
    data = moving[f"heli.acc_{mode}"]
    assert data["distance"] == pytest.approx(V / 60, rel=0.01)  # per tick at 60 Hz
    assert data["velocity"] == pytest.approx([V, 0.0, 0.0], abs=0.01)
    # uniform circular motion: centripetal acceleration v w towards the centre, on the left (+y)
    assert data["acceleration"] == pytest.approx([0.0, V * W, 0.0], abs=0.03)
    assert data["angular_acceleration"] == pytest.approx([0.0, 0.0, 0.0], abs=0.05)


@pytest.mark.parametrize("mode", MODES)
def test_velocity_in_sensor_and_world_frames(circling, mode):
    _, moving, yaw = circling
    data = moving[f"heli.vel_{mode}"]
    assert list(data) == ["timestamp", "linear_velocity", "angular_velocity", "world_linear_velocity"]
    assert data["linear_velocity"] == pytest.approx([V, 0.0, 0.0], abs=0.01)
    assert data["angular_velocity"] == pytest.approx([0.0, 0.0, W], abs=0.01)
    # the position mode differentiates over the last tick: the heading half a tick back
    heading = yaw - (W / 120 if mode == "Position" else 0.0)
    assert data["world_linear_velocity"] == pytest.approx([V * math.cos(heading), V * math.sin(heading), 0.0],
                                                          abs=0.01)


@pytest.mark.parametrize("mode", MODES)
def test_attitude_angles_and_rates(circling, mode):
    _, moving, yaw = circling
    data = moving[f"heli.att_{mode}"]
    assert list(data) == ["timestamp", "rotation", "angular_velocity"]
    assert list(data["rotation"]) == ["yaw", "pitch", "roll"]  # MORSE's Euler on the wire
    att_yaw, pitch, roll = data["rotation"].values()
    assert (roll, pitch) == pytest.approx((0.0, 0.0), abs=5e-3)  # the servos tilt it a little
    assert att_yaw == pytest.approx(yaw, abs=1e-9)
    assert data["angular_velocity"] == pytest.approx([0.0, 0.0, W], abs=0.01)
    # 3.0 s at W rad/s, from yaw 0 (the servo takes a few frames to reach W)
    assert att_yaw == pytest.approx(math.remainder(3.0 * W, 2 * math.pi), abs=0.03)


def test_gyroscope_gives_angles_of_the_sensor(circling, tmp_path):
    _, moving, yaw = circling
    assert moving["heli.gyro"]["yaw"] == pytest.approx(yaw, abs=1e-9)
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    rotate: [0.1, -0.2, 0.3]
    components:
      - {name: gyro, type: gyroscope}
      - {name: turned, type: gyroscope, rotate: [0.0, 0.0, 1.0]}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        gyro, turned = h.data("r.gyro"), h.data("r.turned")
    assert list(gyro) == ["timestamp", "yaw", "pitch", "roll"]
    assert (gyro["roll"], gyro["pitch"], gyro["yaw"]) == pytest.approx((0.1, -0.2, 0.3), abs=1e-8)
    # the sensor's own frame counts: turned by 1 rad about the robot's z axis (then read in world XYZ angles)
    assert turned["yaw"] > gyro["yaw"] + 0.9


def test_attitude_yaw_against_north(tmp_path):
    """With angle_against_north = 20 deg the scene's y axis is 20 deg east of north; a sensor facing
    the scene's y axis (yaw +90 deg) has a bearing of 20 deg: UseAngleAgainstNorth reads -20 deg."""
    text = """
environment:
  name: empty
  time: {strategy: fixed_step, relative: true}
  properties: {longitude: 1.4333, latitude: 43.6, altitude: 135.0, angle_against_north: 20.0}
robots:
  - name: r
    type: fake_robot
    rotate: [0.0, 0.0, 1.5707963267948966]
    components:
      - {name: north, type: attitude, properties: {UseAngleAgainstNorth: true}}
      - {name: scene, type: attitude}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        north, scene = h.data("r.north"), h.data("r.scene")
    assert north["rotation"]["yaw"] == pytest.approx(math.radians(-20.0), abs=1e-9)
    assert scene["rotation"]["yaw"] == pytest.approx(math.pi / 2, abs=1e-9)
    assert north["angular_velocity"] == [0.0, 0.0, 0.0]


def test_airspeed_reads_the_dynamic_pressure_along_its_axis(tmp_path):
    """MORSE's airspeed: 0.5 rho v^2 (rho = 1.225) with v along the sensor's x axis; turned pi/2, it measures
    the robot's sideways speed, the same both ways. A Morsy set going at 1 and 2 m/s reads MORSE's 0.55 and
    2.30 Pa (its airspeed_testing): what is left of the speed at the end of the tick, when the sensor reads it,
    after Bullet's ground friction and the Morsy's heavy damping (0.493); Position mode, the displacement over
    the tick, reads the tick's mean speed."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: morsy
    components:
      - {name: motion, type: motion_xyw}
      - {name: side, type: airspeed, rotate: [0.0, 0.0, 1.5707963267948966], properties: {ComputationMode: Velocity}}
      - {name: side_pos, type: airspeed, rotate: [0.0, 0.0, 1.5707963267948966],
         properties: {ComputationMode: Position}}
      - {name: ahead, type: airspeed}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.2)
        assert list(h.data("robot.side")) == ["timestamp", "diff_pressure"]
        assert h.data("robot.side")["diff_pressure"] == pytest.approx(0.0, abs=1e-3)
        for vx, vy, ahead, side in ((1.0, 0.0, 0.55, 0.0), (0.0, 2.0, 0.0, 2.30), (0.0, -2.0, 0.0, 2.30)):
            h.command("robot.motion", x=vx, y=vy, w=0.0)
            h.run_for(0.1)  # MORSE's test reads it 0.1 s after the command, within 0.01 Pa
            assert h.data("robot.ahead")["diff_pressure"] == pytest.approx(ahead, abs=0.005)
            assert h.data("robot.side")["diff_pressure"] == pytest.approx(side, abs=0.005)
            y0 = h.body_pose("robot")[0][1]
            h.step()
            moved = h.body_pose("robot")[0][1] - y0
            assert h.data("robot.side_pos")["diff_pressure"] == pytest.approx(0.5 * 1.225 * (moved * 60) ** 2, rel=0.01)
            if vy:
                assert h.data("robot.side_pos")["diff_pressure"] > side + 0.02  # the mean, above the tick's end


@pytest.mark.parametrize("angles", [(0.0, 2.5, 0.0), (0.0, -2.9, 0.0), (3.0, 0.0, 0.0), (0.0, 0.0, -3.0),
                                    (0.4, 1.9, -0.3)])
def test_euler_angles_are_chosen_as_blender_chose_them(angles, tmp_path):
    """A rotation has two XYZ Euler triples; MORSE read the one Blender gave, the one with the smaller sum of
    absolute angles: a pitch of 2.5 rad alone reads (roll 0, pitch 2.5, yaw 0), not (pi, 0.64, pi) (MORSE's
    teleport_testing). Pose, gyroscope and odometry read the same triple."""
    roll, pitch, yaw = angles
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: rmax
    translate: [0.0, 0.0, 20.0]
    components:
      - {name: pose, type: pose}
      - {name: gyro, type: gyroscope}
      - {name: tp, type: teleport}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        h.command("r.tp", x=1.0, y=2.0, z=30.0, roll=roll, pitch=pitch, yaw=yaw)
        h.step(2)
        pose, gyro = h.data("r.pose"), h.data("r.gyro")
    for reading in (pose, gyro):
        assert (reading["roll"], reading["pitch"], reading["yaw"]) == pytest.approx(angles, abs=1e-6)


@pytest.mark.parametrize("angles", [(0.0, 2.5, 0.0), (math.pi, 0.3, math.pi), (0.2, -1.8, 2.9),
                                    (0.0, math.pi / 2, 0.7)])
def test_matrix_to_euler_gives_the_smaller_triple_of_the_same_rotation(angles):
    from morsec.kits.geometry import euler_to_quat, matrix_to_euler, quat_to_matrix

    rot = quat_to_matrix(euler_to_quat(*angles))
    got = matrix_to_euler(rot)
    assert quat_to_matrix(euler_to_quat(*got)) == pytest.approx(rot, abs=1e-9)  # the same rotation
    other = (math.remainder(got[0] + math.pi, 2 * math.pi), math.remainder(math.pi - got[1], 2 * math.pi),
             math.remainder(got[2] + math.pi, 2 * math.pi))
    assert sum(map(abs, got)) <= sum(map(abs, other)) + 1e-9
    if abs(math.cos(angles[1])) < 1e-9:  # gimbal lock: Blender puts the rest in roll
        assert got[2] == 0.0 and got[1] == pytest.approx(angles[1])
