"""Modifiers (`alter`): seeded Gaussian noise with the right statistics, coordinate conventions against
independent computations, actuator inputs converted back, and build-time errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from morsec.app.project import build_scene
from morsec.errors import SceneError
from morsec.testing import simulate

LAT, LON, ALT = 43.6, 1.4333, 135.0
# the origin as MORSE held it: numbers in environment properties are Blender game properties, 32-bit floats
LAT32, LON32, ALT32 = (float(np.float32(v)) for v in (LAT, LON, ALT))
A = 6378137.0
F = 1 / 298.257223563
E2 = F * (2 - F)
FEET = 3.2808399
TICKS = 1200


# ---------------------------------------------------------------- independent WGS84

def ecef_of(lat_deg: float, lon_deg: float, alt: float) -> np.ndarray:
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return np.array([(n + alt) * math.cos(lat) * math.cos(lon), (n + alt) * math.cos(lat) * math.sin(lon),
                     (n * (1 - E2) + alt) * math.sin(lat)])


def enu_axes(lat_deg: float, lon_deg: float):
    lat, lon = math.radians(lat_deg), math.radians(lon_deg)
    return (np.array([-math.sin(lon), math.cos(lon), 0.0]),
            np.array([-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)]),
            np.array([math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)]))


def ecef_of_scene(x: float, y: float, z: float) -> np.ndarray:
    e, n, u = enu_axes(LAT32, LON32)
    return ecef_of(LAT32, LON32, ALT32) + x * e + y * n + z * u


def geodetic_of(p) -> tuple[float, float, float]:
    """(lat, lon, alt) by Bowring's fixed-point iteration on the latitude (converges to 1e-12 deg)."""
    x, y, z = p
    r = math.hypot(x, y)
    lat = math.atan2(z, r * (1 - E2))
    for _ in range(10):
        n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
        alt = r / math.cos(lat) - n
        lat = math.atan2(z, r * (1 - E2 * n / (n + alt)))
    n = A / math.sqrt(1 - E2 * math.sin(lat) ** 2)
    return math.degrees(lat), math.degrees(math.atan2(y, x)), r / math.cos(lat) - n


# ---------------------------------------------------------------- noise

NOISY = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    translate: [1.0, 2.0, 3.0]
    rotate: [0.1, 0.2, 0.3]
    components:
      - {name: pose, type: pose, modifiers: [{name: noise, pos_std: 0.1, rot_std: 0.05}]}
      - {name: default, type: pose, modifiers: [{name: noise}]}
      - name: axes
        type: pose
        modifiers: [{name: noise, pos_std: {x: 0.1, y: 0.2, z: 0.3}, rot_std: {roll: 0.01, pitch: 0.02, yaw: 0.03}}]
      - {name: flat, type: pose, modifiers: [{name: noise, pos_std: 0.1, rot_std: 0.05, _2D: true}]}
      - {name: odo, type: odometry, modifiers: [{name: noise, pos_std: 0.2, rot_std: 0.02}]}
      - {name: gps, type: gps, modifiers: [{name: noise, pos_std: 0.5}]}
      - {name: gyro, type: gyroscope, modifiers: [{name: noise, rot_std: {yaw: 0.1}}]}
      - {name: imu, type: imu, modifiers: [{name: noise, gyro_std: 0.01, accel_std: {x: 0.1, y: 0.2, z: 0.3}}]}
      - {name: imu_default, type: imu, modifiers: [{name: imunoise}]}
      - {name: clean, type: pose}
      - {name: clean_imu, type: imu}
