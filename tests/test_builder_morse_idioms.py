"""Builder scripts as MORSE ran them: what `from morse.builder import *` gave besides the classes (math,
bpymorse ...), game properties a component does not declare (tags), the Blender object behind a builder
object (`_bpy_object.game.lock_location_z`), `bpymorse.get_object`, `Environment.add_interface`, and an
unknown `morse.builder.robots.X`."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from morsec.app.project import build_scene
from morsec.component.catalogue import load_catalogue
from morsec.errors import MorsecError, SceneError
from morsec.frontends import load_scene
from morsec.frontends.builder import (
    MORSE_MODULE_NAMES,
    UnknownBuilderName,
    builder_attribute,
    builder_names,
    catalogue_classes,
)
from morsec.testing import simulate

MORSEC = Path(sys.executable).parent / "morsec"


def write(tmp_path: Path, body: str, name: str = "sim.py") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(body).lstrip("\n"), encoding="utf-8")
    return path


def load(path: Path, **kwargs):
    return load_scene(path, load_catalogue(path.parent), **kwargs)


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(MORSEC), *args], capture_output=True, text=True, timeout=120)


def located(err: BaseException, tmp_path: Path) -> str:
    return str(err).replace(str(tmp_path) + os.sep, "")


# ---------------------------------------------------------------- what `from morse.builder import *` gave

def test_star_import_gives_the_modules_morse_gave(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.rotate(z=math.pi / 2)
        robot.translate(x=float(os.environ.get('NOT_SET_ANYWHERE', '1.5')))
        logger.info("%s %s %s", sys.argv, json.dumps([1]), pprint.pformat({}))
        logging.getLogger("mine").debug("ok")
        assert bpymorse.version() == (0, 0, 0)
        env = Environment('empty')
        env.set_time_strategy(TimeStrategies.FixedSimulationStep)
    """)
    robot = load(path).robots[0]
    assert robot.rotate[2] == pytest.approx(1.5707963)
    assert robot.translate[0] == 1.5
    assert {"math", "os", "sys", "json", "logging", "pprint", "logger", "bpymorse"} == set(MORSE_MODULE_NAMES)
    assert set(MORSE_MODULE_NAMES) <= set(builder_names())


def test_public_builder_star_import_gives_them_too():
    namespace: dict = {}
    exec("from morsec.builder import *", namespace)
    assert namespace["math"].pi > 3 and namespace["bpymorse"].__name__.endswith("bpymorse")
    assert "ATRV" in namespace and "TimeStrategies" in namespace


# ---------------------------------------------------------------- Environment.add_interface

def test_environment_add_interface_exposes_the_supervision_services(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        env = Environment('empty', fastmode=True)
        env.add_interface('socket')
        env.add_interface('socket', port=4321)
    """)
    env = load(path).environment
    assert env.services == ["socket"]
    assert env.morse_only["add_interface"] == {"datastream": "socket", "port": 4321}
    err = capsys.readouterr().err
    assert "sim.py:5:1: warning: env.add_interface() (stream options) has no effect" in err
    assert "sim.py:4" not in err


# ---------------------------------------------------------------- properties a type does not declare: tags

def test_undeclared_properties_are_tags_with_a_warning(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        dala = ATRV()
        dala.properties(obstacle=1, GroundRobot=True)
        baro = Barometer()
        baro.properties(DischargingRate=10.0, ReferencePressure=101000.0)
        dala.append(baro)
        motion = MotionVW()
        motion.properties(ControlTyp='Position')
        dala.append(motion)
        env = Environment('empty')
    """)
    scene = load(path)
    robot = scene.robots[0]
    assert robot.tags == {"obstacle": 1} and robot.properties.GroundRobot is True
    baro, motion = robot.components
    assert baro.tags == {"DischargingRate": 10.0} and baro.properties.ReferencePressure == 101000.0
    assert motion.tags == {"ControlTyp": "Position"} and motion.properties.ControlType == "Velocity"
    lines = [line.replace(str(tmp_path) + os.sep, "") for line in capsys.readouterr().err.splitlines()]
    assert lines[0].startswith("sim.py:3:1: warning: dala.properties(obstacle=...): robot type 'atrv' has no "
                               "property 'obstacle'; kept as a tag")
    assert lines[1].startswith("sim.py:5:1: warning: baro.properties(DischargingRate=...): sensor type "
                               "'barometer' has no property 'DischargingRate'")
    assert lines[2].startswith("sim.py:8:1: warning: motion.properties(ControlTyp=...)")
    assert lines[2].endswith("did you mean 'ControlType'?")
    assert len(lines) == 3


