"""The ROS middleware against real ROS 1 (Debian's): a roscore on a free port, `morsec run` as a child
process, and ROS's own tools as the peers (rostopic echo, rostopic pub, rospy with use_sim_time), each in
Debian's Python. Without ROS installed these tests fail: CI installs it (.ci/run)."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
import yaml

from morsec.app.process import SimulationProcess
from morsec.app.project import build_scene
from tests.runtime_helpers import free_port

SYSTEM_PYTHON = "/usr/bin/python3"  # Debian's, whose rospy the tools use


@pytest.fixture(scope="module")
def ros_master(tmp_path_factory):
    """A roscore of this module's own, on a free port; ROS_MASTER_URI and ROS_IP point every child at it."""
    port = free_port()
    folder = tmp_path_factory.mktemp("roscore")
    saved = {k: os.environ.get(k) for k in ("ROS_MASTER_URI", "ROS_IP", "ROS_HOME")}
    os.environ.update(ROS_MASTER_URI=f"http://127.0.0.1:{port}/", ROS_IP="127.0.0.1", ROS_HOME=str(folder))
    with open(folder / "roscore.log", "wb") as log:
        core = subprocess.Popen(["roscore", "-p", str(port)], stdout=log, stderr=subprocess.STDOUT,
                                start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while subprocess.run(["rosnode", "list"], capture_output=True, timeout=20).returncode != 0:
            assert core.poll() is None and time.monotonic() < deadline, (folder / "roscore.log").read_text()
            time.sleep(0.2)
        yield os.environ["ROS_MASTER_URI"]
    finally:
        core.terminate()
        core.wait(20)
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


@pytest.fixture
def simulate(ros_master, tmp_path):
    """`simulate(scene_path, strategy=None)`: build the scene, run it until the test ends."""
    running = []

    def start(source: Path, strategy: str | None = None) -> SimulationProcess:
        build = build_scene(source, tmp_path / f"{source.stem}.build")
        sim = SimulationProcess(build, tmp_path / f"{source.stem}.log", strategy)
        running.append(sim)
        sim.start(60)
        return sim

    yield start
    for sim in running:
        sim.stop()


def messages_folder() -> str:
    """Where morsec generated control_msgs (asked in a child process: this one's sys.path stays as it is)."""
    return subprocess.run([sys.executable, "-c", "from morsec.middleware.ros.messages import ensure_messages; "
                           "print(ensure_messages())"], capture_output=True, text=True, timeout=120,
                          check=True).stdout.strip()


def echo(topic: str, count: int = 1, timeout: float = 20) -> list[dict]:
    """`rostopic echo -n COUNT TOPIC`: the messages, as rostopic prints them (YAML)."""
    out = subprocess.run(["rostopic", "echo", "-n", str(count), topic], capture_output=True, text=True,
                         timeout=timeout, check=True).stdout
    return [yaml.safe_load(doc) for doc in out.split("\n---\n") if doc.strip()]


def publish_once(topic: str, message_type: str, value: str) -> None:
    subprocess.run(["rostopic", "pub", "-1", topic, message_type, value], capture_output=True, timeout=30,
                   check=True)


ROVER_YAML = """
robots:
  - type: atrv
    name: robot
    components:
      - {type: pose, streams: [ros]}
      - {type: odometry, streams: [ros]}
      - {type: motion_vw, name: motion, streams: [ros]}
environment:
  name: empty
"""


def test_a_yaml_scene_streams_to_ros_and_a_twist_moves_the_robot(simulate, tmp_path):
    source = tmp_path / "rover.yaml"
    source.write_text(ROVER_YAML, encoding="utf-8")
    simulate(source)

    pose = echo("/robot/pose")[0]  # MORSE's topic: the component's name; PoseStamped in /map
    assert pose["header"]["frame_id"] == "/map"
    assert abs(pose["header"]["stamp"]["secs"] - time.time()) < 60  # MORSE's clock: epoch-based
    assert abs(pose["pose"]["position"]["x"]) < 0.05 and pose["pose"]["orientation"]["w"] == pytest.approx(1, abs=1e-3)
    odometry = echo("/robot/odometry")[0]
    assert (odometry["header"]["frame_id"], odometry["child_frame_id"]) == ("/odom", "/base_footprint")

    publish_once("/robot/motion", "geometry_msgs/Twist", "{linear: {x: 1.0}, angular: {z: 0.0}}")
    deadline = time.monotonic() + 15
    while (x := echo("/robot/pose")[0]["pose"]["position"]["x"]) < 0.5:
        assert time.monotonic() < deadline, f"the robot did not move forward (x = {x})"
    moved = echo("/robot/odometry")[0]
    assert moved["pose"]["pose"]["position"]["x"] > 0.5 and moved["twist"]["twist"]["linear"]["x"] > 0.5


# a MORSE builder script streaming to ROS as MORSE scripts name serialisers and topics (test_recording records it)
ROVER_SCRIPT = textwrap.dedent("""
        from morse.builder import *
        robot = ATRV()
        pose = Pose()
        pose.add_stream('ros', 'morse.middleware.ros.pose.PoseStampedPublisher', topic='/rover/where')
        pose.add_stream('ros', method='morse.middleware.ros.pose.TFPublisher')
        robot.append(pose)
        robot.translate(x=2.0)
        motion = MotionVW()
        motion.add_interface('ros')
        robot.append(motion)
        env = Environment('empty')
""")


def test_a_builder_scene_names_serialisers_and_topics_as_morse_scripts_do(simulate, tmp_path):
    source = tmp_path / "rover.py"
    source.write_text(ROVER_SCRIPT, encoding="utf-8")
    simulate(source)

    assert echo("/rover/where")[0]["pose"]["position"]["x"] == pytest.approx(2.0, abs=0.05)
    transform = next(t for message in echo("/tf", 5) for t in message["transforms"]
                     if t["child_frame_id"] == "/base_link")
    assert transform["header"]["frame_id"] == "/map"
    assert transform["transform"]["translation"]["x"] == pytest.approx(2.0, abs=0.05)
    info = subprocess.run(["rostopic", "info", "/robot/motion"], capture_output=True, text=True, timeout=20,
                          check=True).stdout
    assert "geometry_msgs/Twist" in info and "/morse" in info.split("Subscribers:")[1]


def test_clock_is_simulated_time_and_use_sim_time_follows_it(simulate, tmp_path):
    source = tmp_path / "slow.yaml"  # half speed, timestamps from 0: simulated time is told apart at once
    source.write_text(ROVER_YAML.replace("  name: empty", "  name: empty\n  time: {scale: 0.5, relative: true}"),
                      encoding="utf-8")
    simulate(source)

    first = echo("/clock")[0]["clock"]
    assert first["secs"] < 30  # relative time: the simulation's, not the wall clock's
    subprocess.run(["rosparam", "set", "use_sim_time", "true"], check=True, timeout=20)
    try:
        node = subprocess.run([SYSTEM_PYTHON, "-c", textwrap.dedent("""
            import time, rospy
            rospy.init_node('sim_time_reader', disable_signals=True)
            while rospy.get_time() == 0: time.sleep(0.01)
            t0, w0 = rospy.get_time(), time.time()
            time.sleep(2.0)
            print(t0, rospy.get_time() - t0, time.time() - w0)
        """)], capture_output=True, text=True, timeout=60, check=True).stdout.split()
    finally:
        subprocess.run(["rosparam", "set", "use_sim_time", "false"], timeout=20)
    start, simulated, wall = (float(v) for v in node)
    assert start < 60  # the node's clock is /clock's
    assert simulated == pytest.approx(0.5 * wall, rel=0.2)  # and it runs at the simulation's pace (scale 0.5)


def test_a_pose_stream_in_moves_a_teleport_and_a_joint_state_streams_an_arm(simulate, tmp_path):
    source = tmp_path / "arm.yaml"
    source.write_text(textwrap.dedent("""
        robots:
          - type: atrv
            name: robot
            components:
              - {type: pose, streams: [ros]}
              - {type: teleport, streams: [ros]}
              - type: kuka_lwr
                name: arm
                translate: [0, 0, 0.9]
                components: [{type: armature_pose, name: joints, streams: [ros]}]
        environment: {name: empty}
    """), encoding="utf-8")
    simulate(source)

    joints = echo("/robot/arm/joints")[0]
    assert joints["name"] == [f"kuka_{i}" for i in range(1, 8)] and len(joints["position"]) == 7
    publish_once("/robot/teleport", "geometry_msgs/Pose", "{position: {x: 3.0, y: -1.0, z: 0.5}, "
                 "orientation: {w: 1.0}}")
    deadline = time.monotonic() + 15
    while abs((p := echo("/robot/pose")[0]["pose"]["position"])["x"] - 3.0) > 0.1:
        assert time.monotonic() < deadline, f"the robot was not teleported: {p}"
    assert p["y"] == pytest.approx(-1.0, abs=0.1)


def run_morsec(*args: str, env: dict) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "morsec", *args], capture_output=True, text=True, timeout=120,
                          env=env)


