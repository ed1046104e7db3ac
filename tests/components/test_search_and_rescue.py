"""search_and_rescue and victim: MORSE's ROSACE pieces. A victim (a static robot with an Injured property)
is detected in a cone in front of the sensor, reported with its requirements and severity, and healed by
the sensor's asynchronous `heal` when it is near enough and the robot has a required ability."""

from __future__ import annotations

import math

import mujoco
import pytest

from morsec.testing import simulate

SCENE = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: detector, type: search_and_rescue, services: [socket],
         properties: {Heal_range: 1.0, Abilities: "1,2,4", Angle: 90.0, Distance: 2.0}}
      - {name: medic, type: search_and_rescue, services: [socket], properties: {Heal_range: 1.0, Abilities: "3"}}
      - {name: motion, type: teleport}
  - {name: Victim, type: victim, translate: [10.0, 0.0, 0.0]}
"""


def go(h, x: float, yaw: float = 0.0) -> None:
    h.command("robot.motion", x=x, y=0.0, z=0.0, yaw=yaw, pitch=0.0, roll=0.0)
    h.run_for(0.4)


def test_a_victim_in_the_cone_is_reported_and_healed(tmp_path):
    with simulate(SCENE, tmp_path) as h:
        client = h.client()
        h.run_for(0.4)
        assert client.call("robot.detector", "get_robot_abilities") == [1, 2, 4]
        assert h.data("robot.detector")["victim_dict"] == {}  # 10 m away, the cone is 2 m long

        go(h, 8.0)  # the victim's near side (x = 9.77) is in the cone; its origin is 2 m away
        found = h.data("robot.detector")["victim_dict"]
        assert list(found) == ["Victim"]
        assert found["Victim"]["requirements"] == [1, 2, 3] and found["Victim"]["severity"] == 10
        assert found["Victim"]["coordinate"] == pytest.approx({"x": 10.0, "y": 0.0, "z": 0.0}, abs=1e-6)
        assert client.call("robot.detector", "get_victim_severity") == 10
        assert client.call("robot.detector", "get_victim_requirements") == [1, 2, 3]
        status, message, _ = client.wait(client.send("robot.detector", "heal"))
        assert status == "FAILED" and "1.00 m" in message  # farther than Heal_range

        go(h, 8.0, math.pi)  # turned away: out of the cone
        assert h.data("robot.detector")["victim_dict"] == {}
        rid = client.send("robot.detector", "get_victim_severity")
        assert client.replies[rid][0] == "FAILED"

        go(h, 9.2)  # 0.8 m from the victim's origin: within reach
        start = h.time
        status, message, when = client.wait(client.send("robot.detector", "heal"))
        assert status == "SUCCESS" and "partially healed" in message
        assert when - start == pytest.approx(10 / 6.0, abs=0.2)  # 10 ticks of the 6 Hz sensor
        h.run_for(0.4)
        victim = h.data("robot.detector")["victim_dict"]["Victim"]
        assert victim["requirements"] == [3] and victim["severity"] == 10  # 1 and 2 healed; 3 left
        # the victim's state is shared: another sensor with ability 3 finishes the job
        assert h.data("robot.medic")["victim_dict"]["Victim"]["requirements"] == [3]
        status, message, _ = client.wait(client.send("robot.medic", "heal"))
        assert status == "SUCCESS" and "'Victim' healed" in message
        h.run_for(0.4)
        assert h.data("robot.detector")["victim_dict"]["Victim"] == {
            "coordinate": {"x": 10.0, "y": 0.0, "z": 0.0}, "requirements": [], "severity": 0}
        geom = mujoco.mj_name2id(h.sim.model, mujoco.mjtObj.mjOBJ_BODY, "Victim")
        colors = h.sim.model.geom_rgba[h.sim.model.geom_bodyid == geom]
        assert (colors[colors[:, 3] > 0] == [0.5, 1.0, 0.5, 1.0]).all()  # healed: green


def test_a_victim_stays_where_it_is_put_and_a_robot_without_abilities_cannot_heal(tmp_path):
    text = SCENE.replace('Abilities: "3"', 'Abilities: "7"')
    with simulate(text, tmp_path) as h:
        go(h, 9.2)
        client = h.client()
        status, message, _ = client.wait(client.send("robot.medic", "heal"))
        assert status == "FAILED" and "Not equipped" in message
        pos, _ = h.body_pose("Victim")
        assert pos == pytest.approx([10.0, 0.0, 0.0], abs=1e-9)  # static: the ATRV's push does not move it
