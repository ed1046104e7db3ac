"""Sensors of the robot's surroundings: barometer, magnetometer, clock, battery, thermometer."""

from __future__ import annotations

import math

import pytest

from morsec.errors import RuntimeFailure
from morsec.testing import simulate

LAT, LON, ALT = 43.6, 1.4333, 135.0


def test_barometer_follows_the_standard_atmosphere(tmp_path):
    """p = p_ref (1 - L dz / T0) ^ (g M / (R L)): 100 m up from the start, about 1196 Pa less."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, 20.0]
    components:
      - {name: baro, type: barometer}
      - {name: baro2, type: barometer, properties: {ReferencePressure: 90000.0}}
      - {name: tp, type: teleport}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        assert h.data("r.baro")["pressure"] == pytest.approx(101325.0, abs=1e-9)  # where it started
        h.command("r.tp", x=0.0, y=0.0, z=120.0)
        h.step(2)
        baro, baro2 = h.data("r.baro"), h.data("r.baro2")
    assert list(baro) == ["timestamp", "pressure"]
    exponent = 9.81 * 0.0289644 / (8.31447 * 0.0065)
    expected = 101325.0 * (1 - 0.0065 * 100.0 / 288.15) ** exponent
    assert baro["pressure"] == pytest.approx(expected, rel=1e-9)
    assert expected == pytest.approx(101325.0 - 1196.0, abs=5.0)
    assert baro2["pressure"] == pytest.approx(90000.0 / 101325.0 * expected, rel=1e-9)


def test_barometer_on_a_teleported_robot_reads_the_height_it_was_put_at(tmp_path):
    """MORSE's barometer_testing: a Morsy (gravity, contacts) teleported to 1000 m reads 89871.0 +- 0.1 Pa.
    The teleport holds the robot through the frame's physics (MORSE's sensors read the pose before
    Blender's physics step): gravity does not pull it 2 mm down before the sensor reads it."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: morsy
    components:
      - {name: baro, type: barometer}
      - {name: tp, type: teleport}
"""
    exponent = 9.81 * 0.0289644 / (8.31447 * 0.0065)
    with simulate(text, tmp_path) as h:
        h.step()
        start = h.body_pose("r")[0][2]
        for height in (100.0, 1000.0):
            h.command("r.tp", x=0.0, y=0.0, z=height)
            for _ in range(3):
                h.step()
                assert h.body_pose("r")[0][2] == pytest.approx(height, abs=1e-9)
                expected = 101325.0 * (1 - 0.0065 * (height - start) / 288.15) ** exponent
                assert h.data("r.baro")["pressure"] == pytest.approx(expected, rel=1e-10)
        assert h.data("r.baro")["pressure"] == pytest.approx(89871.0, abs=0.1)


def test_magnetometer_reads_the_world_magnetic_model(tmp_path):
    from pygeomag import GeoMag

    text = f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {LON}, latitude: {LAT}, altitude: {ALT}}}
robots:
  - name: r
    type: fake_robot
    components:
      - {{name: mag, type: magnetometer, properties: {{date: 2025.5}}}}
      - {{name: mag2020, type: magnetometer, properties: {{date: 2021.0}}}}
      - {{name: facing_north, type: magnetometer, rotate: [0.0, 0.0, 1.5707963267948966],
          properties: {{date: 2025.5}}}}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        mag, mag2020, north = h.data("r.mag"), h.data("r.mag2020"), h.data("r.facing_north")
    assert list(mag) == ["timestamp", "x", "y", "z"]
    wmm = GeoMag(coefficients_file="wmm/WMM_2025.COF").calculate(glat=LAT, glon=LON, alt=ALT / 1000, time=2025.5)
    assert (mag["x"], mag["y"], mag["z"]) == pytest.approx((wmm.x, wmm.y, wmm.z), abs=1.0)
    # Toulouse: about 24 uT north, 0.7 uT east, 40 uT down (declination +1.8 deg, inclination 59 deg)
    assert 20000 < mag["x"] < 28000 and 0 < mag["y"] < 2000 and 35000 < mag["z"] < 45000
    old = GeoMag(coefficients_file="wmm/WMM_2020.COF").calculate(glat=LAT, glon=LON, alt=ALT / 1000, time=2021.0)
    assert (mag2020["x"], mag2020["y"], mag2020["z"]) == pytest.approx((old.x, old.y, old.z), abs=1.0)
    # turned to face north: the reading turns with the sensor (x' = left axis, y' = forward, z' = down)
    assert (north["x"], north["y"], north["z"]) == pytest.approx((-wmm.y, wmm.x, wmm.z), abs=1.0)


def test_magnetometer_gives_morse_figures(tmp_path):
    """MORSE's magnetometer_testing: a date of 2015.0 reads WMM2015 as first published (the model MORSE
    shipped; its test values are that release's), at geodetic points thousands of km from the scene origin
    reached by a teleport with the `geodetic` modifier (x = longitude, y = latitude, z = altitude)."""
    text = """