"""


@pytest.fixture(scope="module")
def noisy(tmp_path_factory):
    """TICKS readings of every sensor of NOISY, as arrays per field."""
    with simulate(NOISY, tmp_path_factory.mktemp("noisy"), seed=7) as h:
        h.step()
        truth = {name: h.data(name) for name in ("r.clean", "r.clean_imu")}
        samples: dict[str, dict[str, list]] = {}
        for _ in range(TICKS):
            h.step()
            for name in h.sim.by_name:
                for key, value in h.data(name).items():
                    samples.setdefault(name, {}).setdefault(key, []).append(value)
    return truth, {name: {k: np.array(v) for k, v in fields.items()} for name, fields in samples.items()}


def check(values: np.ndarray, mean: float, std: float) -> None:
    """Sample mean within 5 standard errors of `mean`, sample std within 10 % of `std`; std 0: untouched,
    every value the same (the true one)."""
    if std == 0:
        assert np.ptp(values) == 0.0 and values[0] == pytest.approx(mean, abs=1e-9)
        return
    assert values.mean() == pytest.approx(mean, abs=5 * std / math.sqrt(len(values)))
    assert values.std() == pytest.approx(std, rel=0.1)


def test_pose_noise_scalar_and_defaults(noisy):
    truth, data = noisy
    clean = truth["r.clean"]
    for field in "xyz":
        check(data["r.pose"][field], clean[field], 0.1)
        check(data["r.default"][field], clean[field], 0.05)  # pos_std default 5 cm
    for field in ("roll", "pitch", "yaw"):
        check(data["r.pose"][field], clean[field], 0.05)
        check(data["r.default"][field], clean[field], math.radians(5))  # rot_std default 5 deg


def test_pose_noise_per_axis_and_2d(noisy):
    truth, data = noisy
    clean = truth["r.clean"]
    for field, std in (("x", 0.1), ("y", 0.2), ("z", 0.3), ("roll", 0.01), ("pitch", 0.02), ("yaw", 0.03)):
        check(data["r.axes"][field], clean[field], std)
    for field, std in (("x", 0.1), ("y", 0.1), ("z", 0.0), ("roll", 0.0), ("pitch", 0.0), ("yaw", 0.05)):
        check(data["r.flat"][field], clean[field], std)


def test_odometry_gps_and_gyroscope_noise(noisy):
    truth, data = noisy
    for field in "xyz":
        check(data["r.odo"][field], 0.0, 0.2)  # odometry starts at 0 wherever the robot is
    for field in ("yaw", "pitch", "roll"):
        check(data["r.odo"][field], 0.0, 0.02)
    for field in ("vx", "vy", "vz", "wx", "wy", "wz"):  # velocities are left alone
        assert np.ptp(data["r.odo"][field]) == 0.0 and abs(data["r.odo"][field][0]) < 1e-12
    for field, value in zip("xyz", (1.0, 2.0, 3.0)):
        check(data["r.gps"][field], value, 0.5)
    clean = truth["r.clean"]
    check(data["r.gyro"]["yaw"], clean["yaw"], 0.1)
    check(data["r.gyro"]["roll"], clean["roll"], 0.0)  # no std given for roll and pitch: no noise
    check(data["r.gyro"]["pitch"], clean["pitch"], 0.0)


def test_imu_noise(noisy):
    truth, data = noisy
    clean = truth["r.clean_imu"]
    accel, rates = data["r.imu"]["linear_acceleration"], data["r.imu"]["angular_velocity"]
    for axis, std in enumerate((0.1, 0.2, 0.3)):
        check(accel[:, axis], clean["linear_acceleration"][axis], std)
        check(rates[:, axis], clean["angular_velocity"][axis], 0.01)
        check(data["r.imu_default"]["linear_acceleration"][:, axis], clean["linear_acceleration"][axis], 0.5)
        check(data["r.imu_default"]["angular_velocity"][:, axis], clean["angular_velocity"][axis], 0.5)
    assert np.all(data["r.imu"]["magnetic_field"] == 0.0)  # not noised
    # the clean IMU reads gravity in the robot's tilted frame: g (−sin p, sin r cos p, cos r cos p)
    r, p = 0.1, 0.2
    assert clean["linear_acceleration"] == pytest.approx(
        [-9.81 * math.sin(p), 9.81 * math.sin(r) * math.cos(p), 9.81 * math.cos(r) * math.cos(p)], abs=1e-9)


def test_noise_values_are_plain_floats(tmp_path):
    with simulate(NOISY, tmp_path, seed=1) as h:
        h.step()
        pose, imu = h.data("r.pose"), h.data("r.imu")
    assert type(pose["x"]) is float and type(pose["yaw"]) is float
    assert all(type(v) is float for v in imu["linear_acceleration"])


# ---------------------------------------------------------------- seeds

SEEDED = """
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}{seed}}}
robots:
  - name: r
    type: atrv
    components:
      - {{name: pose, type: pose, modifiers: [{{name: noise}}]}}
      - {{name: imu, type: imu, modifiers: [{{name: noise}}]}}
      - {{name: odo, type: odometry, modifiers: [{{name: odometrynoise, factor_sigma: 0.1}}, {{name: noise}}]}}
      - {{name: motion, type: motion_vw}}