def without_ros() -> dict:
    """This Python without ROS: its own path has no rospy, and the folder ROS would be taken from is empty."""
    env = dict(os.environ, MORSEC_ROS_PYTHONPATH="/nonexistent/ros")
    env.pop("PYTHONPATH", None)
    return env


def test_without_ros_a_ros_scene_is_refused_in_one_line_saying_what_to_install(tmp_path):
    probe = subprocess.run([sys.executable, "-c", "import rospy"], capture_output=True, env=without_ros())
    assert probe.returncode != 0  # the premise: this interpreter does not see Debian's packages by itself
    source = tmp_path / "rover.yaml"
    source.write_text(ROVER_YAML, encoding="utf-8")
    build = run_morsec("build", str(source), "-o", str(tmp_path / "out"), env=without_ros())
    assert build.returncode == 2, build.stderr
    lines = build.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in build.stderr
    assert f"{source}:6:32: robots[0].components[0].streams[0]: " in lines[0] and "apt-get install ros-core" in lines[0] and "python3-rospy" in lines[0]

    built = build_scene(source, tmp_path / "built")  # built where ROS is, run where it is not
    run = run_morsec("run", str(built), env=without_ros())
    assert run.returncode == 2 and "Traceback" not in run.stderr
    assert "apt-get install ros-core" in run.stderr.strip().splitlines()[-1]

    test_file = tmp_path / "ros_test.py"
    test_file.write_text("from morse.testing.ros import RosTestCase\n", encoding="utf-8")
    imported = subprocess.run([sys.executable, str(test_file)], capture_output=True, text=True, env=without_ros())
    assert "RosInstallationError" in imported.stderr and "apt-get install ros-core" in imported.stderr


