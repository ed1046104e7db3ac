"""A MORSE lab's own components, written in MORSE's component API, in a folder laid out by `morse create`
(tests/fixtures/labsim: default.py, scripts/, src/labsim/{sensors,actuators,builder}), run unchanged: their
builder classes name them by `_classpath`, and what they stream equals what morsec's built-in equivalents stream
on the same scene (a pose, a thermometer finding objects' `Fire` tags with getVectTo, an odometry at two levels
and another frequency, a (v, w) actuator with an asynchronous, interruptible service). Real MuJoCo, real sockets,
real `morsec` processes."""

from __future__ import annotations

import math
import shutil
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from morsec.app.project import build_scene
from morsec.runtime.simulation import RunOptions, Simulation
from morsec.testing import Harness
from tests import test_ros
from tests.runtime_helpers import Morsec

# test_ros's fixtures: `ros_master` (a roscore), `ros_simulate` (a morsec run on it)
ros_master, ros_simulate = test_ros.ros_master, test_ros.simulate

FIXTURE = Path(__file__).parent / "fixtures" / "labsim"
MORSEC = Path(sys.executable).with_name("morsec")
TOLERANCE = 1e-6
# each of the lab's sensors, and morsec's built-in equivalent at the same place on the same robot (default.py)
PAIRS = {"robot.lab_pose": "robot.pose", "robot.lab_thermometer": "robot.thermometer",
         "robot.lab_odometry": "robot.odometry", "robot.lab_deltas": "robot.deltas"}


@pytest.fixture
def labsim(tmp_path) -> Path:
    folder = tmp_path / "labsim"
    shutil.copytree(FIXTURE, folder)
    return folder


def simulation(source: Path, build: Path) -> Harness:
    return Harness(Simulation(build_scene(source, build), RunOptions(strategy="fixed_step", service_port=0,
                                                                      port_base=0)))


def differences(one: dict, other: dict) -> dict[str, float]:
    assert list(one) == list(other), f"not the same fields: {list(one)} and {list(other)}"
    return {key: abs(one[key] - other[key]) for key in one}


def test_the_labs_sensors_stream_what_morsecs_builtin_ones_stream(labsim, tmp_path):
    """4 s of driving past a fire, a second fire lit by the lab's Igniter (a game property written), levels,
    a frequency and properties set by the builder script: every field of every message equal within 1e-6."""
    sim = simulation(labsim, tmp_path / "build")
    try:
        client = sim.client()
        sim.command("robot.motion", v=1.0, w=-0.3)
        worst: dict[tuple[str, str], float] = {}
        seen = {fqn: [] for pair in PAIRS.items() for fqn in pair}
        for frame in range(240):
            sim.step()
            if frame == 120:
                assert client.call("robot.igniter", "ignite", "stove") == ["campfire", "stove"]
            for lab, builtin in PAIRS.items():
                lab_data, builtin_data = sim.data(lab), sim.data(builtin)
                seen[lab].append(lab_data)
                for key, gap in differences(lab_data, builtin_data).items():
                    worst[(lab, key)] = max(worst.get((lab, key), 0.0), gap)
        assert max(worst.values()) <= TOLERANCE, sorted(worst.items(), key=lambda kv: -kv[1])[:5]
        # the comparison compared something: the robot went, the fires warmed, the levels are the builder's
        pose = seen["robot.lab_pose"]
        assert math.dist((pose[0]["x"], pose[0]["y"]), (pose[-1]["x"], pose[-1]["y"])) > 2.5
        temperatures = [m["temperature"] for m in seen["robot.lab_thermometer"]]
        assert temperatures[0] > 15.5 and temperatures[125] - temperatures[119] > 1.0
        assert set(seen["robot.lab_odometry"][-1]) == {"timestamp", "x", "y", "z", "yaw", "pitch", "roll", "vx", "vy",
                                                       "vz", "wz", "wy", "wx"}
        assert set(seen["robot.lab_deltas"][-1]) == {"timestamp", "dx", "dy", "dz", "dyaw", "dpitch", "droll"}
        assert sim.sim.component("robot.lab_odometry").schedule.period == pytest.approx(1 / 30)
        assert sim.component("robot.lab_thermometer")._alpha == 0.3  # properties(Alpha=0.3), under its Python name
    finally:
        sim.sim.close()