"""


def record(tmp_path, name: str, seed: int | None = None, env_seed: int | None = None) -> list:
    text = SEEDED.format(seed=f", seed: {env_seed}" if env_seed is not None else "")
    out = []
    with simulate(text, tmp_path, seed=seed, name=name) as h:
        h.command("r.motion", v=0.5, w=0.2)
        for _ in range(60):
            h.step()
            out.append([h.data(n) for n in ("r.pose", "r.imu", "r.odo")])
    return out


def test_same_seed_same_streams_different_seed_different_streams(tmp_path):
    first = record(tmp_path, "a", seed=1)
    assert record(tmp_path, "b", seed=1) == first  # bit-identical: == on floats
    assert record(tmp_path, "c", env_seed=1) == first  # environment.seed and `morsec run --seed` agree
    assert record(tmp_path, "d", seed=1, env_seed=2) == first  # the run option wins
    other = record(tmp_path, "e", seed=2)
    assert other != first
    assert other[-1][0]["x"] != first[-1][0]["x"]
    assert record(tmp_path, "f") != record(tmp_path, "g")  # no seed: fresh entropy each run


# ---------------------------------------------------------------- coordinate conventions

X, Y, Z = 120.0, -80.0, 15.0
ROLL, PITCH, YAW = 0.1, 0.2, 0.3

COORDINATES = f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {LON}, latitude: {LAT}, altitude: {ALT},
               UTMXOffset: "370000.5", UTMYOffset: 4828000.0, UTMZOffset: 135.0}}
robots:
  - name: r
    type: fake_robot
    translate: [{X}, {Y}, {Z}]
    rotate: [{ROLL}, {PITCH}, {YAW}]
    components:
      - {{name: pose, type: pose}}
      - {{name: ned, type: pose, modifiers: [{{name: NED}}]}}
      - {{name: utm, type: pose, modifiers: [{{name: utm}}]}}
      - {{name: utm_given, type: pose, modifiers: [{{name: utm, x_offset: 10.0}}]}}
      - {{name: ecef, type: pose, modifiers: [{{name: ecef}}]}}
      - {{name: geodetic, type: pose, modifiers: [{{name: geodetic}}]}}
      - {{name: geocentric, type: pose, modifiers: [{{name: geocentric}}]}}
      - {{name: feet, type: pose, modifiers: [{{name: feet}}]}}
      - {{name: ned_feet, type: pose, modifiers: [{{name: ned}}, {{name: feet}}]}}
      - {{name: gps_ned, type: gps, modifiers: [{{name: ned}}]}}
      - {{name: gps_geodetic, type: gps, modifiers: [{{name: geodetic}}]}}
      - {{name: gps_raw_ned, type: gps, level: raw, modifiers: [{{name: ned}}]}}
      - {{name: gyro_ned, type: gyroscope, modifiers: [{{name: ned}}]}}
"""


@pytest.fixture(scope="module")
def converted(tmp_path_factory):
    with simulate(COORDINATES, tmp_path_factory.mktemp("coordinates")) as h:
        h.step()
        return {name.split(".")[1]: h.data(name) for name in h.sim.by_name}


def xyz(data: dict) -> tuple[float, float, float]:
    return data["x"], data["y"], data["z"]


def test_ned_and_feet(converted):
    assert xyz(converted["pose"]) == pytest.approx((X, Y, Z), abs=1e-9)
    assert xyz(converted["ned"]) == pytest.approx((Y, X, -Z), abs=1e-9)  # north, east, down
    assert xyz(converted["gps_ned"]) == pytest.approx((Y, X, -Z), abs=1e-9)
    assert xyz(converted["feet"]) == pytest.approx((X * FEET, Y * FEET, Z * FEET), rel=1e-12)
    assert xyz(converted["ned_feet"]) == pytest.approx((Y * FEET, X * FEET, -Z * FEET), rel=1e-12)  # in order
    assert (converted["ned"]["roll"], converted["ned"]["yaw"]) == (converted["pose"]["roll"], converted["pose"]["yaw"])