environment:
  name: empty
  time: {strategy: fixed_step, relative: true}
  properties: {longitude: 43.6, latitude: 1.4333, altitude: 135.0}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: mag, type: magnetometer, properties: {date: 2015.0}}
      - {name: tp, type: teleport, modifiers: [{name: geodetic}]}
"""
    expected = {(0, 80, 0): (6627.1, -445.9, 54432.3), (120, 0, 0): (39518.2, 392.9, -11252.4),
                (240, -80, 0): (5797.3, 15761.1, -52919.1), (0, 80, 100000): (6314.3, -471.6, 52269.8)}
    with simulate(text, tmp_path) as h:
        for (lon, lat, alt), field in expected.items():
            h.command("r.tp", x=float(lon), y=float(lat), z=float(alt), roll=0.0, pitch=0.0, yaw=0.0)
            h.step(2)
            mag = h.data("r.mag")
            assert (mag["x"], mag["y"], mag["z"]) == pytest.approx(field, abs=0.1), (lon, lat, alt)


def test_magnetometer_on_a_robot_teleported_below_the_ground(tmp_path):
    """The same figures on a Morsy (physics, contacts) as MORSE's test has it: the geodetic points lie
    thousands of km below the scene's ground plane, which does not push a robot the teleport holds."""
    text = """
environment:
  name: empty
  time: {strategy: fixed_step, relative: true}
  properties: {longitude: 43.6, latitude: 1.4333, altitude: 135.0}
robots:
  - name: r
    type: morsy
    components:
      - {name: mag, type: magnetometer, properties: {date: 2015.0}}
      - {name: tp, type: teleport, modifiers: [{name: geodetic}]}
"""
    expected = {(0, 80, 0): (6627.1, -445.9, 54432.3), (120, 0, 0): (39518.2, 392.9, -11252.4)}
    with simulate(text, tmp_path) as h:
        for (lon, lat, alt), field in expected.items():
            h.command("r.tp", x=float(lon), y=float(lat), z=float(alt), roll=0.0, pitch=0.0, yaw=0.0)
            h.step(6)
            mag = h.data("r.mag")
            assert (mag["x"], mag["y"], mag["z"]) == pytest.approx(field, abs=0.1), (lon, lat, alt)


def test_magnetometer_needs_geodetic_properties(tmp_path):
    text = """
environment: {name: empty}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: mag, type: magnetometer}
"""
    with pytest.raises(RuntimeFailure, match=r"r\.mag: .*longitude, latitude and altitude \(missing: longitude, "
                                             r"latitude, altitude\)"):
        with simulate(text, tmp_path):
            pass


def test_clock_gives_the_simulated_time(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: clock, type: clock}
      - {name: slow, type: clock, frequency: 10}
