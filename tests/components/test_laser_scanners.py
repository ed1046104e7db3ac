"""Laser scanners (laser_scanner and its presets sick, hokuyo, sick_ld_mrs, infrared, velodyne_ray_cast) run in
simulations whose numbers can be computed by hand: walls at known distances, a room of known size, the
floor seen from a known height."""

from __future__ import annotations

import csv
import json
import math
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
from pydantic import ValidationError

from morsec.component.catalogue import load_catalogue
from morsec.middleware.socket_streams import encode
from morsec.testing import simulate

CATALOGUE = load_catalogue(Path(__file__).parent)
LASERS = ["laser_scanner", "sick", "hokuyo", "sick_ld_mrs", "infrared", "velodyne_ray_cast"]
# id: (builder name, frequency, laser_range, scan_window, resolution, layers, number of rays)
PRESETS = {
    "laser_scanner": ("LaserScanner", 10.0, 30.0, 180.0, 1.0, 1, 181),
    "sick": ("Sick", 10.0, 30.0, 180.0, 1.0, 1, 181),
    "hokuyo": ("Hokuyo", 10.0, 30.0, 270.0, 0.25, 1, 1081),
    "sick_ld_mrs": ("SickLDMRS", 4.0, 30.0, 100.0, 0.25, 4, 1604),
    "infrared": ("Infrared", 10.0, 2.0, 20.0, 1.0, 1, 21),
    "velodyne_ray_cast": ("VelodyneRayCast", 60.0, 50.0, 31.5, 0.5, 1, 64),
}
HEIGHT = 0.5  # of the fake robot holding the sensor: no geometry, fixed in the world


def holder_scene(components: str, objects: str = "", rotate=(0.0, 0.0, 0.0), env: str = "empty") -> str:
    """A fixed fake robot at (0, 0, HEIGHT) carrying `components` (YAML flow mappings, one a line)."""
    comps = "\n".join(f"      - {c.strip()}" for c in components.strip().splitlines())
    objs = "\n".join(f"  - {o.strip()}" for o in objects.strip().splitlines())
    text = f"""environment: {{name: {env}, time: {{strategy: fixed_step}}}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, {HEIGHT}]
    rotate: {list(rotate)}
    components:
{comps}
"""
    return text + (f"objects:\n{objs}\n" if objs else "")


def wall_x(face: float, half_width: float = 5.0) -> str:
    """A static box whose -x face is the plane x = face (1 m thick, 2*half_width wide, 3 m high)."""
    return f"{{name: wall, type: box, translate: [{face + 0.5}, 0.0, 1.0], size: [1.0, {2 * half_width}, 3.0]}}"


def azimuths(n: int, window: float, offset: float = 0.0) -> np.ndarray:
    return np.radians(-window / 2 + offset + np.arange(n) * window / (n - 1))


def count_ticks(sim, fqn: str) -> list:
    """Wrap a component's default_action to record the simulated time of each call."""
    instance = sim.component(fqn)
    calls = []
    action = instance.default_action

    def counted():
        calls.append(sim.time)
        action()

    instance.default_action = counted
    return calls


# ---------------------------------------------------------------- catalogue

@pytest.mark.parametrize("cid", LASERS)
def test_laser_folders_and_defaults(cid):
    cls = CATALOGUE.get("sensors", cid)
    builder, freq, rng, window, res, layers, nray = PRESETS[cid]
    assert cls.builder_name == builder and CATALOGUE.resolve("sensors", builder) == cid
    assert cls.frequency == freq
    props = cls.Properties()
    assert (props.laser_range, props.scan_window, props.resolution, props.layers) == (rng, window, res, layers)
    assert set(type(props).model_fields) == {"laser_range", "resolution", "scan_window", "Visible_arc", "layers",
                                             "layer_separation", "layer_offset"}
    arc = sys.modules[CATALOGUE.get("sensors", "laser_scanner").__module__].arc_directions
    rays = arc(props.resolution, props.scan_window, props.layers, props.layer_separation, props.layer_offset)
    assert rays.shape == (nray, 3) and np.linalg.norm(rays, axis=1) == pytest.approx(np.ones(nray))
    assert [lv.name for lv in cls.levels] == ["raw", "rssi"] and cls.default_level() == "raw"
    assert [f.name for f in cls.fields_at("raw")] == ["timestamp", "point_list", "range_list"]
    assert [f.name for f in cls.fields_at("rssi")] == ["timestamp", "point_list", "range_list", "remission_list"]
    for name in ("component.py", "model.xml.j2", "README.md"):
        assert (cls.folder / name).is_file(), name
    assert cls.doc() and cls.short_descr
    if cid != "laser_scanner":  # a preset: the laser scanner's class with other defaults
        assert "LaserScanner" in [k.__name__ for k in cls.__mro__[1:]]