def test_ned_angles_of_the_gyroscope(converted):
    """Heading clockwise from north: yaw' = pi/2 - yaw; pitch nose-up positive in NED: -pitch."""
    gyro = converted["gyro_ned"]
    assert gyro["yaw"] == pytest.approx(math.pi / 2 - YAW, abs=1e-8)
    assert gyro["pitch"] == pytest.approx(-PITCH, abs=1e-8)
    assert gyro["roll"] == pytest.approx(ROLL, abs=1e-8)


def test_utm_offsets_from_environment_or_parameters(converted):
    assert xyz(converted["utm"]) == pytest.approx((X + 370000.5, Y + 4828000.0, Z + 135.0), abs=1e-6)
    assert xyz(converted["utm_given"]) == pytest.approx((X + 10.0, Y + 4828000.0, Z + 135.0), abs=1e-6)


def test_ecef_geodetic_geocentric(converted):
    ecef = ecef_of_scene(X, Y, Z)
    assert xyz(converted["ecef"]) == pytest.approx(tuple(ecef), abs=1e-6)
    lat, lon, alt = geodetic_of(ecef)
    for name in ("geodetic", "gps_geodetic"):
        data = converted[name]
        assert (data["x"], data["y"]) == pytest.approx((lon, lat), abs=1e-10)  # x = longitude, y = latitude
        assert data["z"] == pytest.approx(alt, abs=1e-5)
    geocentric = converted["geocentric"]
    assert geocentric["x"] == pytest.approx(math.degrees(math.atan2(ecef[1], ecef[0])), abs=1e-10)
    assert geocentric["y"] == pytest.approx(math.degrees(math.atan2(ecef[2], math.hypot(ecef[0], ecef[1]))), abs=1e-10)
    assert geocentric["z"] == pytest.approx(float(np.linalg.norm(ecef)), abs=1e-6)
    assert geocentric["y"] < lat  # the geocentric latitude is smaller than the geodetic one


def test_position_modifier_on_a_level_without_positions(converted):
    """A GPS at its raw level has no x, y, z: `ned` leaves its data unchanged and it is still sent."""
    raw = converted["gps_raw_ned"]
    lat, lon, _ = geodetic_of(ecef_of_scene(X, Y, Z))
    assert (raw["latitude"], raw["longitude"]) == pytest.approx((lat, lon), abs=1e-9)
    assert "x" not in raw


def test_actuator_inputs_are_converted_back(tmp_path):
    """Teleport commands given in feet, NED and geodetic coordinates land the robot where they say."""
    lat, lon, alt = geodetic_of(ecef_of_scene(30.0, 40.0, 5.0))
    text = f"""
environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {LON}, latitude: {LAT}, altitude: {ALT}}}
robots:
  - {{name: a, type: fake_robot, components: [{{name: tp, type: teleport, modifiers: [{{name: feet}}]}}]}}
  - {{name: b, type: fake_robot, components: [{{name: tp, type: teleport, modifiers: [{{name: ned}}]}}]}}
  - {{name: c, type: fake_robot, components: [{{name: tp, type: teleport, modifiers: [{{name: geodetic}}]}}]}}
"""
    with simulate(text, tmp_path) as h:
        h.command("a.tp", x=10.0 * FEET, y=-2.0 * FEET, z=1.0 * FEET)
        h.command("b.tp", x=5.0, y=3.0, z=-2.0)  # 5 m north, 3 m east, 2 m up
        h.command("c.tp", x=lon, y=lat, z=alt)
        h.step(2)
        assert h.body_pose("a")[0] == pytest.approx([10.0, -2.0, 1.0], abs=1e-9)
        assert h.body_pose("b")[0] == pytest.approx([3.0, 5.0, 2.0], abs=1e-9)
        assert h.body_pose("c")[0] == pytest.approx([30.0, 40.0, 5.0], abs=1e-5)