"""
    with simulate(text, tmp_path) as h:
        h.step(7)
        clock, slow = h.data("r.clock"), h.data("r.slow")
    assert clock == {"timestamp": pytest.approx(7 / 60)}
    assert slow == {"timestamp": pytest.approx(6 / 60)}  # 10 Hz out of 60: ticks at frames 1, 6, 12 ...


def test_battery_discharges_and_charges_in_charging_zones(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: battery, type: battery, properties: {DischargingRate: 0.5}}
      - {name: slow, type: battery, frequency: 4}
zones:
  - {type: Charging, translate: [10.0, 0.0, 0.0], size: [2.0, 2.0, 2.0]}
  - {type: Other, translate: [0.0, 0.0, 0.0], size: [2.0, 2.0, 2.0]}
"""
    with simulate(text, tmp_path) as h:
        assert h.data("r.battery") == {"timestamp": 0.0, "charge": 100.0, "status": "Charged"}
        h.run_for(10.0)
        battery = h.data("r.battery")
        assert battery["charge"] == pytest.approx(100.0 - 10.0 * 0.5, abs=1e-9)
        assert battery["status"] == "Discharging"
        assert h.data("r.slow")["charge"] == pytest.approx(100.0 - 10.0 * 0.05, abs=1e-9)  # default 0.05 %/s
        robot, rot = h.body_pose("r")
        h.sim.place_body(h.sim.robots[0].handle.body_id, [10.5, 0.5, 0.0], rot)
        h.run_for(4.0)
        battery = h.data("r.battery")
        assert battery["charge"] == pytest.approx(95.0 + 4.0 * 0.5, abs=1e-9)
        assert battery["status"] == "Charging"
        h.run_for(8.0)
        assert h.data("r.battery") == {"timestamp": pytest.approx(22.0), "charge": 100.0, "status": "Charged"}


def test_battery_charge_is_exact_to_the_frame(tmp_path):
    """The charge follows the frames elapsed, not a sum of float steps: after n frames at 10 %/s it is exactly
    100 - 10 n / 60, so that 123 frames read by MORSE's battery test are -20.5, not -20.500000000000583 (which
    fails its 20 +- 0.5); across a charging zone's edge, the frames before and after each count once."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: battery, type: battery, properties: {DischargingRate: 10.0}}
zones:
  - {type: Charging, translate: [10.0, 0.0, 0.0], size: [2.0, 2.0, 2.0]}
"""
    with simulate(text, tmp_path) as h:
        h.step(54)
        before = h.data("r.battery")["charge"]
        h.step(123)
        after = h.data("r.battery")["charge"]
        assert (before, after) == (100.0 - 10.0 * 54 / 60, 100.0 - 10.0 * 177 / 60)
        assert after - before == -20.5
        h.step(500 - 177)
        assert h.data("r.battery")["charge"] == 100.0 - 10.0 * 500 / 60
        _, rot = h.body_pose("r")
        h.sim.place_body(h.sim.robots[0].handle.body_id, [10.5, 0.5, 0.0], rot)
        h.step(30)  # the first of them discharges up to the frame the robot was put there, then it charges
        assert h.data("r.battery") == {"timestamp": pytest.approx(530 / 60), "status": "Charging",
                                       "charge": (100.0 - 10.0 * 500 / 60) + 10.0 * 30 / 60}


def test_battery_never_goes_below_zero(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: battery, type: battery, properties: {DischargingRate: 40.0}}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(3.0)
        assert h.data("r.battery")["charge"] == 0.0
        assert h.data("r.battery")["status"] == "Discharging"


def test_thermometer_sums_fire_sources(tmp_path):
    """15 + 200 exp(-0.2 * 5) from a burning box 5 m away, + 600 exp(-0.2 * 10) from a numeric source
    10 m away; a Range of 8 m leaves the far one out; objects without the tag do not count."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, 1.0]
    components:
      - {name: thermo, type: thermometer}
      - {name: near, type: thermometer, properties: {Range: 8.0}}
      - {name: custom, type: thermometer, properties: {FireTag: Hot, DefaultTemperature: -5.0, Alpha: 0.5,
         FireTemperature: 50.0}}
objects:
  - {name: campfire, type: box, translate: [3.0, 4.0, 1.0], properties: {Fire: true, Hot: true}}
  - {name: furnace, type: box, translate: [0.0, -10.0, 1.0], properties: {Fire: 600}}
  - {name: rock, type: box, translate: [1.0, 0.0, 1.0], properties: {Label: rock}}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        thermo, near, custom = h.data("r.thermo"), h.data("r.near"), h.data("r.custom")
    assert list(thermo) == ["timestamp", "temperature"]
    assert thermo["temperature"] == pytest.approx(15 + 200 * math.exp(-1.0) + 600 * math.exp(-2.0), rel=1e-9)
    assert near["temperature"] == pytest.approx(15 + 200 * math.exp(-1.0), rel=1e-9)
    assert custom["temperature"] == pytest.approx(-5 + 50 * math.exp(-2.5), rel=1e-9)