DRIVE = """\
from morse.builder import *
{imports}
robot = ATRV()
robot.translate(-1.0, 2.0, 0.0)
pose = Pose()
robot.append(pose)
motion = {motion}()
motion.properties(ControlType={control!r})
robot.append(motion)
robot.add_default_interface("socket")
env = Environment("empty")
env.set_time_strategy(TimeStrategies.FixedSimulationStep)
"""


def drive_scripts(folder: Path, control: str) -> tuple[Path, Path]:
    lab = folder / f"drive_lab_{control}.py"
    lab.write_text(DRIVE.format(imports="from labsim.builder.actuators import LabMotion", motion="LabMotion",
                                control=control), encoding="utf-8")
    builtin = folder / f"drive_builtin_{control}.py"
    builtin.write_text(DRIVE.format(imports="", motion="MotionVW", control=control), encoding="utf-8")
    return lab, builtin


@pytest.mark.parametrize("control", ["Velocity", "Position"])
def test_the_labs_motion_actuator_drives_as_motion_vw(labsim, tmp_path, control):
    """The same commands on the lab's actuator (robot_parent.apply_speed) and on MotionVW: the robot's pose
    stream the same, frame by frame, within 1e-6."""
    lab_script, builtin_script = drive_scripts(labsim, control)
    poses = []
    for script in (lab_script, builtin_script):
        sim = simulation(script, tmp_path / script.stem)
        try:
            track = []
            for v, w, frames in ((1.0, 0.0, 60), (0.8, 0.6, 90), (0.0, -1.0, 30), (0.5, 0.2, 60)):
                sim.command("robot.motion", v=v, w=w)
                for _ in range(frames):
                    sim.step()
                    track.append(sim.data("robot.pose"))
            poses.append(track)
        finally:
            sim.sim.close()
    lab, builtin = poses
    # two simulations: their clocks started at two wall-clock times, their timestamps from there
    start = lab[0]["timestamp"] - builtin[0]["timestamp"]
    for message in builtin:
        message["timestamp"] += start
    worst = max(max(differences(a, b).values()) for a, b in zip(lab, builtin, strict=True))
    assert worst <= TOLERANCE
    assert math.dist((lab[0]["x"], lab[0]["y"]), (lab[-1]["x"], lab[-1]["y"])) > 1.5
    assert abs(lab[-1]["yaw"] - lab[0]["yaw"]) > 0.3


def test_a_morse_simulation_folder_runs_with_its_services_on_the_socket(labsim, tmp_path):
    """`morsec run labsim` (the folder, as `morse run labsim`); the lab's actuator's services over the socket:
    a synchronous one, an asynchronous one answered when done, one preempted by the next (interruptible), a
    failure's message; its sensors' streams read by a client."""
    lab_script, _ = drive_scripts(labsim, "Velocity")
    folder = subprocess.run([str(MORSEC), "run", "labsim", "--duration", "0.5", "--port-base", "0",
                             "--service-port", "0"], cwd=labsim.parent, capture_output=True, text=True, timeout=120)
    assert folder.returncode == 0, folder.stderr
    assert "robot.lab_thermometer" in folder.stdout and "EXITING SIMULATION" in folder.stdout
    with Morsec(lab_script, tmp_path) as sim:
        client = sim.client()
        assert client.ok("robot.motion", "set_speed", 0.5, 0.0) is None
        assert client.ok("robot.motion", "get_properties")["ControlType"] == "Velocity"
        covered = client.ok("robot.motion", "move", 1.0, 0.0, 1.0)
        assert 0.8 < covered < 1.2  # a second at 1 m/s
        first = client.send_request("robot.motion", "move", 1.0, 0.0, 30.0)
        second = client.send_request("robot.motion", "move", 0.0, 0.5, 0.5)
        answers = {}
        while len(answers) < 2:
            rid, status, result = client.response()
            answers[rid] = (status, result)
        assert answers[first][0] == "PREEMPTED"
        assert answers[second][0] == "SUCCESS"
        status, message = client.call("robot.motion", "move", 1.0, 0.0, -1.0)
        assert (status, message) == ("FAILED", "the duration must be positive")
        stream = sim.stream("robot.pose")
        import json
        assert set(json.loads(stream.line())) == {"timestamp", "x", "y", "z", "yaw", "pitch", "roll"}