def test_first_declared_actuator_has_the_last_word(tmp_path):
    """MORSE's feet, geodetic and ecef tests: of two teleports on one robot, both placing it at every tick,
    the first one declared wins (MORSE ran the logic of the object created last first); once it is
    deactivated, the other one places the robot, its command converted back from feet."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    translate: [10.0, 8.0, 0.1]
    components:
      - {name: pose, type: pose}
      - {name: teleport, type: teleport}
      - {name: teleport_mod, type: teleport, modifiers: [{name: feet}]}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        h.command("r.teleport", x=100.0, y=200.0, z=50.0)
        h.step(2)
        assert xyz(h.data("r.pose")) == pytest.approx((100.0, 200.0, 50.0), abs=1e-9)
        h.sim.by_name["r.teleport"].active = False
        h.command("r.teleport_mod", x=32.8084, y=26.246, z=0.3280)
        h.step(2)
        assert xyz(h.data("r.pose")) == pytest.approx((32.8084 / FEET, 26.246 / FEET, 0.3280 / FEET), abs=1e-9)


def test_odometry_noise_scale_and_drift(tmp_path):
    """A helicopter flying straight 1 m/s for 2 s: odometry scaled by `factor`; a heading drift of
    0.001 rad per tick adds up to 0.12 rad over 120 ticks."""
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: heli
    type: rmax
    translate: [0.0, 0.0, 5.0]
    components:
      - {name: odo, type: odometry}
      - {name: scaled, type: odometry, modifiers: [{name: odometrynoise, factor: 1.2}]}
      - {name: drifting, type: odometry, modifiers: [{name: odometrynoise, factor: 1.0, gyro_drift: 0.001}]}
      - {name: motion, type: motion_vw}
"""
    with simulate(text, tmp_path, seed=3) as h:
        h.command("heli.motion", v=1.0, w=0.0)
        h.step(120)
        odo, scaled, drifting = h.data("heli.odo"), h.data("heli.scaled"), h.data("heli.drifting")
    assert odo["x"] == pytest.approx(2.0, abs=0.1)
    assert scaled["x"] == pytest.approx(1.2 * odo["x"], rel=1e-9)
    assert drifting["yaw"] - odo["yaw"] == pytest.approx(120 * 0.001, abs=1e-6)


# ---------------------------------------------------------------- build-time errors

def build_with(tmp_path, component: str, modifier: str, properties: str = "") -> None:
    source = tmp_path / "bad.yaml"
    source.write_text(f"""environment:
  name: empty{properties}
robots:
  - name: r
    type: fake_robot
    components:
      - {{name: c, type: {component}, modifiers: [{modifier}]}}
""")
    build_scene(source, tmp_path / "out")


@pytest.mark.parametrize(("component", "modifier", "message"), [
    ("clock", "{name: noise}", "modifiers[0].name: modifier 'noise' does not apply to 'clock' "
                               "(it applies to: gps, gyroscope, imu, odometry, pose)"),
    ("imu", "{name: feet}", "modifier 'feet' does not apply to 'imu' (it applies to: destination, gps, pose, "
                            "teleport, waypoint)"),
    ("pose", "{name: noise, pos_std: lots}", "modifiers[0].pos_std: modifier 'noise': pos_std: Input should be"),
    ("imu", "{name: noise, gyro_std: {x: -}}", "modifiers[0].gyro_std"),
    ("pose", "{name: noise, pos_sdt: 0.1}", "modifiers[0].pos_sdt: modifier 'noise': pos_sdt: Extra inputs are "
                                            "not permitted"),
    ("pose", "{name: ned, factor: 2}", "modifiers[0].factor: modifier 'ned': factor: Extra inputs"),
    ("pose", "{name: ecef}", "modifier 'ecef' needs the environment properties longitude, latitude and altitude "
                             "(missing: longitude, latitude, altitude)"),
    ("pose", "{name: nosie}", "unknown modifier 'nosie'; did you mean"),
])
def test_bad_modifiers_are_build_errors(tmp_path, component, modifier, message):
    with pytest.raises(SceneError) as err:
        build_with(tmp_path, component, modifier)
    text = str(err.value)
    assert text.startswith(f"{tmp_path / 'bad.yaml'}:7:")  # file:line:column
    assert "robots[0].components[0].modifiers[0]" in text
    assert message in text