def test_strict_check_makes_warnings_errors(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.properties(obstacle=1)
        robot.make_external()
        env = Environment('empty')
    """)
    assert load(path).robots[0].tags == {"obstacle": 1}
    with pytest.raises(SceneError) as info:
        load(path, strict=True)
    assert located(info.value, tmp_path).startswith("sim.py:3:1: robot.properties(obstacle=...)")
    assert "(--strict: warnings are errors; 1 more warning)" in str(info.value)
    lenient = cli("check", str(path))
    assert lenient.returncode == 0 and "warning" in lenient.stderr
    strict = cli("check", "--strict", str(path))
    assert strict.returncode == 2
    assert strict.stderr.strip().splitlines() == [f"error: {path}:3:1: {str(info.value).split(': ', 1)[1]}"]


def test_yaml_states_tags_and_keeps_strict_properties(tmp_path):
    good = tmp_path / "good.yaml"
    good.write_text(textwrap.dedent("""
        robots:
        - name: dala
          type: atrv
          tags: {obstacle: 1}
          components:
          - {name: baro, type: barometer, tags: {DischargingRate: 10.0}}
    """))
    robot = load(good).robots[0]
    assert robot.tags == {"obstacle": 1} and robot.components[0].tags == {"DischargingRate": 10.0}
    typo = tmp_path / "typo.yaml"
    typo.write_text("robots:\n- type: atrv\n  properties: {obstacle: 1}\n")
    with pytest.raises(SceneError, match=r"typo.yaml:3:16: robots\[0\]\.properties\.obstacle: unknown property"):
        load(typo)
    declared = tmp_path / "declared.yaml"
    declared.write_text("robots:\n- type: atrv\n  components:\n  - {type: proximity, tags: {Range: 3.0}}\n")
    with pytest.raises(SceneError, match=r"declared.yaml:4:37: robots\[0\]\.components\[0\]\.tags\.Range: 'Range' "
                                         r"is a property of sensor type 'proximity': set it under 'properties'"):
        load(declared)


def test_builder_tags_convert_to_yaml_tags(tmp_path, capsys):
    from morsec.app.convert import convert_scene
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.properties(obstacle=1)
        robot._bpy_object.game.lock_location_z = True
    """)
    out = tmp_path / "sim.yaml"
    convert_scene(path, out)
    text = out.read_text()
    assert "tags: {obstacle: 1}" in text and "locks: [location_z]" in text
    assert load(out).model_dump(mode="json") == load(path).model_dump(mode="json")


SENSING = """
robots:
- name: seeker
  type: atrv
  components:
  - {name: prox, type: proximity, properties: {Track: Catch_me, Range: 10.0}}
  - {name: beacon, type: pose, tags: {Catch_me: true}}
- name: target
  type: atrv
  translate: [3, 0, 0]
  tags: {Catch_me: true}
  components:
  - {name: beacon, type: pose, translate: [0, 1, 0], tags: {Catch_me: true}}
- name: bystander
  type: atrv
  translate: [0, 3, 0]
"""


def test_tags_are_what_sensors_read(tmp_path):
    with simulate(SENSING, tmp_path) as sim:
        sim.run_for(0.5)
        near = sim.data("seeker.prox")["near_objects"]
    assert sorted(near) == ["target", "target.beacon"]  # not its own beacon, not the untagged robot
    assert near["target"] == pytest.approx(3.0, abs=0.05)


# ---------------------------------------------------------------- the Blender object behind a builder object

def test_lock_flags_become_locks(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot.translate(z=1.0)
        robot._bpy_object.game.lock_location_z = True
        robot._bpy_object.game.lock_rotation_x = True
        robot._bpy_object.game.lock_rotation_y = True
        robot._bpy_object.game.lock_rotation_x = False
        assert robot._bpy_object.game.lock_location_z and not robot._bpy_object.game.lock_rotation_x
        crate = Cube()
        crate.set_dynamic()
        crate._bpy_object.game.lock_rotation_z = True
        pose = Pose()
        robot.append(pose)
        pose._bpy_object.game.lock_location_x = True
    """)
    scene = load(path)
    assert scene.robots[0].locks == ["location_z", "rotation_y"]
    assert scene.objects[0].locks == ["rotation_z"]
    assert scene.environment.morse_only == {"robot.pose._bpy_object.game.lock_location_x": True}
    err = capsys.readouterr().err
    assert "sim.py:14:1: warning: pose._bpy_object.game.lock_location_x = True locks only robots and passive " \
           "objects in morsec" in err
    assert err.count("warning") == 1


def test_blender_game_settings_map_to_the_builder(tmp_path):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        robot._bpy_object.game.physics_type = 'STATIC'
        robot._bpy_object.game.mass = 42.0
        robot._bpy_object.location = [1.0, 2.0, 0.0]
        assert robot._bpy_object.name == 'robot' or robot._bpy_object.name == 'atrv'
    """)
    robot = load(path).robots[0]
    assert (robot.physics_type, robot.mass, robot.translate) == ("static", 42.0, [1.0, 2.0, 0.0])


LOCKED = """
robots:
- {name: floating, type: atrv, translate: [0, 0, 1], locks: [location_z]}
- {name: falling, type: atrv, translate: [0, 5, 1]}
objects:
- {name: crate, type: box, translate: [3, 0, 2], dynamic: true, locks: [location_z, rotation_x, rotation_y]}
"""


