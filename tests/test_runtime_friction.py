"""MORSE's ground friction against velocity control (morsec.kits.ground_friction): an ATRV driven by
motion_vw goes a little slower than commanded, by what Bullet's Coulomb friction took between two ticks of
MORSE (the robot's friction times the ground's 0.5), and a Waypoint robot that stops slides on."""

from __future__ import annotations

import math

import pytest
from runtime_helpers import Morsec, pose_sensor, robot, scene, scene_file, start_all, stop_all
from test_runtime_motion import MOTION, Recorder, at, drive, start_index

from morsec.kits import ground_friction

G = 9.81


def test_slide_is_coulomb_over_two_substeps():
    mu = ground_friction.ground_friction(None)
    assert mu == 0.25  # Blender's 0.5 for the robot and the ground, multiplied as Bullet does
    mean, end = ground_friction.slide(1.0, 0.0, mu, G, 1 / 60, 1 / 60)
    assert mean[0] == pytest.approx(1.0 - 0.75 * mu * G / 60)  # velocity first, then position, twice
    assert end[0] == pytest.approx(1.0 - mu * G / 60)
    # left alone it stops after v^2 / (2 mu g), never turned back
    speed, moved = (1.0, 0.0), 0.0
    for _ in range(120):
        mean, speed = ground_friction.slide(*speed, mu, G, 1 / 60, 1 / 60)
        moved += mean[0] / 60
    assert speed == (0.0, 0.0)
    assert moved == pytest.approx(1 / (2 * mu * G), abs=0.01)
    # turning, the yaw rate loses a third of the speed's share; on the spot nothing
    v, _, w = ground_friction.turned(0.5, 0.0, -0.4, ground_friction.slide(0.5, 0.0, mu, G, 1 / 60, 1 / 60)[0])
    assert 1 - w / -0.4 == pytest.approx((1 - v / 0.5) / 3)
    assert ground_friction.turned(0.0, 0.0, 1.0, (0.0, 0.0))[2] == 1.0


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("friction")
    process = Morsec(scene_file(tmp, scene(
        robot("slippery", pose_sensor(), MOTION, translate=[0.0, -3.0, 0.0], friction=0.0),
        robot("plain", pose_sensor(), MOTION),
        robot("sticky", pose_sensor(), MOTION, translate=[0.0, 3.0, 0.0], friction=5.0),
        strategy="fixed_step")), tmp)
    start_all(process)
    try:
        yield process
    finally:
        stop_all(process)


def test_friction_slows_a_robot_driven_by_velocity(sim):
    """MORSE's friction_testing: 2 s at 1 m/s go 2.0 m at friction 0 and 1.4 m at friction 5; the
    default friction costs 3 cm/s."""
    names = ("slippery", "plain", "sticky")
    recorders = {f"{name}.pose": Recorder(sim, f"{name}.pose") for name in names}
    records = drive(sim, {name: {"v": 1.0, "w": 0.0} for name in names}, 2.0, recorders)
    gone = {}
    for name in names:
        poses = records[f"{name}.pose"]
        rest = poses[start_index(poses)]
        gone[name] = at(poses, rest["timestamp"] + 2.0)["x"] - rest["x"]
    assert gone["slippery"] == pytest.approx(2.0, abs=0.03)
    assert gone["plain"] == pytest.approx(2.0 * (1 - 0.75 * 0.25 * G / 60), abs=0.03)
    assert gone["sticky"] == pytest.approx(2.0 * (1 - 0.75 * 2.5 * G / 60), abs=0.05)
    assert gone["plain"] < gone["slippery"] - 0.03
    assert not math.isclose(gone["sticky"], gone["plain"], abs_tol=0.3)
