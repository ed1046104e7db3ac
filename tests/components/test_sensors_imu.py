"""IMU: specific force with gravity at rest, body rates and off-centre terms of a turning robot, frames,
and the World Magnetic Model field in the IMU frame."""

from __future__ import annotations

import math

import numpy as np
import pytest

from morsec.testing import simulate

G = 9.81


def test_imu_at_rest_reads_gravity_on_z(tmp_path):
    """An ATRV standing on the ground: (0, 0, +9.81); an IMU pitched down by 90 degrees (its x axis
    pointing at the ground) feels gravity's reaction against its x axis: (-9.81, 0, 0)."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: atrv
    components:
      - {name: imu, type: imu}
      - {name: pitched, type: imu, translate: [0.2, 0.0, 0.3], rotate: [0.0, 1.5707963267948966, 0.0]}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(1.0)
        imu, pitched = h.data("r.imu"), h.data("r.pitched")
    assert list(imu) == ["timestamp", "angular_velocity", "linear_acceleration", "magnetic_field"]
    assert imu["linear_acceleration"] == pytest.approx([0.0, 0.0, G], abs=0.05)
    assert imu["angular_velocity"] == pytest.approx([0.0, 0.0, 0.0], abs=1e-3)
    assert pitched["linear_acceleration"] == pytest.approx([-G, 0.0, 0.0], abs=0.05)
    assert imu["magnetic_field"] == [0.0, 0.0, 0.0]  # no geodetic environment properties
    assert all(type(v) is float for field in ("angular_velocity", "linear_acceleration") for v in imu[field])


def test_imu_of_a_turning_robot(tmp_path):
    """A floating helicopter turning at w = 0.8 rad/s: the rate gyro reads w about z; an IMU mounted
    0.5 m ahead of the rotation axis also feels the centripetal acceleration w^2 r towards the axis
    (-0.32 m/s^2 on its x) on top of gravity. Finite differences (Position mode) agree with MuJoCo's
    sensors (Velocity mode)."""
    w, r = 0.8, 0.5
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 5.0]
    components:
      - {{name: imu, type: imu}}
      - {{name: ahead, type: imu, translate: [{r}, 0.0, 0.0]}}
      - {{name: ahead_fd, type: imu, translate: [{r}, 0.0, 0.0], properties: {{ComputationMode: Position}}}}
      - {{name: motion, type: motion_vw}}
"""
    with simulate(text, tmp_path) as h:
        h.command("heli.motion", v=0.0, w=w)
        h.run_for(2.0)
        imu, ahead, ahead_fd = h.data("heli.imu"), h.data("heli.ahead"), h.data("heli.ahead_fd")
        # the yaw advances by w / 60 per frame
        yaw0 = h.yaw("heli")
        h.step(6)
        assert (h.yaw("heli") - yaw0) == pytest.approx(6 * w / 60, rel=0.02)
    assert imu["angular_velocity"] == pytest.approx([0.0, 0.0, w], abs=0.01)
    assert imu["linear_acceleration"] == pytest.approx([0.0, 0.0, G], abs=0.05)
    assert ahead["angular_velocity"] == pytest.approx([0.0, 0.0, w], abs=0.01)
    assert ahead["linear_acceleration"] == pytest.approx([-w * w * r, 0.0, G], abs=0.05)
    assert ahead_fd["angular_velocity"] == pytest.approx([0.0, 0.0, w], abs=0.01)
    assert ahead_fd["linear_acceleration"] == pytest.approx([-w * w * r, 0.0, G], abs=0.05)


def test_imu_magnetic_field_is_the_wmm_in_the_imu_frame(tmp_path):
    """Scene axes are East, North, Up: an IMU with the scene's orientation reads (B_east, B_north,
    -B_down); turned to face North (yaw +90 deg) it reads (B_north, -B_east, -B_down)."""
    from pygeomag import GeoMag

    lat, lon, alt = -33.87, 151.21, 50.0
    text = f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {lon}, latitude: {lat}, altitude: {alt}}}
robots:
  - name: r
    type: fake_robot
    components:
      - {{name: imu, type: imu, properties: {{date: 2025.5}}}}
      - {{name: north, type: imu, rotate: [0.0, 0.0, 1.5707963267948966], properties: {{date: 2025.5}}}}
      - {{name: later, type: imu, properties: {{date: 2029.5}}}}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        imu, north, later = h.data("r.imu"), h.data("r.north"), h.data("r.later")
    wmm = GeoMag(base_year=2025).calculate(glat=lat, glon=lon, alt=alt / 1000, time=2025.5,
                                           allow_date_outside_lifespan=True)
    # the field drifts tens of nT a year: the date property is what the model is taken at
    assert np.linalg.norm(np.subtract(later["magnetic_field"], imu["magnetic_field"])) > 20.0
    assert imu["magnetic_field"] == pytest.approx([wmm.y, wmm.x, -wmm.z], abs=5.0)
    assert north["magnetic_field"] == pytest.approx([wmm.x, -wmm.y, -wmm.z], abs=5.0)
    assert np.linalg.norm(imu["magnetic_field"]) == pytest.approx(wmm.f, rel=1e-4)
    assert 40000 < wmm.f < 70000  # nT: the Earth's field, not some other unit
    assert math.isfinite(imu["angular_velocity"][0])