def test_a_component_without_a_ros_message_or_an_unknown_serialiser_is_a_located_error(tmp_path):
    from morsec.errors import SceneError
    source = tmp_path / "bad.yaml"
    source.write_text("robots:\n  - type: atrv\n    components:\n      - {type: thermometer, streams: [ros]}\n",
                      encoding="utf-8")
    with pytest.raises(SceneError, match=r"no ROS message for thermometer streams") as err:
        build_scene(source, tmp_path / "out")
    assert err.value.line == 4
    source.write_text("robots:\n  - type: atrv\n    components:\n      - type: pose\n        streams:\n"
                      "          - {middleware: ros, method: morse.middleware.ros.pose.PoseStampedPublishr}\n",
                      encoding="utf-8")
    with pytest.raises(SceneError, match=r"no ROS serialiser .*; did you mean one of 'morse.middleware.ros.pose.PoseStampedPublisher'"):
        build_scene(source, tmp_path / "out")
    source.write_text("robots:\n  - type: atrv\n    components:\n      - type: pose\n        overlays:\n"
                      "          - {middleware: ros, overlay: morse.middleware.ros.overlays.armatures."
                      "ArmatureController}\n", encoding="utf-8")
    with pytest.raises(SceneError, match=r"adapts armature components, not pose"):
        build_scene(source, tmp_path / "out")