def test_geodetic_origin_is_held_as_morse_held_it(tmp_path):
    """MORSE's ecef_testing figures: its environment properties were Blender game properties (32-bit floats),
    so longitude 43.6 was 43.59999847 and a GPS at (10, 8, 0.1) read x = 4617522.748 in ECEF (not the
    4617522.631 of a 64-bit origin, 12 cm away). A string keeps every digit."""
    text = """
environment:
  name: empty
  time: {strategy: fixed_step, relative: true}
  properties: {longitude: %s, latitude: %s, altitude: 135.0}
robots:
  - name: r
    type: fake_robot
    translate: [10.0, 8.0, 0.1]
    components:
      - {name: ecef, type: gps, modifiers: [{name: ECEF}]}
      - {name: geodetic, type: gps, modifiers: [{name: geodetic}]}
"""
    (tmp_path / "numbers").mkdir()
    (tmp_path / "strings").mkdir()
    with simulate(text % (43.6, 1.4333), tmp_path / "numbers") as h:
        h.step()
        ecef, geodetic = h.data("r.ecef"), h.data("r.geodetic")
    assert xyz(ecef) == pytest.approx((4617522.748, 4397221.061, 158481.296875), abs=0.02)  # MORSE's test
    assert (geodetic["x"], geodetic["y"]) == pytest.approx((43.6000883, 1.433372470), abs=2e-6)
    assert geodetic["z"] == pytest.approx(135.1, abs=0.02)
    with simulate(text % ('"43.6"', '"1.4333"'), tmp_path / "strings") as h:
        h.step()
        exact = h.data("r.ecef")
    assert xyz(exact) == pytest.approx(tuple(ecef_of(1.4333, 43.6, 135.0) + ecef_offset(1.4333, 43.6, 10, 8, 0.1)),
                                       abs=1e-6)
    assert exact["x"] == pytest.approx(4617522.631, abs=0.001)


def ecef_offset(lat: float, lon: float, x: float, y: float, z: float) -> np.ndarray:
    e, n, u = enu_axes(lat, lon)
    return x * e + y * n + z * u


def test_geodetic_modifier_builds_with_environment_properties(tmp_path):
    """With the environment's geodetic properties (what the 'ecef' error above asks for) the build records
    the modifier on its component and the properties in the scene, and the simulation applies it: the
    pose at the scene's origin is the environment's point in geocentric coordinates."""
    text = f"""environment:
  name: empty
  time: {{strategy: fixed_step, relative: true}}
  properties: {{longitude: {LON}, latitude: {LAT}, altitude: {ALT}}}
robots:
  - name: r
    type: fake_robot
    components:
      - {{name: c, type: pose, modifiers: [{{name: geocentric}}]}}
      - {{name: plain, type: pose}}
"""
    with simulate(text, tmp_path) as h:
        h.step()
        converted, plain = h.data("r.c"), h.data("r.plain")
        manifest = h.sim.manifest  # the build's manifest.json, as the simulation read it
    components = {c.fqn: c for c in manifest.components}
    [recorded] = components["r.c"].modifiers
    assert (recorded.name, recorded.cls) == ("geocentric", "morsec.modifiers.coordinates:ToGeocentric")
    assert components["r.plain"].modifiers == []
    assert manifest.scene["environment"]["properties"] == {"longitude": LON, "latitude": LAT, "altitude": ALT}
    ecef = ecef_of(LAT32, LON32, ALT32)
    assert xyz(plain) == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)
    assert xyz(converted) == pytest.approx((LON32, math.degrees(math.atan2(ecef[2], math.hypot(ecef[0], ecef[1]))),
                                            float(np.linalg.norm(ecef))), abs=1e-6)


# ---------------------------------------------------------------- a project's own components

BEACON = '''from morsec.component import DataField, Sensor
from morsec.modifiers.noise import PositionNoise


class Beacon(Sensor):
    """Reads the fixed point (1, 2, 3){note}."""

    {modifiers}
    data = (DataField("x", 0.0, "float", "m"), DataField("y", 0.0, "float", "m"),
            DataField("z", 0.0, "float", "m"))

    def default_action(self):
        self.local_data.update(x=1.0, y=2.0, z=3.0)


COMPONENT = Beacon
'''

# a preset of a built-in: takes the modifiers `pose` declares
POSE_PRESET = '''from morsec.component import component_class

Pose = component_class("sensors", "pose")


class LowPose(Pose):
    """A pose sensor for tests."""

    builder_name = "LowPose"


COMPONENT = LowPose
'''

