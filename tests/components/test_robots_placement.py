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
