"""Navigation actuators on an ATRV in the empty world: motion_xyw, waypoint (behaviour, statuses, services,
obstacle avoidance), destination, orientation. Each test drives the robot and checks where it ends up.

Services are dispatched through the simulation's request manager (what the socket server does with a
request line), so that asynchronous answers, preemption and `cancel` are the real ones; one test drives
`morsec run` through real sockets."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from morsec.testing import simulate

FPS = 60

# how far a robot let go at MORSE's 1 m/s (less the tick's friction) slides on the default ground: v^2 / (2 mu g)
COAST = (1.0 - 0.25 * 9.81 / 60) ** 2 / (2 * 0.25 * 9.81)


def atrv(*components: str, objects: str = "", properties: str = "") -> str:
    comps = "\n".join(f"      - {c}" for c in components)
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: robot
    type: atrv
    {properties}
    components:
      - {{name: pose, type: pose, translate: [0.0, 0.0, -0.1]}}
{comps}
"""
    return text + (f"objects:\n{objects}\n" if objects else "")


WAYPOINT = atrv("{name: motion, type: waypoint, services: [socket]}")


def pose(h) -> dict:
    return h.data("robot.pose")


def xy(h) -> np.ndarray:
    p = pose(h)
    return np.array([p["x"], p["y"]])


def run_until(h, predicate, timeout: float) -> float:
    """Step until predicate() holds; the simulated time it took (fails after `timeout` s)."""
    start = h.time
    while not predicate():
        assert h.time - start < timeout, "timed out"
        h.step()
    return h.time - start


# ------------------------------------------------------------------------------------------- motion_xyw
def test_motion_xyw_moves_forward_sideways_and_turns(tmp_path):
    with simulate(atrv("{name: motion, type: motion_xyw}"), tmp_path) as h:
        assert list(h.data("robot.motion")) == ["x", "y", "w"]
        h.command("robot.motion", x=1.0, y=0.5, w=0.0)
        h.run_for(2.0)
        p = pose(h)
        assert (p["x"], p["y"]) == pytest.approx((2.0, 1.0), abs=0.1)
        assert p["yaw"] == pytest.approx(0.0, abs=0.02)
        h.command("robot.motion", x=0.0, y=0.0, w=0.5)
        h.run_for(2.0)
        p = pose(h)
        assert p["yaw"] == pytest.approx(1.0, abs=0.06)
        assert (p["x"], p["y"]) == pytest.approx((2.0, 1.0), abs=0.1)