def test_an_armature_overlay_serves_ros_controller_actions(simulate, tmp_path):
    """MORSE's ArmatureController: a FollowJointTrajectory goal (actionlib, control_msgs) moves the arm and
    succeeds; the joint state then reads the goal exactly (an armature at rest holds its joints); a goal
    naming a joint the arm does not have is rejected."""
    source = tmp_path / "arm.py"
    source.write_text(textwrap.dedent("""
        from morse.builder import *
        robot = ATRV()
        arm = KukaLWR()
        arm.translate(z=0.9)
        robot.append(arm)
        joints = ArmaturePose()
        arm.append(joints)
        joints.add_stream('ros', 'morse.middleware.ros.jointstate.JointStatePublisher')
        arm.add_overlay('ros', 'morse.middleware.ros.overlays.armatures.ArmatureController',
                        namespace='/arm_controller')
        env = Environment('empty')
    """), encoding="utf-8")
    simulate(source, "fixed_step")
    client = subprocess.run([SYSTEM_PYTHON, "-c", textwrap.dedent("""
        import rospy, actionlib
        from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
        from sensor_msgs.msg import JointState
        from trajectory_msgs.msg import JointTrajectoryPoint
        rospy.init_node('arm_client', disable_signals=True)
        client = actionlib.SimpleActionClient('/arm_controller/follow_joint_trajectory', FollowJointTrajectoryAction)
        assert client.wait_for_server(rospy.Duration(10))
        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = ['kuka_2', 'kuka_4']
        goal.trajectory.points = [JointTrajectoryPoint(positions=[0.5, -0.4], time_from_start=rospy.Duration(1.0))]
        print(client.send_goal_and_wait(goal, rospy.Duration(20)))
        state = rospy.wait_for_message('/robot/arm/joints', JointState, timeout=10)
        print(dict(zip(state.name, state.position))['kuka_2'], dict(zip(state.name, state.position))['kuka_4'])
        goal.trajectory.joint_names = ['elbow']
        print(client.send_goal_and_wait(goal, rospy.Duration(20)))
    """)], capture_output=True, text=True,
        timeout=90, env=dict(os.environ, PYTHONPATH=messages_folder()))
    assert client.returncode == 0, client.stderr
    succeeded, positions, rejected = client.stdout.strip().splitlines()
    assert succeeded == "3"  # actionlib's GoalStatus.SUCCEEDED
    assert [float(v) for v in positions.split()] == [0.5, -0.4]
    assert rejected == "5"  # REJECTED


def test_a_waypoint_goal_cancelled_or_preempted_stops_the_robot(simulate, tmp_path):
    """MORSE's WayPoint overlay (move_base) and MORSE's frame order: a goal's `goto` starts at the end of the
    frame after it came, and cancelling the goal (send_goal_and_wait's timeout) cancels it all the same: the
    robot, which drove 1 m/s, stops (it slides, as MORSE's did, no more); a second client's goal preempts the
    first one's, which is told so, and reaches its own goal."""
    source = tmp_path / "waypoint.py"
    source.write_text(textwrap.dedent("""
        from morse.builder import *
        robot = ATRV()
        odometry = Odometry()
        robot.append(odometry)
        odometry.add_stream('ros')
        waypoint = Waypoint()
        robot.append(waypoint)
        waypoint.add_overlay('ros', 'morse.middleware.ros.overlays.waypoints.WayPoint')
        env = Environment('empty')
    """), encoding="utf-8")
    simulate(source, "best_effort")
    client = subprocess.run([SYSTEM_PYTHON, "-c", textwrap.dedent("""
        import time
        import rospy, actionlib
        from geometry_msgs.msg import Point, Pose, PoseStamped, Quaternion
        from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
        from nav_msgs.msg import Odometry
        rospy.init_node('waypoint_client', disable_signals=True)
        def x():
            return rospy.wait_for_message('/robot/odometry', Odometry, timeout=10).pose.pose.position.x
        def goal(x, y):
            return MoveBaseGoal(PoseStamped(pose=Pose(Point(x, y, 0.0), Quaternion(0.0, 0.0, 0.0, 1.0))))
        first = actionlib.SimpleActionClient('/robot/waypoint/move_base', MoveBaseAction)
        second = actionlib.SimpleActionClient('/robot/waypoint/move_base', MoveBaseAction)
        assert first.wait_for_server(rospy.Duration(10)) and second.wait_for_server(rospy.Duration(10))
        print(first.send_goal_and_wait(goal(10.0, 0.0), rospy.Duration(1)))
        before = x()
        time.sleep(1.0)
        print(before, x())
        first.send_goal(goal(10.0, 0.0))
        time.sleep(0.5)
        second.send_goal(goal(before + 1.5, 0.0))
        print(first.wait_for_result(rospy.Duration(5)) and first.get_state(),
              second.wait_for_result(rospy.Duration(10)) and second.get_state())
    """)], capture_output=True, text=True, timeout=90)
    assert client.returncode == 0, client.stderr
    cancelled, positions, preempted = client.stdout.strip().splitlines()
    assert cancelled == "2"  # actionlib's GoalStatus.PREEMPTED
    before, after = (float(v) for v in positions.split())
    assert before > 0.5  # it drove for most of the second
    assert after - before < 0.25  # stopped, sliding (0.2 m from 1 m/s at most); it drove on at 1 m/s before
    assert preempted == "2 3"  # PREEMPTED, SUCCEEDED