# a pose sensor whose noise is a component's own subclass of PoseNoise writing its own modify(): a pose's noise
# is added when its data is read (deferred), but a modify() of its own must still run, at the tick
BIASED_POSE = '''from morsec.component import component_class
from morsec.modifiers.noise import PoseNoise

Pose = component_class("sensors", "pose")


class BiasedNoise(PoseNoise):
    def modify(self, data):
        super().modify(data)
        data["x"] = data["x"] + 10.0


class BiasedPose(Pose):
    """A pose sensor for tests, its noise biased."""

    builder_name = "BiasedPose"
    modifiers = {"noise": BiasedNoise}


COMPONENT = BiasedPose
'''


@pytest.fixture(scope="module")
def project(tmp_path_factory):
    """A project with a sensor declaring `noise`, one declaring no modifier, a preset of `pose` and a pose
    whose noise is its own."""
    root = tmp_path_factory.mktemp("project")
    (root / "morsec.toml").write_text('[project]\nname = "p"\ncomponents = ["components"]\n')
    sources = {"beacon": BEACON.format(note="", modifiers='modifiers = {"noise": PositionNoise}'),
               "quiet_beacon": BEACON.format(note=", no modifier", modifiers="pass"),
               "low_pose": POSE_PRESET, "biased_pose": BIASED_POSE}
    for cid, source in sources.items():
        folder = root / "components" / "sensors" / cid
        folder.mkdir(parents=True)
        (folder / "component.py").write_text(source)
    return root


def project_scene(*components: str) -> str:
    return ("environment: {name: empty, time: {strategy: fixed_step, relative: true}}\nrobots:\n"
            "  - name: r\n    type: fake_robot\n    components:\n"
            + "".join(f"      - {c}\n" for c in components))


def test_a_project_component_declaring_noise_gets_noisy_output(project, tmp_path):
    text = project_scene("{name: noisy, type: beacon, modifiers: [{name: noise, pos_std: 0.5}]}",
                         "{name: clean, type: quiet_beacon}",
                         "{name: pose, type: low_pose, modifiers: [{name: noise, pos_std: 0.2, rot_std: 0.0}, "
                         "{name: feet}]}")
    samples = []
    with simulate(text, tmp_path, project=project, seed=5) as h:
        for _ in range(TICKS):
            h.step()
            samples.append((h.data("r.noisy"), h.data("r.clean"), h.data("r.pose")))
        assert h.sim.component("r.noisy").modifiers[0].__class__.__name__ == "PositionNoise"
    for field, value in zip("xyz", (1.0, 2.0, 3.0)):
        check(np.array([noisy[field] for noisy, _, _ in samples]), value, 0.5)
        check(np.array([clean[field] for _, clean, _ in samples]), value, 0.0)
        check(np.array([pose[field] for _, _, pose in samples]), 0.0, 0.2 * FEET)  # noise, then feet


def test_a_project_component_without_the_modifier_is_a_scene_error(project, tmp_path):
    text = project_scene("{name: clean, type: quiet_beacon, modifiers: [{name: noise}]}")
    with pytest.raises(SceneError) as err:
        with simulate(text, tmp_path, project=project):
            pass
    assert ("modifiers[0].name: modifier 'noise' does not apply to 'quiet_beacon' (it applies to: beacon, "
            "biased_pose, gps, gyroscope, imu, low_pose, odometry, pose)") in str(err.value)


def test_a_noise_subclass_writing_its_own_modify_runs_it(project, tmp_path):
    text = project_scene("{name: pose, type: biased_pose, modifiers: [{name: noise, pos_std: 0.0, rot_std: 0.0}]}")
    with simulate(text, tmp_path, project=project) as h:
        for _ in range(3):
            h.step()
            assert h.data("r.pose")["x"] == 10.0


def test_a_component_declaring_an_unknown_modifier_names_its_file(tmp_path):
    (tmp_path / "morsec.toml").write_text('[project]\nname = "p"\ncomponents = ["components"]\n')
    folder = tmp_path / "components" / "sensors" / "odd"
    folder.mkdir(parents=True)
    (folder / "component.py").write_text(BEACON.format(note="", modifiers='modifiers = {"nosie": PositionNoise}'))
    from morsec.component.catalogue import load_catalogue
    from morsec.errors import MorsecError
    with pytest.raises(MorsecError, match=r"odd/component\.py: unknown modifier 'nosie' in `modifiers`; "
                                          r"did you mean one of 'noise'"):
        load_catalogue(tmp_path)