def test_bad_properties_are_rejected():
    props = CATALOGUE.get("sensors", "sick").Properties
    for bad in ({"resolution": 0.0}, {"laser_range": -1.0}, {"scan_window": 400.0}, {"layers": 0},
                {"laser_rang": 3.0}):
        with pytest.raises(ValidationError):
            props(**bad)


@pytest.mark.parametrize("cid", LASERS)
def test_every_preset_runs_with_its_ray_count(cid, tmp_path):
    nray = PRESETS[cid][-1]
    with simulate(holder_scene(f"{{name: laser, type: {cid}}}"), tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.laser")
        assert list(data) == ["timestamp", "point_list", "range_list"]
        assert np.shape(data["point_list"]) == (nray, 3) and np.shape(data["range_list"]) == (nray,)


# ---------------------------------------------------------------- a Sick in front of a wall

def test_sick_reads_a_wall_at_2_5_m(tmp_path):
    scene = holder_scene("{name: sick, type: sick}", wall_x(2.5))
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.sick")
    ranges, points = np.asarray(data["range_list"]), np.asarray(data["point_list"])
    assert len(ranges) == 181
    assert ranges[90] == pytest.approx(2.5, abs=0.01)
    assert points[90] == pytest.approx([2.5, 0.0, 0.0], abs=0.01)
    a = azimuths(181, 180.0)
    # the wall spans y in [-5, 5]: rays with 2.5 |tan a| < 5 (|a| < 63.4 deg) hit its face x = 2.5
    hits = np.abs(np.tan(a)) * 2.5 < 4.95
    misses = np.abs(np.tan(a)) * 2.5 > 5.05
    assert hits.sum() == 127 and misses.sum() == 54
    expected = 2.5 / np.cos(a[hits])
    assert ranges[hits] == pytest.approx(expected, abs=0.01)
    for deg in (-60, -45, -30, 30, 45, 60):  # oblique rays, by hand
        assert ranges[90 + deg] == pytest.approx(2.5 / math.cos(math.radians(deg)), abs=0.01)
    # hit points: on the wall plane x = 2.5, at y = 2.5 tan a, in the scan plane
    assert points[hits, 0] == pytest.approx(np.full(hits.sum(), 2.5), abs=0.01)
    assert points[hits, 1] == pytest.approx(2.5 * np.tan(a[hits]), abs=0.01)
    assert np.abs(points[:, 2]).max() < 1e-9
    # misses: laser_range and [0, 0, 0], exactly
    assert np.all(ranges[misses] == 30.0)
    assert np.all(points[misses] == 0.0)
    assert ranges[0] == 30.0 and ranges[180] == 30.0  # right (-y) and left (+y)


def test_ray_order_index_0_is_the_right_side(tmp_path):
    # a 2 m wide box on the right only (x in [-1, 1], face y = -2): seen by the first rays, not the last
    wall = "{name: right, type: box, translate: [0.0, -2.5, 1.0], size: [2.0, 1.0, 3.0]}"
    with simulate(holder_scene("{name: sick, type: Sick}", wall), tmp_path) as sim:
        sim.step(1)
        ranges = np.asarray(sim.data("r.sick")["range_list"])
    assert ranges[0] == pytest.approx(2.0, abs=0.01)  # -90 deg: straight at the box
    assert ranges[10] == pytest.approx(2.0 / math.cos(math.radians(10)), abs=0.01)  # -80 deg: x = 0.35 on the face
    assert ranges[30] == 30.0  # -60 deg: reaches y = -2 at x = 2 tan(30 deg) = 1.15, past the box
    assert np.all(ranges[90:] == 30.0)  # the left half sees nothing


def test_points_are_in_the_sensor_frame_when_the_robot_turns(tmp_path):
    # robot turned 90 deg left: its +x is the world's +y; a wall whose face is the plane y = 2.5
    wall = "{name: wall, type: box, translate: [0.0, 3.0, 1.0], size: [10.0, 1.0, 3.0]}"
    scene = holder_scene("{name: sick, type: sick}", wall, rotate=(0.0, 0.0, math.pi / 2))
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.sick")
        _, rot = sim.body_pose("r.sick")
    ranges, points = np.asarray(data["range_list"]), np.asarray(data["point_list"])
    assert rot[:, 0] == pytest.approx([0.0, 1.0, 0.0], abs=1e-9)
    assert ranges[90] == pytest.approx(2.5, abs=0.01)
    assert points[90] == pytest.approx([2.5, 0.0, 0.0], abs=0.01)  # not the world's [0, 2.5, 0]
    for deg in (-45, 30):
        a = math.radians(deg)
        r = 2.5 / math.cos(a)
        assert points[90 + deg] == pytest.approx([r * math.cos(a), r * math.sin(a), 0.0], abs=0.01)


def test_a_pitched_scanner_sees_the_floor(tmp_path):
    # mounted 1 m above the floor, pitched 0.5 rad down: the centre ray meets the floor 1 / sin(0.5) away
    scene = holder_scene("{name: sick, type: sick, translate: [0.0, 0.0, 0.5], rotate: [0.0, 0.5, 0.0]}")
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.sick")
    ranges, points = np.asarray(data["range_list"]), np.asarray(data["point_list"])
    h = HEIGHT + 0.5
    assert ranges[90] == pytest.approx(h / math.sin(0.5), abs=0.01)
    assert points[90] == pytest.approx([h / math.sin(0.5), 0.0, 0.0], abs=0.01)
    a = math.radians(40)  # an oblique ray (x, y) = (cos a, sin a) in the sensor frame: world z = -cos a sin 0.5
    assert ranges[130] == pytest.approx(h / (math.cos(a) * math.sin(0.5)), abs=0.01)


def test_hokuyo_in_a_room(tmp_path):
    # an asymmetric room: the sensor at the origin, walls' inner faces at x = 3, x = -2, y = 1.5, y = -2.5
    walls = """
{name: east, type: box, translate: [3.5, 0.0, 1.0], size: [1.0, 10.0, 3.0]}
{name: west, type: box, translate: [-2.5, 0.0, 1.0], size: [1.0, 10.0, 3.0]}
{name: north, type: box, translate: [0.0, 2.0, 1.0], size: [10.0, 1.0, 3.0]}
{name: south, type: box, translate: [0.0, -3.0, 1.0], size: [10.0, 1.0, 3.0]}
"""
    with simulate(holder_scene("{name: hokuyo, type: hokuyo}", walls), tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.hokuyo")
    ranges, points = np.asarray(data["range_list"]), np.asarray(data["point_list"])
    assert len(ranges) == 1081 and points.shape == (1081, 3)
    a = azimuths(1081, 270.0)
    assert math.degrees(a[0]) == pytest.approx(-135.0) and math.degrees(a[540]) == 0.0
    c, s = np.cos(a), np.sin(a)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 1e-12, 3.0 / c, np.where(c < -1e-12, -2.0 / c, np.inf))
        ty = np.where(s > 1e-12, 1.5 / s, np.where(s < -1e-12, -2.5 / s, np.inf))
    expected = np.minimum(tx, ty)
    assert ranges == pytest.approx(expected, abs=0.01)
    assert ranges[0] == pytest.approx(2.0 * math.sqrt(2), abs=0.01)  # -135 deg: the south-west corner region
    assert points[:, 0] == pytest.approx(expected * c, abs=0.01)
    assert points[:, 1] == pytest.approx(expected * s, abs=0.01)


def test_hokuyo_misses_everything_in_the_empty_world(tmp_path):
    with simulate(holder_scene("{name: hokuyo, type: hokuyo}"), tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.hokuyo")
    assert np.all(np.asarray(data["range_list"]) == 30.0)
    assert np.all(np.asarray(data["point_list"]) == 0.0)
    message = json.loads(encode(data))  # the wire format: plain lists, as MORSE
    assert message["point_list"][0] == [0.0, 0.0, 0.0] and len(message["range_list"]) == 1081
    assert b"-0.0" not in encode(data)


# ---------------------------------------------------------------- multi-layer

def test_sick_ld_mrs_layers(tmp_path):
    with simulate(holder_scene("{name: ldmrs, type: sick_ld_mrs}", wall_x(2.5)), tmp_path) as sim:
        sim.step(1)
        data = sim.data("r.ldmrs")
    ranges = np.asarray(data["range_list"]).reshape(4, 401)
    points = np.asarray(data["point_list"]).reshape(4, 401, 3)
    for layer, elevation_deg in enumerate((1.2, 0.4, -0.4, -1.2)):  # top layer first, 0.8 deg apart
        offset = 0.125 if layer % 2 == 0 else 0.0  # the even layers are shifted in azimuth
        a = azimuths(401, 100.0, offset)
        e = math.radians(elevation_deg)
        assert ranges[layer] == pytest.approx(2.5 / (math.cos(e) * np.cos(a)), abs=0.01)
        p = points[layer]
        assert np.degrees(np.arcsin(p[:, 2] / ranges[layer])) == pytest.approx(np.full(401, elevation_deg), abs=1e-6)
        assert np.degrees(np.arctan2(p[:, 1], p[:, 0])) == pytest.approx(np.degrees(a), abs=1e-6)
        assert math.degrees(a[0]) == pytest.approx(-50.0 + offset)
        assert math.degrees(a[-1]) == pytest.approx(50.0 + offset)


# ---------------------------------------------------------------- the robot carrying the laser

def test_the_carrying_robot_is_not_seen_but_others_are(tmp_path):
    # `sick` sits inside the ATRV's chassis box (without the exclusion every ray would hit it from inside,
    # at 0.13 to 0.28 m); `low` sits under the chassis between the front wheels, which are other bodies
    # than the robot's root (without the exclusion its +-90 deg rays would hit them at 0.29 m)
    scene = """environment: {name: empty, time: {strategy: fixed_step}}
robots:
  - name: r
    type: atrv
    components:
      - {name: sick, type: sick, translate: [0.32, 0.0, 0.1]}
      - {name: low, type: sick, translate: [0.32, 0.0, -0.02]}
  - name: other
    type: atrv
    translate: [0.0, 3.0, 0.0]
objects:
  - {name: wall, type: box, translate: [3.32, 0.0, 1.0], size: [1.0, 4.0, 3.0]}
"""
    with simulate(scene, tmp_path) as sim:
        sim.run_for(0.5)
        data, low = sim.data("r.sick"), sim.data("r.low")
        other, _ = sim.body_pose("other")
        groups = sim.sim.model.geom_group.copy()
    assert not np.any(groups == 5)  # the robot's geoms are back in their groups after the scan
    assert np.asarray(low["range_list"])[0] == 30.0 and np.asarray(low["range_list"]).min() > 1.0
    ranges = np.asarray(data["range_list"])
    assert ranges.min() > 1.0  # nothing of its own robot (chassis 0.45 m, wheels 0.43 m away)
    assert ranges[90] == pytest.approx(2.5, abs=0.01)
    assert ranges[0] == 30.0  # right: nothing
    # left (+90 deg): the other ATRV's front-right wheel, whose outer face is 0.43 m right of its origin
    assert ranges[180] == pytest.approx(other[1] - 0.43, abs=0.02)


# ---------------------------------------------------------------- levels, frequency, properties

def test_rssi_level_adds_remission(tmp_path):
    scene = holder_scene("{name: sick, type: sick, level: rssi}\n{name: raw, type: sick}", wall_x(2.5))
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        data, raw = sim.data("r.sick"), sim.data("r.raw")
    assert list(data) == ["timestamp", "point_list", "range_list", "remission_list"]
    assert "remission_list" not in raw
    remission, ranges = np.asarray(data["remission_list"]), np.asarray(data["range_list"])
    assert len(remission) == 181
    assert np.all(remission[ranges < 30.0] == 0.5)  # a box without material: MuJoCo's default specular
    assert np.all(remission[ranges == 30.0] == 0.0)  # misses
    assert np.all(raw["range_list"] == ranges)


@pytest.mark.parametrize("cid,expected", [("sick", 10), ("hokuyo", 10), ("sick_ld_mrs", 4), ("infrared", 10),
                                          ("velodyne_ray_cast", 60)])
def test_default_frequency(cid, expected, tmp_path):
    with simulate(holder_scene(f"{{name: laser, type: {cid}}}"), tmp_path) as sim:
        calls = count_ticks(sim, "r.laser")
        sim.run_for(1.0)  # the first scan is at the first frame
        before = len(calls)
        sim.run_for(1.0)
    assert len(calls) - before == expected  # scans in one simulated second
    assert np.diff(calls[1:]) == pytest.approx(np.full(len(calls) - 2, 1.0 / expected), abs=1e-9)  # evenly


def test_frequency_can_be_set(tmp_path):
    with simulate(holder_scene("{name: laser, type: sick, frequency: 20}"), tmp_path) as sim:
        calls = count_ticks(sim, "r.laser")
        sim.run_for(1.0)
        before = len(calls)
        sim.run_for(1.0)
    assert len(calls) - before == 20


def test_laser_range_changes_at_run_time(tmp_path):
    with simulate(holder_scene("{name: sick, type: sick}", wall_x(2.5)), tmp_path) as sim:
        sim.step(1)
        assert sim.data("r.sick")["range_list"][90] == pytest.approx(2.5, abs=0.01)
        sim.call("r.sick", "set_property", "laser_range", 2.0)
        assert sim.call("r.sick", "get_properties")["laser_range"] == 2.0
        sim.run_for(0.1)
        data = sim.data("r.sick")
        ranges = np.asarray(data["range_list"])
        assert np.all(ranges == 2.0) and np.all(np.asarray(data["point_list"]) == 0.0)
        sim.call("r.sick", "set_property", "laser_range", 3.0)
        sim.run_for(0.1)
        ranges = np.asarray(sim.data("r.sick")["range_list"])
        assert ranges[90] == pytest.approx(2.5, abs=0.01)
        assert ranges[90 + 40] == 3.0  # 2.5 / cos(40 deg) = 3.26 > 3
        assert ranges[90 + 30] == pytest.approx(2.5 / math.cos(math.radians(30)), abs=0.01)
        assert len(ranges) == 181  # resolution / window are fixed at start
        with pytest.raises(ValueError):
            sim.call("r.sick", "set_property", "laser_range", -1.0)


def test_range_cutoff_is_exact(tmp_path):
    # a wall at 2.5 m: seen with laser_range 2.51, missed with 2.49
    scene = holder_scene("{name: a, type: sick, properties: {laser_range: 2.51}}\n"
                         "{name: b, type: sick, properties: {laser_range: 2.49}}", wall_x(2.5))
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        assert sim.data("r.a")["range_list"][90] == pytest.approx(2.5, abs=1e-6)
        assert sim.data("r.b")["range_list"][90] == 2.49


def test_infrared_is_short_range(tmp_path):
    scene = holder_scene("{name: ir, type: infrared}", wall_x(1.5))
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        ranges = np.asarray(sim.data("r.ir")["range_list"])
    a = azimuths(21, 20.0)
    assert ranges == pytest.approx(1.5 / np.cos(a), abs=0.01)
    with simulate(holder_scene("{name: ir, type: infrared}", wall_x(2.5)), tmp_path, name="far") as sim:
        sim.step(1)
        assert np.all(np.asarray(sim.data("r.ir")["range_list"]) == 2.0)


# ---------------------------------------------------------------- velodyne

def test_velodyne_fan_and_rotation(tmp_path):
    # 2 m above the floor: ray i (elevation -27.75 + 0.5 i deg) meets the floor when pointing down
    scene = holder_scene("{name: velo, type: velodyne_ray_cast, translate: [0.0, 0.0, 1.5]}")
    h = HEIGHT + 1.5
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        first = sim.data("r.velo")
        sim.step(30)  # 30 more scans at 60 Hz
        later = sim.data("r.velo")
    elevation = np.radians(-27.75 + 0.5 * np.arange(64))
    with np.errstate(divide="ignore"):
        floor = np.where(elevation < 0, h / np.sin(-elevation), np.inf)
    down = floor <= 50.0  # the floor within laser_range: rays 0 to 50 (elevation -2.75 deg: 41.7 m)
    assert down.sum() == 51
    for data, scans_before in ((first, 0), (later, 30)):
        ranges, points = np.asarray(data["range_list"]), np.asarray(data["point_list"])
        assert len(ranges) == 64
        assert ranges[down] == pytest.approx(floor[down], abs=0.01)
        assert np.all(ranges[~down] == 50.0)
        assert np.all(points[~down] == 0.0)
        azimuth = math.atan2(points[0, 1], points[0, 0])
        assert azimuth == pytest.approx(scans_before * 0.01745, abs=1e-6)  # 1 deg a scan, about +z
        assert points[down, 2] == pytest.approx(np.full(down.sum(), -h), abs=0.01)  # on the floor


def test_component_models_are_visual_only(tmp_path):
    # a velodyne's 0.2 m cylinder 2 m in front of the sick, on another (geometry-less) fake robot: not seen
    scene = """environment: {name: empty, time: {strategy: fixed_step}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, 0.5]
    components:
      - {name: sick, type: sick, color: [1.0, 0.0, 0.0]}
  - name: post
    type: fake_robot
    translate: [2.0, 0.0, 0.5]
    components:
      - {name: velodyne, type: velodyne_ray_cast, color: [0.2, 0.2, 0.2, 0.5]}
"""
    with simulate(scene, tmp_path) as sim:
        sim.step(1)
        assert np.all(np.asarray(sim.data("r.sick")["range_list"]) == 30.0)
        model = sim.sim.model
        for body, rgba in (("r.sick", [1.0, 0.0, 0.0, 1.0]), ("post.velodyne", [0.2, 0.2, 0.2, 0.5])):
            b = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, body)
            geoms = np.flatnonzero(model.geom_bodyid == b)
            assert len(geoms) == 1
            g = geoms[0]
            assert model.geom_group[g] == 2 and model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0
            assert model.geom_rgba[g] == pytest.approx(rgba)


def test_ten_publications_per_simulated_second(tmp_path):
    # what a client sees: a text stream (CSV) of a Sick, one row per publication, timestamps in sim time
    scene = """environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: r
    type: fake_robot
    components:
      - {name: sick, type: sick, streams: [{middleware: text, file: sick.csv, format: csv}]}
"""
    with simulate(scene, tmp_path) as sim:
        sim.run_for(2.0)
    rows = list(csv.DictReader((tmp_path / "sick.csv").open()))
    stamps = np.array([float(row["timestamp"]) for row in rows])
    assert np.count_nonzero((stamps > 1.0 + 1e-6) & (stamps <= 2.0 + 1e-6)) == 10
    assert len(json.loads(rows[-1]["range_list"])) == 181 and json.loads(rows[-1]["point_list"])[0] == [0.0, 0.0, 0.0]
