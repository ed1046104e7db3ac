"""The Python builder front end: MORSE builder scripts record the same scene a YAML file states."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from morsec.app.project import build_scene
from morsec.cli.standalone import morsec_args
from morsec.component.catalogue import load_catalogue
from morsec.errors import MorsecError, SceneError
from morsec.frontends import load_scene
from morsec.scene.walk import walk_components

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
SCRIPTS = Path(__file__).resolve().parent / "builder_scripts"
MORSEC = Path(sys.executable).parent / "morsec"


def twins() -> list[tuple[Path, Path]]:
    """Every scenes/*.py with a same-stem YAML (or TOML) scene beside it."""
    pairs = []
    for script in sorted(SCENES.glob("*.py")):
        for suffix in (".yaml", ".yml", ".toml"):
            other = script.with_suffix(suffix)
            if other.is_file():
                pairs.append((script, other))
    return pairs


def write(tmp_path: Path, body: str, name: str = "sim.py") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(body).lstrip("\n"), encoding="utf-8")
    return path


def load(path: Path):
    return load_scene(path, load_catalogue(path.parent))


def fqns(scene, path: Path) -> list[str]:
    return [placed.fqn for placed in walk_components(scene)]


def cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([str(MORSEC), *args], cwd=cwd, capture_output=True, text=True, timeout=120)


# ---------------------------------------------------------------- builder twins of the example scenes

def test_the_tutorial_has_a_builder_twin():
    assert (SCENES / "tutorial.py", SCENES / "tutorial.yaml") in twins()


@pytest.mark.parametrize("script,scene", twins(), ids=lambda p: p.name)
def test_builder_twin_builds_byte_identical(script, scene, tmp_path, capsys):
    a = build_scene(script, tmp_path / "from_script")
    b = build_scene(scene, tmp_path / "from_scene")
    files_a = sorted(p.relative_to(a) for p in a.rglob("*") if p.is_file())
    files_b = sorted(p.relative_to(b) for p in b.rglob("*") if p.is_file())
    assert files_a == files_b
    for rel in files_a:
        assert (a / rel).read_bytes() == (b / rel).read_bytes(), f"{rel} differs between {script.name} and {scene.name}"
    assert "warning" not in capsys.readouterr().err, "an example twin should not need MORSE-only calls"


@pytest.mark.parametrize("script,scene", twins(), ids=lambda p: p.name)
def test_builder_twin_gives_equal_ir(script, scene):
    assert load(script).model_dump(mode="json") == load(scene).model_dump(mode="json")


# ---------------------------------------------------------------- the corpus of MORSE-style scripts

EXPECTED_NAMES = {
    "tutorial_atrv.py": (["robot"], ["robot.motion", "robot.pose"]),
    "renaming.py": (
        ["morsy", "mana", "dala", "robot4", "foo", "bar", "m"] + [f"m_{i:03d}" for i in range(1, 10)]
        + ["robot", "robot_001", "robot_002", "named", "named_001"],
        ["morsy.my_kuka", "morsy.my_kuka.my_pose", "mana.arm", "mana.arm.my_pose2", "dala.my_kuka",
         "dala.my_kuka.pose", "robot4.arm", "robot4.arm.pose", "foo.arm", "foo.arm.pose", "bar.arm", "bar.arm.pose",
         "m.arm", "m.arm.pose"] + [x for i in range(1, 10) for x in (f"m_{i:03d}.arm", f"m_{i:03d}.arm.pose")]),
    "loops.py": (
        ["explorer", "explorer_001", "explorer_002", "flock", "flock_001", "flock_002", "scout", "scout_001",
         "atrv", "atrv_001"],
        ["explorer.motion", "explorer_001.motion", "explorer_002.motion", "flock.pose", "flock_001.pose",
         "flock_002.pose"]),
    "sub_components.py": (
        ["carrier", "worker", "lifter"],
        ["carrier.platform", "carrier.platform.platform_pose", "carrier.odometry", "worker.platform",
         "worker.platform.platform_pose", "worker.odometry", "lifter.base_pose", "lifter.base_pose.mount",
         "lifter.base_pose.mount.tip"]),
    "properties_levels.py": (["robot"], ["robot.motion", "robot.raw", "robot.diff", "robot.integ", "robot.pose"]),
    "modifiers.py": (["robot"], ["robot.pose", "robot.ned_pose", "robot.utm_pose", "robot.odometry", "robot.teleport"]),
    "multinode.py": (["dala1", "dala2"], ["dala1.pose1", "dala2.pose2"]),
    "middleware.py": (["robot"], ["robot.pose", "robot.odometry", "robot.motion", "robot.teleport"]),
    "time_settings.py": (["robot"], ["robot.motion"]),
    "display_and_blender.py": (["robot"], ["robot.pose"]),
    "custom_component.py": (["robot"], ["robot.sensor", "robot.drive"]),
    "passive_objects.py": (["robot"], ["robot.pose"]),
    "robot_physics.py": (["heavy", "ghost", "statue", "phantom", "rigid"],
                         ["heavy.pose", "ghost.pose", "statue.pose", "phantom.pose", "rigid.pose"]),
}


def test_every_corpus_script_has_expected_names():
    assert sorted(p.name for p in SCRIPTS.glob("*.py")) == sorted(EXPECTED_NAMES)


@pytest.mark.parametrize("name", sorted(EXPECTED_NAMES))
def test_corpus_script_builds_with_morse_names(name, tmp_path):
    path = SCRIPTS / name
    out = build_scene(path, tmp_path / "build")
    manifest = json.loads((out / "manifest.json").read_text())
    robots, components = EXPECTED_NAMES[name]
    assert [r["name"] for r in manifest["robots"]] == robots
    assert [c["fqn"] for c in manifest["components"]] == components


def test_corpus_settings_reach_the_ir():
    scene = load(SCRIPTS / "properties_levels.py")
    comps = {c.name: c for c in scene.robots[0].components}
    assert comps["motion"].properties.ControlType == "Position"
    assert (comps["raw"].level, comps["raw"].frequency) == ("raw", 10.0)
    assert (comps["diff"].level, comps["diff"].frequency) == ("differential", 60.0)
    assert comps["integ"].profile is True
    assert scene.environment.properties == {"longitude": 1.26, "latitude": 43.26, "altitude": 130.0}

    scene = load(SCRIPTS / "modifiers.py")
    mods = {c.name: [m.model_dump() for m in c.modifiers] for c in scene.robots[0].components}
    assert mods["pose"] == [{"name": "noise", "pos_std": 0.1, "rot_std": 0.05}]
    assert mods["ned_pose"] == [{"name": "ned"}]
    assert mods["odometry"] == [{"name": "odometrynoise", "factor": 1.05}]
    assert scene.environment.seed == 42

    scene = load(SCRIPTS / "multinode.py")
    assert scene.environment.multinode.distribution == {"nodeA": ["dala1"], "nodeB": ["dala2"]}
    assert scene.environment.multinode.server_port == 65000

    scene = load(SCRIPTS / "time_settings.py")
    time = scene.environment.time
    assert (time.strategy, time.frequency, time.scale, time.relative, time.physics_substeps, time.auto_tune) == \
        ("fixed_step", 120.0, 2.0, True, 4, False)

    scene = load(SCRIPTS / "middleware.py")
    comps = {c.name: c for c in scene.robots[0].components}
    assert [(s.middleware, s.port, s.file) for s in comps["pose"].streams] == [("socket", 60500, None),
                                                                             ("text", None, "pose.txt")]
    assert comps["odometry"].streams[0].classpath == "morse.middleware.socket_datastream.SocketDatastreamManager"
    assert comps["odometry"].streams[0].method == "publish"
    assert comps["motion"].interfaces == ["socket"] and comps["motion"].services == ["socket"]
    assert comps["teleport"].services == ["socket"]
    assert scene.environment.services == ["socket"]
    assert scene.environment.stream_managers["socket"].time_sync is True
    assert scene.environment.stream_managers["socket"].sync_port == 12000

    scene = load(SCRIPTS / "robot_physics.py")
    robots = {r.name: r for r in scene.robots}
    assert (robots["heavy"].mass, robots["heavy"].friction, robots["heavy"].color) == (120.0, 0.8, [0.2, 0.2, 0.8])
    assert robots["ghost"].ghost == 0.4
    assert robots["statue"].physics_type == "static"
    assert robots["phantom"].collision is False
    assert robots["rigid"].physics_type == "rigid_body"
    assert all(r.default_interface == "socket" for r in scene.robots)


def test_custom_component_classpath_maps_to_the_catalogue():
    scene = load(SCRIPTS / "custom_component.py")
    sensor, drive = scene.robots[0].components
    assert (sensor.type, sensor.frequency) == ("pose", 20.0)
    assert (drive.type, drive.properties.ControlType) == ("motion_vw", "Velocity")


def test_passive_objects_sizes_are_twice_the_scale():
    scene = load(SCRIPTS / "passive_objects.py")
    objects = {o.name: o for o in scene.objects}
    assert (objects["table"].type, objects["table"].size) == ("box", [2.0, 1.0, 0.8])
    assert objects["table"].color == [0.6, 0.4, 0.2]
    assert objects["bottle"].properties == {"Object": True, "Graspable": True, "Label": "bottle"}
    assert (objects["ball"].dynamic, objects["ball"].mass, objects["ball"].color) == (True, 0.5, [1.0, 0.0, 0.0])
    zones = {z.name: z for z in scene.zones}
    assert zones["charging_zone"].size == [4.0, 4.0, 2.0]  # MORSE's Zone.size is the half-extent
    assert zones["danger"].size == [2.0, 2.0, 2.0]  # a unit Blender cube spans -1..1
    assert zones["danger"].properties == {"Level": 3}


# ---------------------------------------------------------------- recording rules

def test_translate_and_rotate_are_additive(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.translate(1.0, 2.0)
        robot.translate(x=0.5, z=0.25)
        robot.rotate(z=0.5)
        robot.rotate(0.1, 0.0, 0.25)
        pose = Pose()
        pose.location = (0.0, 0.0, 1.0)
        pose.translate(z=-0.5)
        robot.append(pose)
        env = Environment('empty')
    """)
    scene = load(path)
    robot = scene.robots[0]
    assert robot.translate == [1.5, 2.0, 0.25]
    assert robot.rotate == [0.1, 0.0, 0.75]
    assert robot.components[0].translate == [0.0, 0.0, 0.5]


def test_names_are_final_once_the_environment_exists(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        pose = Pose()
        robot.append(pose)
        other = ATRV('robot')
        before = robot.name
        env = Environment('empty')
        env.properties(names=",".join([before, robot.name, pose.name, other.name]))
    """)
    scene = load(path)
    assert scene.environment.properties["names"] == "robot,robot,robot.pose,robot_001"


def test_unnamed_components_are_named_after_their_type(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.append(Pose())
        robot.append(Pose())
        pose = Pose()
        robot.append(pose)
        env = Environment('empty')
    """)
    scene = load(path)
    assert [c.name for c in scene.robots[0].components] == ["pose_001", "pose_002", "pose"]


def test_time_and_camera_methods(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        env = Environment('empty', fastmode=True, auto_tune_time=False)
        env.set_time_scale(slowdown_by=4)
        env.set_time_strategy(TimeStrategies.BestEffort)
        env.set_camera_clip(clip_start=0.2, clip_end=50)
        env.set_camera_focal_length(50.0)
        env.set_camera_speed(3.0)
        env.set_gravity(3.71)
        env.set_auto_start(False)
        env.fullscreen(True)
        env.set_debug(True)
        env.set_viewport('WIREFRAME', clip_end=200)
    """)
    e = load(path).environment
    assert (e.fastmode, e.time.auto_tune, e.time.scale, e.time.strategy) == (True, False, 0.25, "best_effort")
    assert (e.camera.clip, e.camera.focal, e.camera.speed, e.gravity) == ([0.2, 50.0], 50.0, 3.0, 3.71)
    assert (e.auto_start, e.fullscreen, e.debug, e.viewport.shade, e.viewport.clip_end) == \
        (False, True, True, "WIREFRAME", 200.0)


def test_simulator_frequency_turns_auto_tuning_off(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        env = Environment('empty')
        env.simulator_frequency(100)
    """)
    time = load(path).environment.time
    assert (time.frequency, time.auto_tune) == (100.0, False)


def test_from_morsec_builder_works_under_morsec(tmp_path):
    path = write(tmp_path, """
        from morsec.builder import *
        robot = ATRV()
        motion = MotionVW()
        robot.append(motion)
        env = Environment('empty')
    """)
    assert fqns(load(path), path) == ["robot.motion"]


def test_morse_builder_submodules_resolve_to_the_builder_names(tmp_path):
    path = write(tmp_path, """
        import morse.builder
        from morse.builder.sensors import Pose
        from morse.builder.actuators import MotionVW
        from morse.builder.robots import ATRV
        from morse.builder.robots.morserobots import ATRV as ATRV2
        from morse.builder.creator import SensorCreator
        from morse.builder import Environment
        import morsec.builder
        assert issubclass(Pose, SensorCreator) and ATRV is ATRV2 is morsec.builder.ATRV
        robot = ATRV()
        robot.append(Pose())
        env = Environment('empty')
    """)
    assert fqns(load(path), path) == ["robot.pose"]
    # the same package outside morsec, in plain Python (the `morse` package ships beside `morsec`)
    import morse.builder.sensors
    assert morse.builder.sensors.Pose is morse.builder.Pose
    with pytest.raises(ImportError, match="no sensor 'NoSuchSensor' in morsec's catalogue"):
        morse.builder.sensors.NoSuchSensor  # noqa: B018


def test_project_components_appear_as_builder_classes(tmp_path):
    (tmp_path / "morsec.toml").write_text("[project]\n")
    folder = tmp_path / "components" / "sensors" / "lab_hygrometer"
    folder.mkdir(parents=True)
    (folder / "component.py").write_text(textwrap.dedent("""
        from morsec.component import ComponentProperties, DataField, Sensor

        class LabHygrometer(Sensor):
            \"\"\"Humidity at the sensor.\"\"\"
            short_descr = "Humidity"
            builder_name = "LabHygrometer"
            frequency = 4.0

            class Properties(ComponentProperties):
                range: float = 2.0

            data = (DataField("humidity", 0.5, "float", "relative humidity"),)

        COMPONENT = LabHygrometer
    """))
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        thermo = LabHygrometer()
        thermo.properties(range=5.0)
        thermo.add_stream('socket')
        robot.append(thermo)
        env = Environment('empty')
    """)
    scene = load(path)
    thermo = scene.robots[0].components[0]
    assert (thermo.name, thermo.type, thermo.properties.range, thermo.frequency) == ("thermo", "lab_hygrometer", 5.0, 4.0)


# ---------------------------------------------------------------- MORSE-only features: accepted, recorded, warned once

def test_morse_only_calls_are_recorded_and_warned_once(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.make_external()
        env = Environment('empty')
        env.set_material_mode('GLSL')
        env.set_material_mode('MULTITEXTURE')
        env.enable_mist()
        env.save()
    """)
    scene = load(path)
    err = capsys.readouterr().err
    assert err.count("set_material_mode") == 1
    assert "sim.py:5:1: warning: env.set_material_mode()" in err
    assert "sim.py:7:1: warning: env.enable_mist()" in err
    assert "sim.py:3:1: warning: ATRV.make_external()" in err
    only = scene.environment.morse_only
    assert only["set_material_mode"] == {"material_mode": "MULTITEXTURE"}
    assert only["enable_mist"] == {"enable": True}
    assert only["robot.make_external"] == {}
    assert "save" in only


def test_morse_only_settings_land_in_the_manifest(tmp_path, capsys):
    out = build_scene(SCRIPTS / "display_and_blender.py", tmp_path / "b")
    manifest = json.loads((out / "manifest.json").read_text())
    only = manifest["scene"]["environment"]["morse_only"]
    assert set(only) == {"set_material_mode", "set_horizon_color", "enable_mist", "use_vsync"}
    assert manifest["scene"]["environment"]["stereo"] == "NONE"  # set_stereo is a display setting
    assert only["set_horizon_color"] == {"color": [0.1, 0.2, 0.3]}


def test_blend_environment_is_morse_only(tmp_path, capsys):
    blend = tmp_path / "flat.blend"
    blend.write_bytes(b"BLENDER-v279")
    path = write(tmp_path, f"""
        from morse.builder import *
        robot = ATRV()
        env = Environment('{blend}')
    """)
    scene = load(path)
    assert scene.environment.name == "empty"
    assert scene.environment.morse_only["Environment"] == {"filename": str(blend)}
    assert "sim.py:3:7: warning: env.Environment()" in capsys.readouterr().err


def test_a_blend_environment_that_is_no_file_is_an_error(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        env = Environment('/somewhere/flat.blend')
    """)
    with pytest.raises(SceneError, match=r"sim.py:3:7: environment.name: unknown environment '/somewhere/flat'"):
        load(path)


# ---------------------------------------------------------------- errors: one line, the script's file:line

ERRORS = {
    "unknown_method": ("""
        from morse.builder import *
        robot = ATRV()
        robot.set_fooo(1)
        """, "sim.py:3:1: ATRV (robot) has no method or attribute 'set_fooo'"),
    "dotted_name": ("""
        from morse.builder import *
        robot = ATRV()
        robot.name = 'my.robot'
        """, "sim.py:3:1: invalid name 'my.robot': dots are not allowed"),
    "script_exception": ("""
        from morse.builder import *
        robot = ATRV()
        speed = 1 / 0
        """, "sim.py:3:9: ZeroDivisionError: division by zero"),
    "syntax_error": ("""
        from morse.builder import *
        robot = ATRV(
        """, "sim.py:2:13: Python syntax error"),
    "unknown_class": ("""
        from morse.builder import *
        robot = ATRV()
        motion = MotionVw()
        """, "sim.py:3:10: NameError: name 'MotionVw' is not defined; did you mean"),
    "binding_without_middleware": ("""
        from morse.builder import *
        robot = ATRV()
        motion = MotionVW()
        motion.configure_mw(['morse.middleware.zeromq_datastream.ZmqDatastreamManager', 'read', 'x'])
        robot.append(motion)
        """, "sim.py:4:1: configure_mw(['morse.middleware.zeromq_datastream.ZmqDatastreamManager', 'read', 'x']): "
             "no morsec middleware for classpath"),
    "unknown_middleware": ("""
        from morse.builder import *
        robot = ATRV()
        motion = MotionVW()
        motion.add_stream('zeromq')
        robot.append(motion)
        """, ("sim.py:4:1: robots[0].components[0].streams[0]", "'zeromq'", "'socket'")),
    "bad_property_value": ("""
        from morse.builder import *
        robot = ATRV()
        motion = MotionVW()
        motion.properties(ControlType='Sideways')
        robot.append(motion)
        """, ("sim.py:4:1: robots[0].components[0].properties.ControlType", "'Sideways'")),
    "unknown_environment": ("""
        from morse.builder import *
        robot = ATRV()
        env = Environment('emty')
        """, ("sim.py:3:7: environment.name", "'emty'")),
    "unappended_sensor": ("""
        from morse.builder import *
        robot = ATRV()
        pose = Pose()
        env = Environment('empty')
        """, "sim.py:3:8: Pose is not appended to a robot"),
    "append_robot": ("""
        from morse.builder import *
        robot = ATRV()
        other = ATRV()
        robot.append(other)
        """, "sim.py:4:1: ATRV.append(ATRV): only sensors and actuators can be appended"),
    "time_scale": ("""
        from morse.builder import *
        env = Environment('empty')
        env.set_time_scale(slowdown_by=2, accelerate_by=2)
        """, "sim.py:3:1: set_time_scale(): give exactly one of"),
    "two_environments": ("""
        from morse.builder import *
        env = Environment('empty')
        env2 = Environment('empty')
        """, "sim.py:3:8: only one Environment per scene (the first one is at line 2)"),
    "unknown_classpath": ("""
        from morse.builder import *
        class Foo(SensorCreator):
            _classpath = 'mysim.sensors.foo.Foo'
        robot = ATRV()
        foo = Foo()
        """, "sim.py:5:7: Foo: _classpath 'mysim.sensors.foo.Foo' names no component of the catalogue"),
    "passive_object": ("""
        from morse.builder import *
        chair = PassiveObject('props/objects', 'Chair')
        """, "sim.py:2:9: PassiveObject('props/objects', 'Chair'): no catalogue prop by that name"),
    "morse_core": ("""
        from morse.core.wheeled_robot import MorsePhysicsRobot
        """, "sim.py:1:1: ModuleNotFoundError: No module named 'morse.core.wheeled_robot'"),
    "multinode_unknown_robot": ("""
        from morse.builder import *
        robot = ATRV()
        env = Environment('empty')
        env.configure_multinode(distribution={'nodeA': ['robot', 'nobody']})
        """, ("sim.py:4:1: environment.multinode.distribution.nodeA[1]", "'nobody'")),
    "multinode_unassigned_robot": ("""
        from morse.builder import *
        dala1 = ATRV()
        dala2 = ATRV()
        env = Environment('empty')
        env.configure_multinode(distribution={'nodeA': [dala1.name]})
        """, "sim.py:5:1: environment.multinode.distribution: robot 'dala2' is on no node"),
    "multinode_hla": ("""
        from morse.builder import *
        dala1 = ATRV()
        env = Environment('empty')
        env.configure_multinode(protocol='hla', server_port=60400, distribution={'nodeA': [dala1.name]})
        """, ("sim.py:4:1: environment.multinode.protocol: protocol 'hla' needs an HLA run-time infrastructure",
              "use protocol 'socket'")),
}


@pytest.mark.parametrize("case", sorted(ERRORS))
def test_errors_name_the_script_line(case, tmp_path, capsys):
    body, expected = ERRORS[case]
    path = write(tmp_path, body)
    with pytest.raises(MorsecError) as info:
        load(path)
    assert str(info.value).startswith(str(tmp_path)), str(info.value)
    message = str(info.value).replace(str(tmp_path) + os.sep, "")
    prefix, *fragments = (expected,) if isinstance(expected, str) else expected
    assert message.startswith(prefix), message
    assert all(fragment in message for fragment in fragments), message
    assert "\n" not in message


def test_passive_object_lists_searched_folders_and_finds_blend_assets(tmp_path, monkeypatch):
    assets = tmp_path / "assets"
    (assets / "props").mkdir(parents=True)
    (assets / "props" / "chairs.blend").write_bytes(b"BLENDER")
    monkeypatch.setenv("MORSE_RESOURCE_PATH", str(assets))
    missing = write(tmp_path, """
        from morse.builder import *
        table = PassiveObject('props/tables')
    """, "missing.py")
    with pytest.raises(SceneError, match=r"searched .*assets.*(add folders with MORSE_RESOURCE_PATH)"):
        load(missing)
    found = write(tmp_path, """
        from morse.builder import *
        chair = PassiveObject('props/chairs', 'Chair')
    """, "found.py")
    with pytest.raises(SceneError, match=r"found .*chairs.blend: import it first, `morsec import-blend .*chairs.blend "
                                         r"--kind props`, then PassiveObject\('props/chairs', 'Chair'\)"):
        load(found)
    catalogue_prop = write(tmp_path, """
        from morse.builder import *
        crate = PassiveObject('props/basic', 'box')
        crate.size = [0.4, 0.4, 0.4]
    """, "prop.py")
    obj = load(catalogue_prop).objects[0]
    assert (obj.name, obj.type, obj.size) == ("crate", "box", [0.4, 0.4, 0.4])


def test_cli_error_is_one_line_exit_2(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.set_fooo(1)
    """)
    result = cli("build", str(path), "-o", str(tmp_path / "b"))
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert result.stderr.strip().splitlines() == [f"error: {path}:3:1: ATRV (robot) has no method or attribute "
                                                  "'set_fooo'; did you mean one of 'set_color', 'set_friction'?"]


# ---------------------------------------------------------------- plain Python: python mysim.py [-- morsec args]

STANDALONE = """
    from morsec.builder import *
    robot = ATRV()
    pose = Pose()
    pose.add_stream('socket')
    robot.append(pose)
    env = Environment('empty')
    print("script ran")
"""


def run_python(script: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "MORSE_RESOURCE_PATH"}
    return subprocess.run([sys.executable, str(script), *args], cwd=script.parent, capture_output=True, text=True,
                          timeout=120, env=env)


def test_morsec_args():
    assert morsec_args([], "s.py") == ["build", "s.py"]
    assert morsec_args(["--", "-o", "out"], "s.py") == ["build", "s.py", "-o", "out"]
    assert morsec_args(["x", "--", "run", "--duration", "1"], "s.py") == ["run", "s.py", "--duration", "1"]


def test_plain_python_builds(tmp_path):
    script = write(tmp_path, STANDALONE + "    env.create()\n")
    result = run_python(script)
    assert result.returncode == 0, result.stderr
    assert result.stdout.count("script ran") == 1
    reference = build_scene(script, tmp_path / "reference")
    for name in ("scene.xml", "manifest.json", "middleware.json", "robots/robot.urdf"):
        assert (tmp_path / "build" / "sim" / name).read_bytes() == (reference / name).read_bytes()


def test_plain_python_passes_morsec_arguments(tmp_path):
    script = write(tmp_path, STANDALONE + "    env.create()\n")
    result = run_python(script, "--", "-o", "elsewhere")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "elsewhere" / "manifest.json").is_file()
    result = run_python(script, "--", "check")
    assert (result.returncode, result.stdout.strip().splitlines()[-1]) == (0, f"ok: {script}")


def test_plain_python_without_create_builds_at_exit(tmp_path):
    script = write(tmp_path, STANDALONE)
    result = run_python(script)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "build" / "sim" / "manifest.json").is_file()


def test_plain_python_error_is_one_line(tmp_path):
    script = write(tmp_path, """
        from morsec.builder import *
        robot = ATRV()
        pose = Pose()
        env = Environment('empty')
        env.create()
    """)
    result = run_python(script)
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert result.stderr.strip() == f"error: {script}:3:8: Pose is not appended to a robot: call robot.append(...) " \
                                    "(or append it to a FakeRobot())"


def test_plain_python_runs(tmp_path):
    script = write(tmp_path, STANDALONE + "    env.create()\n")
    result = run_python(script, "--", "run", "--duration", "0.1", "--time-strategy", "fixed_step")
    assert result.returncode == 0, result.stderr
    assert "robot.pose" in result.stdout and "EXITING SIMULATION" in result.stdout


def test_recording_from_python_code():
    from morsec.builder import recording
    from morsec.scene import validate_scene
    with recording() as session:
        from morsec.builder import ATRV, Cube, Environment, Pose
        rover = ATRV()
        rover.append(Pose())
        box = Cube()
        box.scale = 0.5
        env = Environment('empty')
    scene = validate_scene(*session.scene_data(), session.catalogue)
    assert [r.name for r in scene.robots] == ["rover"]
    assert [(o.name, o.size) for o in scene.objects] == [("box", [1.0, 1.0, 1.0])]
    del rover, box, env


def test_basic_mesh_sizes(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        unit = Cube()
        flat = Cube('slab')
        flat.scale = (2.0, 1.0, 0.05)
        ball = Sphere()
        ball.size = [0.3, 0.3, 0.3]
        prop = PassiveObject('box')
        big_prop = PassiveObject('props/basic', 'box')
        big_prop.scale = (2.0, 2.0, 2.0)
        env = Environment('empty')
    """)
    objects = {o.name: o for o in load(path).objects}
    assert objects["unit"].size == [2.0, 2.0, 2.0]  # a Blender cube spans -1..1
    assert objects["slab"].size == [4.0, 2.0, 0.1]
    assert objects["ball"].size == [0.3, 0.3, 0.3]  # size: full extent, as in the IR
    assert objects["prop"].size == [0.5, 0.5, 0.5]  # a catalogue prop keeps its default size
    assert objects["big_prop"].size == [1.0, 1.0, 1.0]  # ... and scale multiplies it


def test_overlays_interfaces_and_bindings(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        motion = KukaLWR()
        motion.add_overlay('ros', 'morse.middleware.ros.overlays.armatures.ArmatureController', namespace='/arm')
        motion.configure_overlay('ros', 'morse.middleware.ros.overlays.armatures.ArmatureController')
        motion.add_interface('socket', port=61000)
        robot.append(motion)
        pose = Pose()
        pose.add_stream(['morse.middleware.text_datastream.TextDatastreamManager', 'write', 'x/y'])
        pose.alter(classpath='morse.modifiers.pose_noise.PoseNoiseModifier', pos_std=0.2)
        pose.configure_modifier('NED')
        robot.append(pose)
        env = Environment('empty')
    """)
    motion, pose = load(path).robots[0].components
    assert [o.model_dump() for o in motion.overlays] == [
        {"middleware": "ros", "overlay": "morse.middleware.ros.overlays.armatures.ArmatureController",
         "namespace": "/arm"},
        {"middleware": "ros", "overlay": "morse.middleware.ros.overlays.armatures.ArmatureController"}]
    assert motion.interfaces == ["socket"] and motion.services == ["socket"]
    assert [(s.middleware, s.port) for s in motion.streams] == [("socket", 61000)]
    assert [(s.middleware, s.classpath, s.method, s.path) for s in pose.streams] == [
        ("text", "morse.middleware.text_datastream.TextDatastreamManager", "write", "x/y")]
    assert [m.model_dump() for m in pose.modifiers] == [{"name": "posenoise", "pos_std": 0.2}, {"name": "ned"}]