def test_building_a_ros_scene_leaves_this_python_as_it_was(tmp_path):
    """A build only asks whether ROS is there: Debian's folder is not added to the compiling process's path
    (what else that process imports, and the build cache's key, stay the same)."""
    before = list(sys.path)
    source = tmp_path / "rover.yaml"
    source.write_text(ROVER_YAML, encoding="utf-8")
    build_scene(source, tmp_path / "out")
    assert sys.path == before


def test_a_default_interface_on_ros_streams_the_components_ros_has_messages_for(tmp_path):
    import json
    source = tmp_path / "default.yaml"
    source.write_text("robots:\n  - type: atrv\n    default_interface: ros\n    components:\n"
                      "      - {type: pose}\n      - {type: thermometer}\n      - {type: motion_vw}\n", encoding="utf-8")
    streams = json.loads((build_scene(source, tmp_path / "out") / "middleware.json").read_text())["streams"]
    assert [(s["component"], s["direction"], s["topic"], s["message"]) for s in streams] == [
        ("atrv.motion_vw", "IN", "/atrv/motion_vw", "geometry_msgs/Twist"),
        ("atrv.pose", "OUT", "/atrv/pose", "geometry_msgs/PoseStamped")]


def test_a_static_tf_stream_records_where_the_component_is_on_its_robot(tmp_path):
    """StaticTFPublisher's transform is the component's place on its robot, a nested one's composed with its
    parent's: a camera 0.1 m ahead on a pan-tilt unit turned 90 degrees left, 1 m up the robot."""
    import json
    import math
    source = tmp_path / "static.yaml"
    source.write_text(textwrap.dedent("""
        robots:
          - type: atrv
            name: robot
            components:
              - type: ptu
                name: ptu
                translate: [0, 0, 1]
                rotate: [0, 0, 1.5707963267948966]
                components:
                  - type: pose
                    name: eye
                    translate: [0.1, 0, 0]
                    streams: [{middleware: ros, method: morse.middleware.ros.static_tf.StaticTF2Publisher}]
    """), encoding="utf-8")
    stream = json.loads((build_scene(source, tmp_path / "out") / "middleware.json").read_text())["streams"][0]
    (x, y, z), (roll, pitch, yaw) = stream["placement"]
    assert (stream["parent_frame_id"], stream["frame_id"]) == ("base_link", "/robot/ptu/eye")
    assert (x, y, z) == pytest.approx((0.0, 0.1, 1.0)) and yaw == pytest.approx(math.pi / 2)
    assert (roll, pitch) == pytest.approx((0.0, 0.0))


