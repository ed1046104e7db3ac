"""Where `translate` puts a robot, as MORSE: the origin of a robot that floats (NoGravity: the RMax, the
submarine) is where the script says, so its pose sensor reads that height (MORSE's destination, teleport,
ned, orientation, rmax_velocity ... tests: `RMax().translate(z=20)` reads z = 20); a robot that gravity
sets on the ground stands there, its origin spawn_height up."""

from __future__ import annotations

import pytest

from morsec.testing import simulate


def scene(robot: str, translate: list[float], properties: str = "") -> str:
    return f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: r
    type: {robot}
    translate: {translate}
    {properties}
    components:
      - {{name: pose, type: pose}}
"""


@pytest.mark.parametrize("robot, translate", [("rmax", [10.0, 8.0, 20.0]), ("rmax", [0.0, 0.0, 10.0]),
                                              ("submarine", [0.0, 200.0, 5.0])])
def test_a_floating_robot_stands_where_it_was_put(robot, translate, tmp_path):
    with simulate(scene(robot, translate), tmp_path) as h:
        h.step()
        assert [h.data("r.pose")[k] for k in "xyz"] == pytest.approx(translate, abs=1e-6)
        h.run_for(1.0)
        assert [h.data("r.pose")[k] for k in "xyz"] == pytest.approx(translate, abs=1e-3)


def test_an_rmax_with_gravity_lands_on_its_skids(tmp_path):
    """NoGravity false: translate z is the ground under its skids, 0.55 m below the origin."""
    with simulate(scene("rmax", [0.0, 0.0, 0.0], "properties: {NoGravity: false}"), tmp_path) as h:
        h.step()
        assert h.data("r.pose")["z"] == pytest.approx(0.55, abs=1e-3)
        h.run_for(1.0)
        assert h.data("r.pose")["z"] == pytest.approx(0.55, abs=0.01)


@pytest.mark.parametrize("robot, rest", [("atrv", 0.10), ("pioneer3dx", 0.15), ("segwayrmp400", 0.20)])
def test_a_ground_robot_put_low_stands_at_morse_height(robot, rest, tmp_path):
    """MORSE's tests read these heights on a Pose at the origin (vw_testing z = 0.10; pionner3dx_testing a
    Pose 0.15 m below the origin reads 0; segway_vw / reverse_vw translate(z=0.1) and read 0.20 at once)."""
    for z in (0.0, 0.1):
        with simulate(scene(robot, [0.0, 0.0, z]), tmp_path, name=f"z{round(z * 10)}") as h:
            h.step()
            assert h.data("r.pose")["z"] == pytest.approx(rest, abs=1e-3)
            h.run_for(1.0)
            assert h.data("r.pose")["z"] == pytest.approx(rest, abs=0.005)


def test_a_ground_robot_put_high_falls_from_there(tmp_path):
    """translate z above its standing height is where its origin starts (MORSE's), then it falls."""
    with simulate(scene("atrv", [0.0, 0.0, 1.0]), tmp_path) as h:
        h.step()
        assert h.data("r.pose")["z"] == pytest.approx(1.0, abs=2e-3)  # one frame of fall: 1.4 mm
        h.run_for(1.5)
        assert h.data("r.pose")["z"] == pytest.approx(0.10, abs=0.01)


TELEPORTED = """
environment: {name: empty, time: {strategy: fixed_step, frequency: 60}}
robots:
  - name: r
    type: atrv
    translate: [1.0, 2.0, 0.0]
    components:
      - {name: pose, type: pose}
      - {name: teleport, type: teleport}
      - {name: motion, type: motion_vw}
"""


def test_a_teleport_that_receives_nothing_holds_its_robot_however_it_is_pushed(tmp_path):
    """An idle teleport keeps applying its command: a robot moved by hand, or driven by another actuator,
    is back at the command's pose at the next frame (the teleport skips recomputing the pose only while
    the robot is still where the command put it)."""
    with simulate(TELEPORTED, tmp_path) as sim:
        sim.step(5)
        held = sim.data("r.pose")
        robot = sim.sim.robots[0].handle
        robot.base_qpos()[:2] += [0.5, -0.3]  # pushed by hand, between two frames
        sim.step(1)
        assert (sim.data("r.pose")["x"], sim.data("r.pose")["y"]) == pytest.approx((held["x"], held["y"]), abs=1e-9)
        sim.command("r.motion", v=1.0, w=0.5)  # another actuator drives it
        sim.step(30)
        assert [sim.data("r.pose")[k] for k in ("x", "y", "z", "yaw")] == \
            pytest.approx([held[k] for k in ("x", "y", "z", "yaw")], abs=1e-9)
        sim.command("r.teleport", x=3.0, y=-1.0, z=held["z"], roll=held["roll"], pitch=held["pitch"], yaw=0.5)
        sim.step(1)
        assert [sim.data("r.pose")[k] for k in ("x", "y", "yaw")] == pytest.approx([3.0, -1.0, 0.5], abs=1e-6)