def test_locked_bodies_hold_their_axis(tmp_path):
    with simulate(LOCKED, tmp_path) as sim:
        start = sim.body_pose("floating")[0][2]
        sim.run_for(1.0)
        assert sim.body_pose("floating")[0][2] == pytest.approx(start, abs=1e-3)
        assert sim.body_pose("falling")[0][2] < 0.5
        assert sim.body_pose("crate")[0][2] == pytest.approx(2.0, abs=1e-3)
    xml = (tmp_path / "build-scene" / "scene.xml").read_text()
    assert '<velocity name="floating/lock_location_z" site="floating/centre_of_mass" refsite="morsec_world" gear="0 0 1 0 0 0"' in xml
    assert 'name="crate/lock_rotation_y"' in xml and "falling/lock" not in xml


def test_scene_without_locks_has_no_world_site(tmp_path):
    path = tmp_path / "plain.yaml"
    path.write_text("robots:\n- {type: atrv}\n")
    out = build_scene(path, tmp_path / "b")
    assert "morsec_world" not in (out / "scene.xml").read_text()


def test_bpymorse_get_object_and_properties(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        dala = ATRV()
        dala.name = 'dala'
        camera = SemanticCamera()
        dala.append(camera)
        env = Environment('indoors-1/boxes')
        bpymorse.properties(bpymorse.get_object('dala'), Catch_me=True)
        bpymorse.properties(bpymorse.get_object('dala.camera'), tag='Box')
        ground = bpymorse.get_object('Ground')
        ground.game.use_actor = True
        box = bpymorse.get_object('RedBox')
        bpymorse.properties(box, Type="Box")
        bpymorse.get_context_scene().game_settings.fps = 120
        assert bpymorse.get_properties(dala) == {'Catch_me': True}
    """)
    scene = load(path)
    robot = scene.robots[0]
    assert robot.tags == {"Catch_me": True} and robot.components[0].properties.tag == "Box"
    only = scene.environment.morse_only
    assert only["Ground.game.use_actor"] is True
    assert only["bpymorse.get_context_scene().game_settings.fps"] == 120
    # RedBox is an object of the environment (indoors-1/boxes): the script's to set, as in MORSE
    assert "RedBox.properties" not in only
    [red] = [o for o in scene.objects if o.name == "RedBox"]
    assert red.properties == {"Object": "RedBox", "Type": "Box"} and red.translate == [-7.5, 0.0, 0.965]
    assert [o.name for o in scene.objects].count("RedBox") == 1
    err = capsys.readouterr().err.replace(str(tmp_path) + os.sep, "")
    assert "sim.py:10:1: warning: bpymorse.get_object('Ground').game.use_actor = True: 'Ground' is an object of " \
           "MORSE's Blender environment file, which morsec does not load" in err
    assert "RedBox" not in err
    assert "sim.py:13:1: warning: bpymorse.get_context_scene()" in err


def test_laser_arc_is_morse_only(tmp_path, capsys):
    path = write(tmp_path, """
        from morse.builder import *
        robot = ATRV()
        sick = Sick()
        sick.create_laser_arc()
        robot.append(sick)
    """)
    assert "robot.sick.create_laser_arc" in load(path).environment.morse_only
    assert "sim.py:4:1: warning: Sick.create_laser_arc() draws the scan arc" in capsys.readouterr().err


# ---------------------------------------------------------------- morse.builder.robots.X that morsec lacks

def test_builder_attribute_resolves_and_names_what_is_missing():
    robots = "morse.builder.robots"
    assert builder_attribute(robots, "ATRV") is catalogue_classes(load_catalogue())["ATRV"]
    assert builder_attribute("morse.builder", "math").pi > 3
    assert builder_attribute("morse.builder.bpymorse", "get_object").__name__ == "get_object"
    with pytest.raises(UnknownBuilderName, match=r"no robot 'Pioneer3DXX' in morsec's catalogue "
                                                 r"\(from morse.builder.robots\); did you mean 'Pioneer3DX'\?"):
        builder_attribute(robots, "Pioneer3DXX")
    with pytest.raises(UnknownBuilderName, match=r"no sensor 'Posee' .*did you mean 'Pose'\?"):
        builder_attribute("morse.builder.sensors", "Posee")
    with pytest.raises(ImportError):  # `try: from morse.builder.robots import X / except ImportError:` works
        builder_attribute(robots, "NoSuchRobot")
    with pytest.raises(AttributeError):  # not a class name: the import system's probes, submodules
        builder_attribute(robots, "morserobots")


@pytest.mark.parametrize("body,line", [
    ("from morse.builder.robots import Pioneer3DXX\n", 1),
    ("import morse.builder.robots\nrobot = morse.builder.robots.Pioneer3DXX()\n", 2),
])
def test_unknown_robot_class_is_one_located_line(tmp_path, body, line):
    path = write(tmp_path, body)
    with pytest.raises(MorsecError) as info:
        load(path)
    message = located(info.value, tmp_path)
    assert message.startswith(f"sim.py:{line}:"), message
    assert "'Pioneer3DXX'" in message and "did you mean 'Pioneer3DX'?" in message
    assert "not callable" not in message and "\n" not in message
