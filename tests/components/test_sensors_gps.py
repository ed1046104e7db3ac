"""GPS: scene coordinates, then WGS84 geodetic coordinates of known points, checked against an
independent computation (geodetic -> ECEF -> ENU offset -> ECEF -> Heikkinen's closed form)."""

from __future__ import annotations

import datetime
import math

import numpy as np
import pytest

from morsec.errors import RuntimeFailure
from morsec.testing import simulate

LAT, LON, ALT = 43.6, 1.4333, 135.0
# the origin the simulation uses: numbers in environment properties are 32-bit floats, as MORSE's
LAT32, LON32, ALT32 = (float(np.float32(v)) for v in (LAT, LON, ALT))
A = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)
B = A * (1 - F)


def ecef_of(lat_deg: float, lon_deg: float, alt: float) -> np.ndarray:
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return np.array([(n + alt) * math.cos(lat) * math.cos(lon), (n + alt) * math.cos(lat) * math.sin(lon),
                     (n * (1 - E2) + alt) * math.sin(lat)])


def geodetic_of(p) -> tuple[float, float, float]:
    """Heikkinen (1982): closed-form ECEF -> (lat, lon, alt)."""
    x, y, z = p
    ep2 = (A * A - B * B) / (B * B)
    r = math.hypot(x, y)
    f = 54 * B * B * z * z
    g = r * r + (1 - E2) * z * z - E2 * (A * A - B * B)
    c = E2 * E2 * f * r * r / g ** 3
    s = (1 + c + math.sqrt(c * c + 2 * c)) ** (1 / 3)
    pp = f / (3 * (s + 1 / s + 1) ** 2 * g * g)
    q = math.sqrt(1 + 2 * E2 * E2 * pp)
    r0 = -pp * E2 * r / (1 + q) + math.sqrt(A * A / 2 * (1 + 1 / q) - pp * (1 - E2) * z * z / (q * (1 + q))
                                            - pp * r * r / 2)
    u = math.sqrt((r - E2 * r0) ** 2 + z * z)
    v = math.sqrt((r - E2 * r0) ** 2 + (1 - E2) * z * z)
    z0 = B * B * z / (A * v)
    return math.degrees(math.atan((z + ep2 * z0) / r)), math.degrees(math.atan2(y, x)), u * (1 - B * B / (A * v))


def expected_geodetic(east: float, north: float, up: float) -> tuple[float, float, float]:
    lat, lon = math.radians(LAT32), math.radians(LON32)
    e = np.array([-math.sin(lon), math.cos(lon), 0.0])
    n = np.array([-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)])
    u = np.array([math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)])
    return geodetic_of(ecef_of(LAT32, LON32, ALT32) + east * e + north * n + up * u)


def scene(extra_env: str = "", robot: str = "") -> str:
    return f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {LON}, latitude: {LAT}, altitude: {ALT}{extra_env}}}
robots:
{robot}
"""


def test_geodetic_helpers_agree_at_the_origin():
    lat, lon, alt = geodetic_of(ecef_of(LAT, LON, ALT))
    assert (lat, lon) == pytest.approx((LAT, LON), abs=1e-12)
    assert alt == pytest.approx(ALT, abs=1e-6)


def test_gps_levels_at_a_known_point(tmp_path):
    robot = """
  - name: r
    type: fake_robot
    translate: [300.0, -400.0, 25.0]
    components:
      - {name: simple, type: gps}
      - {name: raw, type: gps, level: raw}
      - {name: ext, type: gps, level: extended}
