"""Outdoor environments MORSE's tests use: land-1/rosace_1 (a flat field with a fire that spreads) and
water-1/deep_water (a water surface nothing collides with, no floor)."""

from __future__ import annotations

import pytest

from morsec.testing import simulate


def test_rosace_1_is_flat_ground_with_a_fire_that_spreads(tmp_path):
    text = """
environment: {name: land-1/rosace_1, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: thermometer, type: thermometer, properties: {DefaultTemperature: 25.0}}
      - {name: motion, type: teleport}
  - {name: rover, type: atrv, translate: [30.0, -6.0, 0.0]}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.5)
        for name in ("robot", "rover"):
            assert h.body_pose(name)[0][2] == pytest.approx(0.1, abs=0.01)  # ATRVs stand on flat ground
        assert h.data("robot.thermometer")["temperature"] == pytest.approx(25.0, abs=0.01)  # the fire is far
        h.command("robot.motion", x=40.0, y=0.0, z=0.0, yaw=0.0, pitch=0.0, roll=0.0)
        h.run_for(0.5)
        readings = [h.data("robot.thermometer")["temperature"]]
        for _ in range(3):
            h.run_for(5.0)
            readings.append(h.data("robot.thermometer")["temperature"])
        assert readings[0] > 28.0  # the first bush burns from the start, 16 m away
        assert readings == sorted(readings) and len(set(readings)) == 4  # a new bush every 4 s: hotter and hotter
    burning = [o for o in h.sim.objects if o.name.startswith("fire_")]
    assert len(burning) == 20 and all(o.properties["Fire"] is True for o in burning)


def test_thermometer_ignores_a_source_until_its_start_time(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - {name: r, type: fake_robot, components: [{name: thermo, type: thermometer}]}
objects:
  - {name: pyre, type: box, translate: [5.0, 0.0, 0.0], properties: {Fire: 300, Fire_Start: 1.0}}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.5)
        assert h.data("r.thermo")["temperature"] == pytest.approx(15.0)
        h.run_for(1.0)
        assert h.data("r.thermo")["temperature"] == pytest.approx(15.0 + 300 * 2.718281828459045 ** -1.0)


def test_deep_water_has_a_surface_nothing_collides_with_and_no_floor(tmp_path):
    text = """
environment: {name: water-1/deep_water, time: {strategy: fixed_step, relative: true}}
robots:
  - {name: sub, type: submarine, translate: [0.0, 200.0, -20.0], components: [{name: pose, type: pose}]}
objects:
  - {name: crate, type: box, translate: [0.0, 0.0, 1.0], dynamic: true}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(2.0)
        assert h.body_pose("sub")[0] == pytest.approx([0.0, 200.0, -20.0], abs=0.01)  # floats where it is put
        assert h.body_pose("crate")[0][2] < -5.0  # fell through the surface: nothing below