# ------------------------------------------------------------------------------------------- waypoint
def test_waypoint_defaults_are_morse(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        wp = h.component("robot.motion")
        assert list(h.data("robot.motion")) == ["x", "y", "z", "tolerance", "speed"]
        d = h.data("robot.motion")
        # the goal starts at the actuator's position: the robot stays, "Arrived"
        assert (d["x"], d["y"], d["z"]) == pytest.approx((0.0, 0.0, 0.1), abs=1e-6)
        assert d["tolerance"] == 0.5 and d["speed"] == 1.0
        props = wp.properties.model_dump()
        assert props == {"ObstacleAvoidance": True, "FreeZ": False, "AngleTolerance": pytest.approx(math.radians(10)),
                         "Speed": 1.0, "Target": "", "Ignore": "", "ControlType": "Velocity",
                         "RemainAtDestination": False}
        assert wp.get_status() == "Arrived"
        h.run_for(1.0)
        assert np.linalg.norm(xy(h)) < 0.01


def test_waypoint_reaches_goal_and_reports_arrived(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        wp = h.component("robot.motion")
        h.command("robot.motion", x=5.0, y=3.0, z=0.0, tolerance=0.5, speed=1.0)
        h.step()
        assert wp.get_status() == "Transit"
        took = run_until(h, lambda: wp.get_status() == "Arrived", timeout=10.0)
        assert np.linalg.norm(xy(h) - [5.0, 3.0]) <= 0.5 + 0.02
        assert took == pytest.approx((math.hypot(5, 3) - 0.5) / 1.0, abs=0.8)  # about `speed` m/s
        h.run_for(1.0)  # and stays there
        assert np.linalg.norm(xy(h) - [5.0, 3.0]) <= 0.52
        assert wp.get_status() == "Arrived"


def test_waypoint_turns_on_the_spot_while_heading_error_is_large(tmp_path):
    goal = np.array([-3.0, 1.0])
    with simulate(WAYPOINT, tmp_path) as h:
        wp = h.component("robot.motion")
        h.command("robot.motion", x=float(goal[0]), y=float(goal[1]), z=0.0, tolerance=0.3, speed=1.0)
        start = xy(h)
        turning_frames = 0
        while True:
            p = pose(h)
            bearing = math.atan2(goal[1] - p["y"], goal[0] - p["x"])
            error = abs((bearing - p["yaw"] + math.pi) % (2 * math.pi) - math.pi)
            if error < math.radians(61):
                break
            h.step()
            turning_frames += 1
            # v = 0 while the heading error is >= 60 degrees: the robot turns in place
            assert np.linalg.norm(xy(h) - start) < 0.02
        # it turned from 162 degrees off at up to speed/2 = 0.5 rad/s
        assert turning_frames / FPS == pytest.approx((math.radians(162) - math.radians(61)) / 0.5, abs=0.3)
        run_until(h, lambda: wp.get_status() == "Arrived", timeout=10.0)
        assert np.linalg.norm(xy(h) - goal) <= 0.32


def test_waypoint_goto_completes_with_arrived(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        client = h.client()
        rid = client.send("robot.motion", "goto", 2.0, 0.0, 0.0, 0.1, 1.0)
        assert rid not in client.replies  # asynchronous: no answer yet
        run_until(h, lambda: rid in client.replies, timeout=5.0)
        assert client.replies[rid] == ("SUCCESS", "Arrived")
        assert pose(h)["x"] == pytest.approx(2.0, abs=0.1)
        assert pose(h)["y"] == pytest.approx(0.0, abs=0.1)
        assert client.call("robot.motion", "get_status") == "Arrived"


def test_waypoint_setdest_answers_whether_it_moves(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        client = h.client()
        assert client.call("robot.motion", "setdest", 0.2, 0.1, 0.0) is False  # already within 0.5 m
        assert h.data("robot.motion")["x"] == pytest.approx(0.0)  # goal not changed
        assert client.call("robot.motion", "setdest", 3.0, 0.0, 0.0, 0.2, 1.5) is True
        assert h.data("robot.motion")["speed"] == 1.5
        h.run_for(3.0)
        # arrived within 0.2 m of x = 3, it set no velocity any more and slid on, as MORSE's, until the ground's
        # friction (0.5 x 0.5) stopped it: v^2 / (2 mu g) from 1.5 m/s
        assert pose(h)["x"] == pytest.approx(2.8 + 1.5 ** 2 / (2 * 0.25 * 9.81), abs=0.2)
        assert client.call("robot.motion", "get_status") == "Arrived"


def test_waypoint_stop_keeps_goto_pending_and_resume_goes_on(tmp_path):
    """MORSE's waypoint service test: stop, the goto stays pending, resume, it completes."""
    with simulate(WAYPOINT, tmp_path) as h:
        client = h.client()
        rid = client.send("robot.motion", "goto", 4.0, 0.0, 0.0, 0.1, 1.0)
        h.run_for(2.0)
        assert client.call("robot.motion", "get_status") == "Transit"
        assert client.call("robot.motion", "stop") == "Stop"
        stopped_at = pose(h)["x"]
        assert stopped_at == pytest.approx(2.0, abs=0.15)
        h.run_for(1.0)
        # no velocity set any more: it slides on, as MORSE's, until the ground's friction stops it
        slid_to = pose(h)["x"]
        assert slid_to == pytest.approx(stopped_at + COAST, abs=0.05)
        h.run_for(0.5)
        assert pose(h)["x"] == pytest.approx(slid_to, abs=0.01)  # stopped
        assert rid not in client.replies  # still pending
        assert client.call("robot.motion", "get_status") == "Stop"
        assert client.call("robot.motion", "resume") == "Transit"
        h.run_for(0.5)
        assert pose(h)["x"] == pytest.approx(slid_to + 0.5, abs=0.15)
        assert client.call("robot.motion", "get_status") == "Transit"
        run_until(h, lambda: rid in client.replies, timeout=3.0)
        assert client.replies[rid] == ("SUCCESS", "Arrived")
        assert pose(h)["x"] == pytest.approx(4.0, abs=0.15)


def test_waypoint_second_goto_preempts_the_first(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        client = h.client()
        first = client.send("robot.motion", "goto", 10.0, 0.0, 0.0, 0.1, 1.0)
        h.run_for(1.0)
        second = client.send("robot.motion", "goto", 1.0, 2.0, 0.0, 0.3, 1.0)
        assert first not in client.replies
        h.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
        assert client.replies[first] == ("PREEMPTED", None)  # as the second starts
        assert second not in client.replies
        run_until(h, lambda: second in client.replies, timeout=8.0)
        assert client.replies[second] == ("SUCCESS", "Arrived")
        assert np.linalg.norm(xy(h) - [1.0, 2.0]) <= 0.32


def test_waypoint_cancel_preempts_and_stops_the_robot(tmp_path):
    with simulate(WAYPOINT, tmp_path) as h:
        client = h.client()
        rid = client.send("robot.motion", "goto", 10.0, 0.0, 0.0, 0.1, 1.0)
        h.run_for(2.0)
        client.cancel(rid)
        assert client.replies[rid] == ("PREEMPTED", None)
        at_cancel = xy(h)
        h.run_for(1.0)
        # the goal is now where it was: the robot slides to a stop there, as MORSE's
        assert np.linalg.norm(xy(h) - at_cancel) == pytest.approx(COAST, abs=0.05)
        assert client.call("robot.motion", "get_status") == "Arrived"


def test_waypoint_remains_arrived_unless_asked_to_remain_at_destination(tmp_path):
    for remain in (False, True):
        text = atrv(f"{{name: motion, type: waypoint, properties: {{RemainAtDestination: {str(remain).lower()}}}}}")
        with simulate(text, tmp_path, name=f"remain_{remain}") as h:
            wp = h.component("robot.motion")
            h.command("robot.motion", x=2.0, y=0.0, z=0.0, tolerance=0.2, speed=1.0)
            h.step()
            run_until(h, lambda wp=wp: wp.get_status() == "Arrived", timeout=5.0)
            h.run_for(1.0)  # arrived, it slides to a stop (MORSE's Waypoint sets no velocity any more)
            # push it 1 m back
            pushed_to = pose(h)["x"] - 1.0
            pos, rot = h.body_pose("robot")
            wp.robot.set_pose(pos - [1.0, 0.0, 0.0], rot)
            h.run_for(3.0)
            if remain:
                assert pose(h)["x"] == pytest.approx(2.0, abs=0.25)
            else:
                assert pose(h)["x"] == pytest.approx(pushed_to, abs=0.05)
                assert wp.get_status() == "Arrived"


def test_waypoint_free_z_flies_a_floating_robot_in_3d(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 3.0]
    components:
      - {name: motion, type: waypoint, properties: {FreeZ: true}}
"""
    with simulate(text, tmp_path) as h:
        wp = h.component("heli.motion")
        h.command("heli.motion", x=5.0, y=0.0, z=5.0, tolerance=0.3, speed=1.0)
        h.step()
        run_until(h, lambda: wp.get_status() == "Arrived", timeout=8.0)
        pos, _ = h.body_pose("heli")
        assert np.linalg.norm(pos - [5.0, 0.0, 5.0]) <= 0.32  # 3D distance
        h.run_for(1.0)
        assert np.linalg.norm(h.body_pose("heli")[0] - pos) < 0.02  # floats there


def test_waypoint_position_control_moves_kinematically(tmp_path):
    with simulate(atrv("{name: motion, type: waypoint, properties: {ControlType: Position}}"), tmp_path) as h:
        wp = h.component("robot.motion")
        h.command("robot.motion", x=4.0, y=2.0, z=0.0, tolerance=0.3, speed=1.0)
        h.step()
        run_until(h, lambda: wp.get_status() == "Arrived", timeout=8.0)
        assert np.linalg.norm(xy(h) - [4.0, 2.0]) <= 0.32


CRATE = "  - {name: crate, type: box, translate: [4.0, %s, 0.5], size: [1.0, 1.0, 1.0]%s}"


def _drive_past_crate(h, goal=(8.0, 0.0), timeout=20.0) -> tuple[bool, float]:
    """Drive to `goal`; (whether the robot touched the crate, the time it took or inf)."""
    m, d = h.sim.model, h.sim.data
    crate = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "crate")
    wp = h.component("robot.motion")
    h.command("robot.motion", x=goal[0], y=goal[1], z=0.0, tolerance=0.5, speed=1.0)
    touched = False
    start = h.time
    while h.time - start < timeout:
        h.step()
        for c in d.contact[:d.ncon]:
            if crate in (m.geom_bodyid[c.geom1], m.geom_bodyid[c.geom2]):
                touched = True
        if wp.get_status() == "Arrived":
            return touched, h.time - start
    return touched, math.inf


@pytest.mark.parametrize("offset", [0.0, 0.3, -0.3])
def test_waypoint_avoids_a_crate_on_its_path(tmp_path, offset):
    with simulate(atrv("{name: motion, type: waypoint}", objects=CRATE % (offset, "")), tmp_path) as h:
        touched, took = _drive_past_crate(h)
        assert not touched
        assert took < 14.0
        assert np.linalg.norm(xy(h) - [8.0, 0.0]) <= 0.52


def test_waypoint_without_avoidance_runs_into_the_crate(tmp_path):
    text = atrv("{name: motion, type: waypoint, properties: {ObstacleAvoidance: false}}", objects=CRATE % (0.0, ""))
    with simulate(text, tmp_path) as h:
        touched, took = _drive_past_crate(h, timeout=8.0)
        assert touched and took == math.inf


def test_waypoint_ignores_objects_with_an_ignored_property(tmp_path):
    text = atrv("{name: motion, type: waypoint, properties: {Ignore: 'Soft, Grass'}}",
                objects=CRATE % (0.0, ", properties: {Soft: true}"))
    with simulate(text, tmp_path) as h:
        touched, _ = _drive_past_crate(h, timeout=8.0)
        assert touched


def test_waypoint_moves_its_target_marker(tmp_path):
    text = atrv("{name: motion, type: waypoint, properties: {Target: flag}}",
                objects="  - {name: flag, type: cylinder, translate: [0.0, 5.0, 0.5], size: [0.1, 0.1, 1.0]}")
    with simulate(text, tmp_path) as h:
        h.command("robot.motion", x=3.0, y=-2.0, z=0.5, tolerance=0.5, speed=1.0)
        h.step()
        pos, _ = h.body_pose("flag")
        assert pos == pytest.approx([3.0, -2.0, 0.5], abs=1e-6)


# ------------------------------------------------------------------------------------------- destination
def test_destination_goes_straight_without_turning(tmp_path):
    text = atrv("{name: dest, type: destination, properties: {Speed: 1.0, Tolerance: 0.1}}")
    with simulate(text, tmp_path) as h:
        dest = h.component("robot.dest")
        d = h.data("robot.dest")
        assert list(d) == ["x", "y", "z"] and (d["x"], d["y"]) == pytest.approx((0.0, 0.0))
        assert dest.properties.model_dump() == {"Tolerance": 0.1, "Speed": 1.0,
                                                "ControlType": "Velocity", "RemainAtDestination": False}
        assert dest.status == "Stop"
        h.command("robot.dest", x=3.0, y=2.0, z=0.0)
        h.run_for(1.0)
        assert dest.status == "Transit"
        p = pose(h)
        # on the straight line to the goal, 1 m along it, still facing +x
        assert math.hypot(p["x"], p["y"]) == pytest.approx(1.0, abs=0.1)
        # (the lateral servo gives way a little to the skid-steer wheels' friction)
        assert math.atan2(p["y"], p["x"]) == pytest.approx(math.atan2(2.0, 3.0), abs=0.05)
        assert p["yaw"] == pytest.approx(0.0, abs=0.02)
        run_until(h, lambda: dest.status == "Stop", timeout=5.0)
        assert np.linalg.norm(xy(h) - [3.0, 2.0]) <= 0.12
        assert pose(h)["yaw"] == pytest.approx(0.0, abs=0.02)


def test_destination_default_speed_is_five(tmp_path):
    with simulate(atrv("{name: dest, type: destination}"), tmp_path) as h:
        assert h.component("robot.dest").properties.Speed == 5.0
        h.command("robot.dest", x=0.0, y=-4.0, z=0.0)
        h.run_for(0.5)
        assert pose(h)["y"] == pytest.approx(-2.5, abs=0.2)
        h.run_for(1.0)
        assert pose(h)["y"] == pytest.approx(-4.0, abs=0.5)
        assert h.component("robot.dest").status == "Stop"


# ------------------------------------------------------------------------------------------- orientation
def test_orientation_is_instantaneous_by_default(tmp_path):
    with simulate(atrv("{name: orientation, type: orientation}"), tmp_path) as h:
        comp = h.component("robot.orientation")
        assert math.isinf(comp.properties.speed) and comp.properties.tolerance == 0.02
        assert list(h.data("robot.orientation")) == ["yaw", "pitch", "roll"]
        h.command("robot.orientation", yaw=1.2, pitch=0.0, roll=0.0)
        h.step()
        assert pose(h)["yaw"] == pytest.approx(1.2, abs=0.01)
        h.run_for(1.0)
        assert pose(h)["yaw"] == pytest.approx(1.2, abs=0.01)


def test_orientation_with_a_speed_turns_at_that_rate(tmp_path):
    text = atrv("{name: orientation, type: orientation, properties: {speed: 0.5}}")
    with simulate(text, tmp_path) as h:
        h.command("robot.orientation", yaw=-1.0, pitch=0.0, roll=0.0)
        h.run_for(1.0)
        assert pose(h)["yaw"] == pytest.approx(-0.5, abs=0.05)
        h.run_for(1.5)
        assert pose(h)["yaw"] == pytest.approx(-1.0, abs=0.03)  # reached within tolerance, stopped
        h.run_for(1.0)
        assert pose(h)["yaw"] == pytest.approx(-1.0, abs=0.03)


def test_orientation_rates_are_the_robots_angular_velocity(tmp_path):
    """MORSE's Orientation sets each angle's rate as the robot's angular velocity about its own axis: an
    RMax pitching and yawing at 0.5 rad/s reads (0, 0.5, 0.5) on its Attitude sensor (MORSE's
    attitude_testing), not the -sin(pitch) 0.5 about x that turning the Euler angles exactly takes."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: rmax
    translate: [0.0, 0.0, 20.0]
    components:
      - {name: orientation, type: orientation, properties: {speed: 0.5}}
      - {name: attitude, type: attitude}
"""
    with simulate(text, tmp_path) as h:
        h.command("robot.orientation", yaw=1.0, pitch=1.0, roll=0.0)
        h.run_for(0.25)  # the roll it drifts into on that path is still within the tolerance
        attitude = h.data("robot.attitude")
        assert attitude["rotation"]["pitch"] == pytest.approx(0.125, abs=0.01)
        assert attitude["angular_velocity"] == pytest.approx([0.0, 0.5, 0.5], abs=0.003)


def test_orientation_speed_accepts_inf_in_a_scene(tmp_path):
    text = atrv("{name: orientation, type: orientation, properties: {speed: .inf}}")
    with simulate(text, tmp_path) as h:
        assert math.isinf(h.component("robot.orientation").properties.speed)


# ------------------------------------------------------------------------------------------- real sockets
def test_waypoint_services_over_sockets(tmp_path):
    """`morsec run` as a user runs it: goto answers "Arrived", a second goto preempts the first, cancel."""
    from tests.runtime_helpers import Morsec, pose_sensor, robot, scene, scene_file, wait_until

    motion = {"name": "motion", "type": "waypoint", "streams": ["socket"], "services": ["socket"]}
    path = scene_file(tmp_path, scene(robot("robot", pose_sensor(), motion), strategy="best_effort"))
    with Morsec(path, tmp_path) as sim:
        client = sim.client(timeout=20.0)
        assert client.call("robot.motion", "goto", 0.6, 0.0, 0.0, 0.1, 1.0) == ("SUCCESS", "Arrived")
        first = client.send_request("robot.motion", "goto", 20.0, 0.0, 0.0, 0.1, 1.0)
        second = client.send_request("robot.motion", "goto", 20.0, 1.0, 0.0, 0.1, 1.0)
        assert client.response(first)[1:] == ("PREEMPTED", None)
        client.send(f"{second} cancel\n")
        assert client.response(second)[1:] == ("PREEMPTED", None)
        status = wait_until(lambda: client.ok("robot.motion", "get_status") == "Arrived" or None, timeout=5.0)
        assert status