TEXT_AND_SOCKET = """\
from morse.builder import *
from labsim.builder.sensors import Heading, LabPose, LabThermometer
robot = ATRV()
robot.translate(2.0, 0.0, 0.0)
robot.rotate(z=0.5)
heading = Heading()
heading.add_stream("socket")
robot.append(heading)
lab_pose = LabPose()
robot.append(lab_pose)
lab_pose.add_stream("text")
lab_pose.add_stream("socket")
thermo = LabThermometer()
thermo.properties(DefaultTemperature=21.5)
robot.append(thermo)
thermo.add_stream("text")
thermo.add_service("socket")
env = Environment("empty")
"""


def test_the_labs_sensors_stream_on_text_and_socket(labsim, tmp_path):
    script = labsim / "streams.py"
    script.write_text(TEXT_AND_SOCKET, encoding="utf-8")
    with Morsec(script, tmp_path, strategy="fixed_step") as sim:
        import json
        message = json.loads(sim.stream("robot.lab_pose").line())
        assert message["x"] == pytest.approx(2.0, abs=1e-6)
        heading = json.loads(sim.stream("robot.heading").line())["heading"]  # a Blender Vector, as a list
        assert heading == pytest.approx([math.cos(0.5), math.sin(0.5), 0.0], abs=1e-4)
        assert sim.client().ok("robot.thermo", "get_local_data")["temperature"] == 21.5
        files = dict(sim.text_files)
    written = (tmp_path / files["robot.thermo"]).read_text(encoding="utf-8")
    assert "temperature = 21.5" in written
    assert "x = 2.0" in (tmp_path / files["robot.lab_pose"]).read_text(encoding="utf-8")


def test_game_objects_stand_for_mujoco_bodies(labsim, tmp_path):
    """What a MORSE component reads of Blender's objects: names, parents and children, world and local poses,
    game properties read and written, vectors, distances and rays to other objects, position_3d and its
    transformations, the persistent storage."""
    sim = simulation(labsim, tmp_path / "build")
    try:
        sim.step()
        pose = sim.component("robot.lab_pose")
        from morse.core import blenderapi, mathutils
        objects = blenderapi.scene().objects
        me, robot, fire = pose.bge_object, pose.robot_parent.bge_object, objects["campfire"]
        assert me.name == "robot.lab_pose" and pose.name() == "robot.lab_pose" and me.parent is robot
        assert me in robot.children and robot.parent is None and "robot" in objects
        assert list(me.localPosition) == pytest.approx([0.2, 0.0, 0.3], abs=1e-6)
        assert robot["Robot_Tag"] and fire["Fire"] and "Fire" not in objects["stove"]
        objects["stove"]["Fire"] = 450.0  # a number: morsec's thermometer takes it as the fire's temperature
        assert sim.sim.objects_with("Fire")[-1].name == "stove"
        distance, world, local = me.getVectTo(fire)
        assert distance == pytest.approx(me.getDistanceTo(fire)) and world.length == pytest.approx(1, abs=1e-6)
        expected = (fire.worldPosition - me.worldPosition)
        assert distance == pytest.approx(expected.length, abs=1e-5)
        assert list(me.worldOrientation * local) == pytest.approx(list(world), abs=1e-5)  # Blender 2.7x's *
        hit, point, normal = me.rayCast(fire)  # through its own robot, onto the campfire's nearest face
        assert hit is fire and list(normal) == pytest.approx([-1.0, 0.0, 0.0], abs=1e-5)
        assert point.x == pytest.approx(fire.worldPosition.x - 1.0, abs=1e-5)  # Cube(): 2 m wide
        assert me.rayCastTo(objects["stove"], 0, "Fire") is objects["stove"]
        assert me.rayCast(fire, None, 0, "NoSuchProperty") == (None, None, None)
        # position_3d: MORSE's Transformation3d
        mine, robots = pose.position_3d, pose.robot_parent.position_3d
        relative = robots.transformation3d_with(mine)
        assert (relative.x, relative.y, relative.z) == pytest.approx((0.2, 0.0, 0.3), abs=1e-9)
        assert relative.yaw == pytest.approx(0.0, abs=1e-9) and mine.distance(robots) == pytest.approx(math.hypot(0.2, 0.3))
        assert isinstance(mine.matrix, mathutils.Matrix) and list(mine.translation) == pytest.approx([mine.x, mine.y, mine.z])
        assert list((mine.matrix * mathutils.Vector((0, 0, 0, 1)))[:3]) == pytest.approx([mine.x, mine.y, mine.z], abs=1e-5)
        assert (mine.rotation.to_euler().z) == pytest.approx(mine.yaw, abs=1e-6)
        assert pose.sensor_to_robot_position_3d().z == pytest.approx(0.3)
        storage = blenderapi.persistantstorage()
        assert storage.time.time == pytest.approx(sim.sim.clock.now())
        assert storage.componentDict["robot.thermometer"] is sim.component("robot.thermometer")
        assert pose.robot_parent in storage.robotDict.values() and pose.frequency == 60.0
    finally:
        sim.sim.close()