"""
    with simulate(scene(robot=robot), tmp_path) as h:
        h.step(2)
        simple, raw, ext = h.data("r.simple"), h.data("r.raw"), h.data("r.ext")
    assert list(simple) == ["timestamp", "x", "y", "z"]
    assert (simple["x"], simple["y"], simple["z"]) == pytest.approx((300.0, -400.0, 25.0), abs=1e-9)
    assert list(raw) == ["timestamp", "longitude", "latitude", "altitude", "velocity"]
    assert list(ext) == ["timestamp", "longitude", "latitude", "altitude", "velocity", "date", "time", "heading"]
    lat, lon, alt = expected_geodetic(300.0, -400.0, 25.0)
    for data in (raw, ext):
        assert data["latitude"] == pytest.approx(lat, abs=1e-9)  # 0.1 mm
        assert data["longitude"] == pytest.approx(lon, abs=1e-9)
        assert data["altitude"] == pytest.approx(alt, abs=1e-4)
        assert data["velocity"] == [0.0, 0.0, 0.0]
    # 300 m east, 400 m south of the origin: about 0.0037 deg east, 0.0036 deg south; a little higher than
    # 25 m above the origin because the Earth curves away below the tangent plane (+ d^2 / 2R ≈ 0.02 m)
    assert lon - LON32 == pytest.approx(math.degrees(300.0 / (math.cos(math.radians(LAT)) * 6388838.0)), rel=1e-3)
    assert lat - LAT32 == pytest.approx(math.degrees(-400.0 / 6367000.0), rel=1e-3)
    assert alt == pytest.approx(ALT + 25.0 + 500.0 ** 2 / (2 * 6371000.0), abs=2e-3)
    # relative time: the timestamp is 2/60 s after 1 January 1970, 00:00:00 UTC
    assert (ext["date"], ext["time"]) == ("010170", "000000")
    assert ext["heading"] == math.inf  # standing still: not observable


def test_gps_angle_against_north(tmp_path):
    """With angle_against_north = 30 the scene's y axis points 30 degrees east of true north."""
    robot = """
  - name: r
    type: fake_robot
    translate: [0.0, 1000.0, 0.0]
    components:
      - {name: gps, type: gps, level: raw}
"""
    with simulate(scene(extra_env=", angle_against_north: 30.0", robot=robot), tmp_path) as h:
        h.step()
        data = h.data("r.gps")
    lat, lon, alt = expected_geodetic(1000.0 * math.sin(math.radians(30)), 1000.0 * math.cos(math.radians(30)), 0.0)
    assert (data["latitude"], data["longitude"]) == pytest.approx((lat, lon), abs=1e-9)
    assert data["altitude"] == pytest.approx(alt, abs=1e-4)


def test_gps_velocity_and_heading_of_a_moving_robot(tmp_path):
    """A floating helicopter heading north-east (yaw 45 deg) at 2 m/s: ENU velocity (√2, √2, 0), heading 45."""
    robot = """
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 10.0]
    rotate: [0.0, 0.0, 0.7853981633974483]
    components:
      - {name: gps, type: gps, level: extended}
      - {name: motion, type: motion_vw}
"""
    with simulate(scene(robot=robot), tmp_path) as h:
        h.command("heli.motion", v=2.0, w=0.0)
        h.run_for(2.0)
        data = h.data("heli.gps")
    assert data["velocity"] == pytest.approx([math.sqrt(2), math.sqrt(2), 0.0], abs=0.02)
    assert data["heading"] == pytest.approx(45.0, abs=0.1)
    assert data["time"] == "000002"


def test_gps_date_and_time_are_the_utc_timestamp(tmp_path):
    text = scene(robot="""
  - name: r
    type: fake_robot
    components:
      - {name: gps, type: gps, level: extended}
""").replace("relative: true", "relative: false")
    with simulate(text, tmp_path) as h:
        h.step()
        data = h.data("r.gps")
    utc = datetime.datetime.fromtimestamp(data["timestamp"], tz=datetime.UTC)
    assert data["date"] == f"{utc.day:02d}{utc.month:02d}{utc.year % 100:02d}"
    assert data["time"] == f"{utc.hour:02d}{utc.minute:02d}{utc.second:02d}"


def test_geodetic_levels_need_the_environment_properties(tmp_path):
    text = """
environment: {name: empty}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: gps, type: gps, level: raw}
"""
    with pytest.raises(RuntimeFailure, match=r"r\.gps: .*longitude, latitude and altitude"):
        with simulate(text, tmp_path):
            pass
