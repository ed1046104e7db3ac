"""The example scenes do what their comments say: the rover drives waypoints round MORSE's boxes while its
laser sees the room, the quadrotor flies to a waypoint, the car drives and steers."""

import math
from pathlib import Path

import numpy as np

from morsec.testing import simulate

SCENES = Path(__file__).resolve().parent.parent / "scenes"


def scene(name: str) -> str:
    return (SCENES / f"{name}.yaml").read_text()


def test_rover_drives_waypoints_and_its_laser_sees_the_room(tmp_path):
    with simulate(scene("rover_laser"), tmp_path) as sim:
        sim.run_for(0.2)
        scan = sim.data("rover.sick")
        ranges = np.asarray(scan["range_list"])
        assert len(ranges) == 181
        # the laser is 0.5 m ahead of the ATRV's origin, looking along +x at the east wall (x = 15)
        assert abs(ranges[90] - 14.5) < 0.02
        # goal behind the blue box (centred at (-3.48, -3.0)): the rover must go round it
        assert sim.call("rover.waypoint", "setdest", -5.0, -4.5, 0.0, 0.5, 1.0) is True
        for _ in range(40):
            sim.run_for(1.0)
            if sim.call("rover.waypoint", "get_status") == "Arrived":
                break
        pose = sim.data("rover.pose")
        assert sim.call("rover.waypoint", "get_status") == "Arrived"
        assert math.hypot(pose["x"] + 5.0, pose["y"] + 4.5) <= 0.5
        assert abs(pose["roll"]) < 0.1 and abs(pose["pitch"]) < 0.1  # drove, did not climb the box


def test_quadrotor_flies_to_a_waypoint(tmp_path):
    with simulate(scene("quadrotor_waypoints"), tmp_path) as sim:
        sim.call("quadrotor.waypoint", "setdest", 2.0, 1.0, 3.0, 0.0, 0.2)
        sim.run_for(20.0)
        pose = sim.data("quadrotor.pose")
        assert math.dist((pose["x"], pose["y"], pose["z"]), (2.0, 1.0, 3.0)) < 0.3
        assert sim.data("quadrotor.gps")["altitude"] > 146.0 + 2.5  # raw GPS: geodetic altitude


def test_car_drives_forward_and_turns_left(tmp_path):
    with simulate(scene("car"), tmp_path) as sim:
        sim.run_for(0.5)
        start = sim.data("car.pose")
        sim.command("car.steer_force", steer=0.0, force=-20.0, brake=0.0)  # MORSE's forces: 10 kg
        sim.run_for(3.0)
        straight = sim.data("car.pose")
        assert straight["x"] - start["x"] > 1.0 and abs(straight["y"] - start["y"]) < 0.3
        sim.command("car.steer_force", steer=0.4, force=-20.0, brake=0.0)
        sim.run_for(3.0)
        turned = sim.data("car.pose")
        assert turned["yaw"] - straight["yaw"] > 0.2  # steering left turns counter-clockwise