def run_morsec(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(MORSEC), *args], cwd=cwd, capture_output=True, text=True, timeout=180)


BAD_SENSOR = """\
import morse.core.sensor
from morse.helpers.components import add_data


class Heavy(morse.core.sensor.Sensor):
    add_data('lifted', False, 'bool', 'whether it lifted')

    def default_action(self):
        self.local_data['lifted'] = True
        self.bge_object.applyForce([0, 0, 100])
"""


def test_what_is_not_emulated_stops_the_run_with_the_components_line(labsim):
    (labsim / "src" / "labsim" / "sensors" / "heavy.py").write_text(BAD_SENSOR, encoding="utf-8")
    (labsim / "heavy.py").write_text(textwrap.dedent("""\
        from morse.builder import *
        from morse.builder.creator import SensorCreator

        class Heavy(SensorCreator):
            _classpath = "labsim.sensors.heavy.Heavy"

        robot = ATRV()
        robot.append(Heavy())
        env = Environment("empty")
    """), encoding="utf-8")
    result = run_morsec("run", "heavy.py", "--duration", "1", "--port-base", "0", "--service-port", "0",
                        cwd=labsim)
    assert result.returncode == 1, result.stderr
    lines = result.stderr.strip().splitlines()
    assert lines == [f"error: {labsim / 'src' / 'labsim' / 'sensors' / 'heavy.py'}:10: KX_GameObject.applyForce "
                     "(robot.heavy) is not emulated by morsec (docs/coming-from-morse.md lists what is)"]


def test_a_module_morsec_does_not_emulate_is_a_located_build_error(labsim):
    (labsim / "src" / "labsim" / "actuators" / "wheels.py").write_text(textwrap.dedent("""\
        import morse.core.actuator
        from morse.core.wheeled_robot import MorsePhysicsRobot


        class Wheels(morse.core.actuator.Actuator):
            pass
    """), encoding="utf-8")
    result = run_morsec("build", "labsim", "-o", "build", cwd=labsim.parent)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.stderr
    assert lines[0].startswith(f"error: {labsim / 'src' / 'labsim' / 'actuators' / 'wheels.py'}:2: "
                               "ModuleNotFoundError: No module named 'morse.core.wheeled_robot'")


def test_morsec_components_lists_the_labs_components_beside_the_catalogue(labsim):
    result = run_morsec("components", cwd=labsim)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    mine = [line.split()[0] for line in lines if line.endswith("[MORSE API]")]
    assert mine == ["labsim.sensors.heading.Heading", "labsim.sensors.odometry.LabOdometry", "labsim.sensors.pose.LabPose",
                    "labsim.sensors.thermometer.LabThermometer", "labsim.actuators.igniter.Igniter",
                    "labsim.actuators.motion.LabMotion"]
    assert any(line.split()[:2] == ["thermometer", "Thermometer"] for line in lines)  # the catalogue's, still
    page = run_morsec("components", "labsim.sensors.odometry.LabOdometry", cwd=labsim).stdout
    assert "`raw`" in page and "`integrated`" in page and "`dyaw`" in page