def test_nav_pr2_serves_the_navigation_topics(simulate, tmp_path):
    """MORSE's NavPR2 with add_interface('ros'): its laser on /scan (181 rays, -90 to +90 degrees, 30 m), its
    odometry on /odom, a Twist on /cmd_vel moving it holonomically, as ROS's navigation stack expects; the
    laser measures a wall 10 m ahead coming closer (far and wide enough for the robot never to reach it, however
    long `rostopic pub -1`'s three seconds of latching take under load); BasePR2's /joint_states beside them."""
    import math
    source = tmp_path / "nav_pr2.py"
    source.write_text(textwrap.dedent("""
        from morse.builder import *
        pr2 = NavPR2(with_keyboard=False)
        pr2.add_interface('ros')
        wall = Cube('wall')
        wall.scale = (0.1, 10.0, 1.0)
        wall.translate(x=10.0, z=1.0)
        env = Environment('empty')
    """), encoding="utf-8")
    simulate(source)

    scan = echo("/scan")[0]
    ahead = 10.0 - 0.1 - 0.275  # the wall's near face, from the laser 0.275 m ahead of the robot's origin
    assert len(scan["ranges"]) == 181 and scan["range_max"] == pytest.approx(30.0)
    assert (scan["angle_min"], scan["angle_increment"]) == (pytest.approx(-math.pi / 2), pytest.approx(math.pi / 180))
    assert scan["ranges"][90] == pytest.approx(ahead, abs=0.01) and scan["ranges"][0] == pytest.approx(30.0)
    odometry = echo("/odom")[0]
    assert (odometry["header"]["frame_id"], odometry["child_frame_id"]) == ("/odom", "/base_footprint")
    assert "torso_lift_joint" in echo("/joint_states")[0]["name"]

    publish_once("/cmd_vel", "geometry_msgs/Twist", "{linear: {x: 0.5, y: 0.3}}")
    deadline = time.monotonic() + 15
    while (where := echo("/odom")[0]["pose"]["pose"]["position"])["x"] < 0.6:
        assert time.monotonic() < deadline, f"the PR2 did not move forward: {where}"
    publish_once("/cmd_vel", "geometry_msgs/Twist", "{}")
    time.sleep(0.5)
    where = echo("/odom")[0]["pose"]["pose"]["position"]
    assert where["y"] / where["x"] == pytest.approx(0.6, abs=0.05)  # both at once: holonomic
    assert echo("/scan")[0]["ranges"][90] == pytest.approx(ahead - where["x"], abs=0.01)


def test_localized_pr2_broadcasts_its_pose_on_tf(simulate, tmp_path):
    """MORSE's LocalizedPR2 with add_interface('ros'): the pose as the transform map -> base_link, read by
    ROS's own tf listener (Debian's python3-tf) as ROS nodes read it, moving when /cmd_vel says so."""
    source = tmp_path / "localized_pr2.py"
    source.write_text(textwrap.dedent("""
        from morse.builder import *
        pr2 = LocalizedPR2()
        pr2.translate(x=1.0, y=2.0)
        pr2.add_interface('ros')
        env = Environment('empty')
    """), encoding="utf-8")
    simulate(source)
    listener = subprocess.run([SYSTEM_PYTHON, "-c", textwrap.dedent("""
        import time, rospy, tf
        from geometry_msgs.msg import Twist
        rospy.init_node('pr2_tf_reader', disable_signals=True)
        listener = tf.TransformListener()
        listener.waitForTransform('map', 'base_link', rospy.Time(0), rospy.Duration(20))
        print(*listener.lookupTransform('map', 'base_link', rospy.Time(0))[0])
        command = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        while command.get_num_connections() == 0: time.sleep(0.05)
        go = Twist(); go.linear.x = 0.5
        command.publish(go)
        time.sleep(2.0)
        command.publish(Twist())
        time.sleep(0.5)
        print(*listener.lookupTransform('map', 'base_link', rospy.Time(0))[0])
    """)], capture_output=True, text=True, timeout=90)
    assert listener.returncode == 0, listener.stderr
    before, after = ([float(v) for v in line.split()] for line in listener.stdout.strip().splitlines())
    assert before == pytest.approx([1.0, 2.0, 0.0], abs=0.01)
    # 2 s of wall clock at 0.5 m/s, in best effort (simulated time keeps up with the wall clock unless the
    # machine is loaded): forward, along x where it faces, and nowhere else
    assert 0.3 < after[0] - before[0] < 1.1 and after[1:] == pytest.approx(before[1:], abs=0.01)