ROS_SCENE = """\
from morse.builder import *
from labsim.builder.actuators import LabMotion
from labsim.builder.sensors import LabPose
robot = ATRV()
robot.translate(x=1.5)
lab_pose = LabPose()
lab_pose.add_stream('ros', 'morse.middleware.ros.pose.PoseStampedPublisher')
robot.append(lab_pose)
pose = Pose()
pose.add_stream('ros')
robot.append(pose)
motion = LabMotion()
motion.add_stream('ros', 'morse.middleware.ros.motion_vw.TwistReader')
robot.append(motion)
env = Environment('empty')
"""


def test_the_labs_components_stream_on_ros(labsim, ros_simulate):
    """On ROS 1 (Debian's roscore and rostopic as the peers), with the serialisers a MORSE script names: the
    lab's pose publishes what Pose publishes, a Twist drives the lab's actuator."""
    script = labsim / "ros_scene.py"
    script.write_text(ROS_SCENE, encoding="utf-8")
    ros_simulate(script, "fixed_step")
    echo, publish_once = test_ros.echo, test_ros.publish_once
    lab, builtin = echo("/robot/lab_pose")[0], echo("/robot/pose")[0]
    assert lab["header"]["frame_id"] == builtin["header"]["frame_id"] == "/map"
    assert lab["pose"]["position"]["x"] == pytest.approx(1.5, abs=0.01)
    for key in ("x", "y", "z"):  # the robot at rest: both read the same place, at whatever tick
        assert lab["pose"]["position"][key] == pytest.approx(builtin["pose"]["position"][key], abs=1e-4)
    publish_once("/robot/motion", "geometry_msgs/Twist", "{linear: {x: 1.0}, angular: {z: 0.0}}")
    deadline = time.monotonic() + 20
    while (x := echo("/robot/lab_pose")[0]["pose"]["position"]["x"]) < 2.5:
        assert time.monotonic() < deadline, f"the lab's actuator did not drive the robot (x = {x})"


KEYS_AND_BUG = """\
import morse.core.sensor
from morse.core import blenderapi
from morse.helpers.components import add_data


class Keys(morse.core.sensor.Sensor):
    add_data('pressed', False, 'bool', 'a key')

    def __init__(self, obj, parent=None):
        super().__init__(obj, parent)
        self.keyboard = blenderapi.keyboard()


class Buggy(morse.core.sensor.Sensor):
    add_data('ratio', 0.0, 'float', 'a ratio')

    def default_action(self):
        self.local_data['ratio'] = 1.0 / 0.0
"""


@pytest.mark.parametrize("component, code", [("Keys", 1), ("Buggy", 0)])
def test_a_component_built_on_what_is_not_emulated_stops_at_start_and_a_bug_of_its_own_is_its_line(labsim, component,
                                                                                                    code):
    module = labsim / "src" / "labsim" / "sensors" / "odd.py"
    module.write_text(KEYS_AND_BUG, encoding="utf-8")
    (labsim / "odd.py").write_text(textwrap.dedent(f"""\
        from morse.builder import *
        from morse.builder.creator import SensorCreator

        class Odd(SensorCreator):
            _classpath = "labsim.sensors.odd.{component}"

        robot = ATRV()
        odd = Odd()
        robot.append(odd)
        env = Environment("empty")
    """), encoding="utf-8")
    result = run_morsec("run", "odd.py", "--duration", "0.5", "--time-strategy", "fixed_step", "--port-base", "0",
                        "--service-port", "0", cwd=labsim)
    assert result.returncode == code, result.stderr
    assert "Traceback" not in result.stderr
    if component == "Keys":  # in the component's __init__, as the simulation starts: nothing runs
        assert result.stderr.strip().splitlines() == [
            f"error: {module}:11: blenderapi.keyboard() is not emulated by morsec: no keyboard reaches a component "
            "(morsec's Keyboard actuator reads the viewer's keys) (docs/coming-from-morse.md lists what is)"]
        assert "SCENE INITIALIZED" not in result.stdout
    else:  # logged once, at its line, and the simulation goes on
        logged = [line for line in result.stderr.splitlines() if "ZeroDivisionError" in line]
        assert logged == [f"ERROR morsec.runtime: robot.odd: ComponentError: {module}:18: ZeroDivisionError: "
                          "float division by zero"]
        assert "EXITING SIMULATION" in result.stdout
