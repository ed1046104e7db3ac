"""`morsec run --record`: the MCAP file, read back by the `mcap` package's reader, its ROS 2 messages decoded by
two CDR implementations (mcap-ros2-support's and rosbags'), its JSON messages checked against their JSON
Schemas, and by Foxglove's own JavaScript reader (@mcap/core, tests/node: .ci/run installs it with npm). The
runs are real `morsec run` processes with real clients; they end by themselves, by SIGINT, SIGTERM and SIGKILL."""

from __future__ import annotations

import base64
import json
import math
import signal
import subprocess
import textwrap
import time
from pathlib import Path

import jsonschema
import pytest
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
from rosbags.typesys import Stores, get_typestore

from morsec.kits.geometry import euler_to_quat
from morsec.middleware.base import StreamRequest
from morsec.middleware.record.channels import NO_ROS2, ROS2_DISTRIBUTION, plan_stream, ros2_outputs
from morsec.middleware.record.ros2 import CONVERTERS
from morsec.middleware.ros.serialisers import SERIALISERS
from tests.runtime_helpers import MORSEC, Morsec, scene, scene_file
from tests.test_ros import ROVER_SCRIPT, ros_master  # noqa: F401 (a roscore of this module's own)

ROOT = Path(__file__).resolve().parent.parent
NODE_READER = ROOT / "tests" / "node" / "read_mcap.mjs"
STORE = get_typestore(Stores(f"ros2_{ROS2_DISTRIBUTION}"))
GEO = {"longitude": 1.4437, "latitude": 43.6045, "altitude": 146.0}


def rover(*extra: dict) -> dict:
    """An ATRV with a sensor of each kind ROS has a message for, a battery (JSON only) and motion_vw."""
    return {"name": "robot", "type": "atrv", "components": [
        {"name": "pose", "type": "pose", "streams": ["socket"]},
        {"name": "odometry", "type": "odometry", "streams": ["socket"]},
        {"name": "sick", "type": "sick", "translate": [0.5, 0.0, 0.4], "frequency": 10, "streams": ["socket"],
         "properties": {"resolution": 10.0}},
        {"name": "imu", "type": "imu", "streams": ["socket"]},
        {"name": "gps", "type": "gps", "level": "raw", "streams": ["socket"]},
        {"name": "clock", "type": "clock", "streams": ["socket"]},
        {"name": "velocity", "type": "velocity", "streams": ["socket"]},
        {"name": "battery", "type": "battery", "streams": ["socket"]},
        {"name": "camera", "type": "video_camera", "translate": [0.3, 0.0, 0.6], "frequency": 5,
         "streams": ["socket"], "properties": {"cam_width": 16, "cam_height": 12}},
        {"name": "motion", "type": "motion_vw", "streams": ["socket"]},
        *extra]}


def read_all(path: Path) -> dict:
    """Everything in a recording: channels by topic, schemas, metadata, and each channel's messages (the
    record, and its decoded form: JSON parsed, ROS 2 by mcap-ros2-support's decoder)."""
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        assert summary is not None, "a finished MCAP file has a summary"
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        messages: dict[str, list] = {}
        for _schema, channel, message, decoded in reader.iter_decoded_messages(
                topics=[c.topic for c in summary.channels.values() if c.message_encoding == "cdr"]):
            messages.setdefault(channel.topic, []).append((message, decoded))
        for _schema, channel, message in reader.iter_messages(
                topics=[c.topic for c in summary.channels.values() if c.message_encoding == "json"]):
            messages.setdefault(channel.topic, []).append((message, json.loads(message.data)))
    channels = {c.topic: (c, summary.schemas[c.schema_id]) for c in summary.channels.values()}
    return {"summary": summary, "channels": channels, "metadata": metadata, "messages": messages}


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """A run of the rover recorded with its services, while a client drives it and asks the time."""
    folder = tmp_path_factory.mktemp("recording")
    source = scene_file(folder, scene(rover(), environment={"properties": GEO}))
    path = folder / "run.mcap"
    with Morsec(source, folder, args=["--record", path, "--record-services"]) as sim:
        client = sim.client()
        with sim.stream("robot.motion") as motion:
            motion.send('{"v": 1.0, "w": 0.5}\n')
            told = client.ok("time", "now")
            client.ok("time", "sleep", 1.0)
        client.ok("simulation", "quit")
        assert sim.wait(60) == 0, sim.output()
    return {"path": path, "told": told, "read": read_all(path), "output": sim.output()}


# ------------------------------------------------------------------------------------------- the table
def test_every_ros_serialiser_has_a_ros2_converter_and_its_messages_exist_in_ros2():
    """One table (the ROS middleware's): each of its serialisers is recorded as ROS 2 or said not to be."""
    for name in SERIALISERS:
        if name in NO_ROS2:
            assert name not in CONVERTERS
            continue
        assert name in CONVERTERS, f"serialiser {name} has no ROS 2 converter"
        for topic, ros_type in ros2_outputs(name, "/robot/x"):
            assert ros_type in STORE.types, f"{name}: {ros_type} is no ROS 2 {ROS2_DISTRIBUTION} message"
            assert topic.startswith("/")


def test_a_component_with_a_ros_stream_is_recorded_as_that_stream():
    request = StreamRequest("robot.pose", "OUT", {}, ("pose",), {})
    default = plan_stream(request, "morsec/sensors/pose", {"properties": {"x": {}, "y": {}, "z": {}}}, [])
    assert [(c.topic, c.schema, c.encoding) for c in default.channels] == [
        ("robot.pose", "morsec/sensors/pose", "jsonschema"), ("/robot/pose", "geometry_msgs/msg/PoseStamped", "ros2msg")]
    [(conversion)] = default.conversions
    assert (conversion.serialiser, conversion.endpoint["frame_id"], conversion.channels) == ("pose_stamped", "/map", (1,))
    stamped = {"topic": "/rover/where", "serialiser": "pose_stamped", "message": "geometry_msgs/PoseStamped",
               "frame_id": "/map"}
    tf = {"topic": "/robot/pose", "serialiser": "pose_tf", "message": "tf2_msgs/TFMessage", "frame_id": "/world",
          "child_frame_id": "/rover"}
    named = plan_stream(request, "morsec/sensors/pose", {}, [stamped, tf])
    assert [(c.topic, c.schema) for c in named.channels[1:]] == [
        ("/rover/where", "geometry_msgs/msg/PoseStamped"), ("/tf", "tf2_msgs/msg/TFMessage")]
    assert [(c.serialiser, c.channels) for c in named.conversions] == [("pose_stamped", (1,)), ("pose_tf", (2,))]
    assert named.conversions[1].endpoint["child_frame_id"] == "/rover"


def test_a_level_without_the_fields_of_its_ros_message_is_recorded_as_json_only():
    request = StreamRequest("robot.odo", "OUT", {}, ("odometry",), {})
    plan = plan_stream(request, "morsec/sensors/odometry/differential", {"properties": {"dx": {}, "dy": {}}}, [])
    assert [c.topic for c in plan.channels] == ["robot.odo"] and plan.conversions == ()
    assert plan.notes == ("recorded as JSON only: its messages have no x, y, z for a nav_msgs/msg/Odometry",)
    battery = plan_stream(StreamRequest("robot.battery", "OUT", {}, ("battery",), {}), "b", {}, [])
    assert [c.topic for c in battery.channels] == ["robot.battery"] and battery.notes == ()


# ------------------------------------------------------------------------------------------- converters
SAMPLE_POSE = {"timestamp": 12.25, "x": 1.0, "y": -2.0, "z": 0.5, "yaw": 0.3, "pitch": -0.1, "roll": 0.2}


def quaternion_of(data: dict) -> list[float]:
    w, x, y, z = euler_to_quat(data["roll"], data["pitch"], data["yaw"])
    return [x, y, z, w]


def decode_both(ros_type: str, cdr: bytes):
    """The message decoded by rosbags and by mcap-ros2-support; both must read it."""
    from mcap.records import Schema
    text = STORE.generate_msgdef(ros_type, ros_version=2)[0]
    theirs = DecoderFactory().decoder_for("cdr", Schema(id=1, name=ros_type, encoding="ros2msg",
                                                        data=text.encode()))(cdr)
    return STORE.deserialize_cdr(cdr, ros_type), theirs


def converted(serialiser: str, data: dict, **endpoint) -> list:
    """Each output of a serialiser's converter, decoded twice: [(rosbags', mcap-ros2-support's) | None]."""
    out = CONVERTERS[serialiser](STORE, {"topic": "/robot/x", **endpoint}).convert(data)
    outputs = ros2_outputs(serialiser, "/robot/x")
    assert len(out) == len(outputs)
    return [None if cdr is None else decode_both(ros_type, cdr) for cdr, (_, ros_type) in zip(out, outputs)]


def test_pose_messages_carry_the_pose_its_time_and_frame():
    for serialiser in ("pose_stamped", "pose_with_covariance"):
        for msg in converted(serialiser, SAMPLE_POSE, frame_id="/map")[0]:
            assert (msg.header.stamp.sec, msg.header.stamp.nanosec, msg.header.frame_id) == (12, 250_000_000, "map")
            where = msg.pose if serialiser == "pose_stamped" else msg.pose.pose
            assert [where.position.x, where.position.y, where.position.z] == [1.0, -2.0, 0.5]
            q = where.orientation
            assert [q.x, q.y, q.z, q.w] == pytest.approx(quaternion_of(SAMPLE_POSE), abs=1e-12)
    for msg in converted("pose", SAMPLE_POSE)[0]:
        assert msg.position.y == -2.0
    for msg in converted("pose_tf", SAMPLE_POSE, frame_id="/map", child_frame_id="/base_link")[0]:
        (t,) = msg.transforms
        assert (t.header.frame_id, t.child_frame_id, t.transform.translation.x) == ("map", "base_link", 1.0)


def test_odometry_is_a_nav_msgs_odometry_and_its_transform():
    data = {**SAMPLE_POSE, "vx": 0.5, "vy": 0.0, "vz": 0.0, "wx": 0.0, "wy": 0.0, "wz": 0.25}
    (odometry, transform) = converted("odometry", data, frame_id="/odom", child_frame_id="/base_footprint")
    for msg in odometry:
        assert (msg.header.frame_id, msg.child_frame_id) == ("odom", "base_footprint")
        assert msg.pose.pose.position.x == 1.0 and list(msg.pose.covariance) == [0.0] * 36
        assert (msg.twist.twist.linear.x, msg.twist.twist.angular.z) == (0.5, 0.25)
    for msg in transform:
        assert (msg.transforms[0].header.frame_id, msg.transforms[0].child_frame_id) == ("odom", "base_footprint")


def test_static_transforms_go_once_a_second_or_once():
    endpoint = {"frame_id": "/robot/sick", "parent_frame_id": "base_link",
                "placement": [[0.5, 0.0, 0.4], [0.0, 0.0, math.pi / 2]]}
    converter = CONVERTERS["static_tf"](STORE, {"topic": "/robot/sick", **endpoint})
    sent = [converter.convert({"timestamp": t})[0] is not None for t in (0.0, 0.5, 1.01, 1.5, 2.1)]
    assert sent == [True, False, True, False, True]
    (msg, _), = converted("static_tf", {"timestamp": 3.0}, **endpoint)
    t = msg.transforms[0]
    assert (t.header.frame_id, t.child_frame_id, t.header.stamp.sec) == ("base_link", "robot/sick", 4)
    assert (t.transform.translation.x, t.transform.rotation.z) == pytest.approx((0.5, math.sqrt(0.5)))
    once = CONVERTERS["static_tf2"](STORE, {"topic": "/robot/sick", **endpoint})
    assert [once.convert({"timestamp": t})[0] is not None for t in (0.0, 5.0)] == [True, False]


def test_sensor_messages_of_the_other_kinds():
    scan = {"timestamp": 1.0, "range_list": [1.0, 2.5, 30.0], "remission_list": [0.1, 0.2, 0.3]}
    for msg in converted("laser_scan", scan, frame_id="/robot/sick",
                         geometry={"scan_window": 20.0, "resolution": 10.0, "laser_range": 30.0})[0]:
        assert list(msg.ranges) == [1.0, 2.5, 30.0] and msg.range_max == 30.0
        assert (msg.angle_min, msg.angle_max) == pytest.approx((-math.radians(10), math.radians(10)))
    imu = {"timestamp": 1.0, "angular_velocity": [0.1, 0.2, 0.3], "linear_acceleration": [0.0, 0.0, 9.81]}
    for msg in converted("imu", imu, frame_id="/imu")[0]:
        assert list(msg.orientation_covariance)[0] == -1.0  # no orientation: ROS's way of saying so
        assert (msg.angular_velocity.z, msg.linear_acceleration.z, msg.header.frame_id) == (0.3, 9.81, "imu")
    fix = {"timestamp": 1.0, **GEO}
    for msg in converted("nav_sat_fix", fix, frame_id="/gps")[0]:
        assert (msg.latitude, msg.longitude, msg.altitude, msg.status.service) == (43.6045, 1.4437, 146.0, 1)
    twist = {"timestamp": 1.0, "linear_velocity": [1.0, 0.0, 0.0], "angular_velocity": [0.0, 0.0, 0.5]}
    for msg in converted("twist_stamped", twist, frame_id="/robot/velocity")[0]:
        assert (msg.twist.linear.x, msg.twist.angular.z) == (1.0, 0.5)
    for msg in converted("clock", {"timestamp": 7.5})[0]:
        assert (msg.clock.sec, msg.clock.nanosec) == (7, 500_000_000)
    for msg in converted("joint_state", {"timestamp": 1.0, "pan": 0.5, "tilt": -0.25}, frame_id="/ptu")[0]:
        assert (list(msg.name), list(msg.position)) == (["pan", "tilt"], [0.5, -0.25])


def test_camera_images_and_depth_points():
    pixels = bytes(range(2 * 3 * 4))
    frame = {"timestamp": 2.0, "width": 3, "height": 2, "image": base64.b64encode(pixels).decode(),
             "intrinsic_matrix": [[10.0, 0.0, 1.5], [0.0, 10.0, 1.0], [0.0, 0.0, 1.0]]}
    image, info = converted("image", frame, frame_id="/robot/camera")
    for msg in image:
        assert (msg.width, msg.height, msg.encoding, msg.step, bytes(msg.data)) == (3, 2, "rgba8", 12, pixels)
    for msg in info:
        assert list(msg.k) == [10.0, 0.0, 1.5, 0.0, 10.0, 1.0, 0.0, 0.0, 1.0] and msg.p[3] == 0.0
    assert converted("image", {"timestamp": 2.0, "image": None}) == [None, None]
    import numpy as np
    points = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], dtype=np.float32)
    for msg in converted("point_cloud2", {"timestamp": 2.0, "points": base64.b64encode(points.tobytes()).decode()})[0]:
        assert (msg.width, msg.point_step, [f.name for f in msg.fields]) == (2, 12, ["x", "y", "z"])
        assert np.frombuffer(bytes(msg.data), dtype=np.float32).tolist() == points.ravel().tolist()


def test_actuator_commands_as_the_messages_ros_would_have_sent():
    for msg in converted("twist", {"v": 1.5, "w": -0.5})[0]:
        assert (msg.linear.x, msg.angular.z) == (1.5, -0.5)
    for msg in converted("twist_xyw", {"x": 1.0, "y": 2.0, "w": 0.5})[0]:
        assert (msg.linear.x, msg.linear.y, msg.angular.z) == (1.0, 2.0, 0.5)
    for msg in converted("pose_in", {"x": 1.0, "yaw": math.pi / 2})[0]:
        assert (msg.position.x, msg.orientation.z) == pytest.approx((1.0, math.sqrt(0.5)))
    for msg in converted("point_in", {"x": 1.0, "y": 2.0, "z": 3.0})[0]:
        assert (msg.x, msg.y, msg.z) == (1.0, 2.0, 3.0)
    for msg in converted("joint_state_in", {"elbow": 0.5})[0]:
        assert (list(msg.name), list(msg.position)) == (["elbow"], [0.5])


# ------------------------------------------------------------------------------------------- a real run
EXPECTED_CHANNELS = {
    "robot.pose": ("morsec/sensors/pose", "jsonschema", "json"),
    "/robot/pose": ("geometry_msgs/msg/PoseStamped", "ros2msg", "cdr"),
    "/robot/odometry": ("nav_msgs/msg/Odometry", "ros2msg", "cdr"),
    "/tf": ("tf2_msgs/msg/TFMessage", "ros2msg", "cdr"),
    "/robot/sick": ("sensor_msgs/msg/LaserScan", "ros2msg", "cdr"),
    "/robot/imu": ("sensor_msgs/msg/Imu", "ros2msg", "cdr"),
    "/robot/gps": ("sensor_msgs/msg/NavSatFix", "ros2msg", "cdr"),
    "robot.gps": ("morsec/sensors/gps/raw", "jsonschema", "json"),
    "/robot/clock": ("rosgraph_msgs/msg/Clock", "ros2msg", "cdr"),
    "/robot/velocity": ("geometry_msgs/msg/TwistStamped", "ros2msg", "cdr"),
    "robot.battery": ("morsec/sensors/battery", "jsonschema", "json"),
    "/robot/camera/image": ("sensor_msgs/msg/Image", "ros2msg", "cdr"),
    "/robot/camera/camera_info": ("sensor_msgs/msg/CameraInfo", "ros2msg", "cdr"),
    "robot.motion": ("morsec/actuators/motion_vw", "jsonschema", "json"),
    "/robot/motion": ("geometry_msgs/msg/Twist", "ros2msg", "cdr"),
    "/morsec/requests": ("morsec/service_request", "jsonschema", "json"),
    "/morsec/answers": ("morsec/service_answer", "jsonschema", "json"),
}


def test_every_stream_is_recorded_with_its_ros2_message_and_its_json(recording):
    read = recording["read"]
    found = {topic: (schema.name, schema.encoding, channel.message_encoding)
             for topic, (channel, schema) in read["channels"].items()}
    for topic, expected in EXPECTED_CHANNELS.items():
        assert found.get(topic) == expected, topic
    assert "/robot/battery" not in found  # ROS has no message for a battery: JSON only
    for topic, (_channel, schema) in read["channels"].items():
        if schema.encoding == "ros2msg":
            assert schema.data.decode() == STORE.generate_msgdef(schema.name, ros_version=2)[0]
            assert read["messages"].get(topic), f"{topic}: no message"
    morsec = read["metadata"]["morsec"]
    assert (morsec["time"], morsec["time_origin"]) == ("simulated", "unix_epoch")
    assert [r["name"] for r in json.loads(morsec["details"])["robots"]] == ["robot"]
    assert {s["component"] for s in json.loads(morsec["streams"])} >= {"robot.pose", "robot.motion"}


def test_json_messages_follow_their_schema_and_are_logged_at_their_simulated_time(recording):
    read = recording["read"]
    for topic, (_channel, schema) in read["channels"].items():
        if schema.encoding != "jsonschema":
            continue
        validator = jsonschema.Draft202012Validator(json.loads(schema.data))
        previous = -1
        for message, data in read["messages"].get(topic, []):
            validator.validate(data)
            assert message.log_time >= previous and message.publish_time == message.log_time
            previous = message.log_time
            if "timestamp" in data:
                assert message.log_time == round(data["timestamp"] * 1e9), topic


def test_ros2_messages_carry_what_the_json_says(recording):
    messages = recording["read"]["messages"]
    poses = {m.log_time: data for m, data in messages["robot.pose"]}
    assert len(messages["/robot/pose"]) == len(poses) > 60
    for message, pose in messages["/robot/pose"]:
        data = poses[message.log_time]
        stamp = pose.header.stamp.sec * 1_000_000_000 + pose.header.stamp.nanosec
        assert stamp == message.log_time and pose.header.frame_id == "map"
        assert [pose.pose.position.x, pose.pose.position.y, pose.pose.position.z] == [data["x"], data["y"], data["z"]]
        q = pose.pose.orientation
        assert [q.x, q.y, q.z, q.w] == pytest.approx(quaternion_of(data), abs=1e-12)
    assert messages["robot.pose"][-1][1]["x"] > 0.3  # the client's command moved it
    for topic, entries in messages.items():  # rosbags reads every ROS 2 message too
        channel, schema = recording["read"]["channels"][topic]
        if schema.encoding == "ros2msg":
            for message, _ in entries[:20]:
                STORE.deserialize_cdr(message.data, schema.name)
    images = {m.log_time: data for m, data in messages["/robot/camera/image"]}
    (first_time, first), *_ = [(m.log_time, d) for m, d in messages["robot.camera"]]
    assert (images[first_time].width, images[first_time].height) == (16, 12)
    assert bytes(images[first_time].data) == base64.b64decode(first["image"])
    ranges = [list(m.ranges) for _, m in messages["/robot/sick"]]
    assert ranges[0] == [data for _, d in messages["robot.sick"][:1] for data in d["range_list"]]


def test_actuator_commands_and_services_are_recorded(recording):
    messages = recording["read"]["messages"]
    [(command, sent)] = messages["robot.motion"]
    assert sent == {"v": 1.0, "w": 0.5}
    [(same, twist)] = messages["/robot/motion"]
    assert (twist.linear.x, twist.angular.z, same.log_time) == (1.0, 0.5, command.log_time)
    requests = [data for _, data in messages["/morsec/requests"]]
    answers = [data for _, data in messages["/morsec/answers"]]
    now = next(r for r in requests if (r["component"], r["service"]) == ("time", "now"))
    answer = next(a for a in answers if (a["client"], a["id"]) == (now["client"], now["id"]))
    assert answer["status"] == "SUCCESS" and answer["result"] == recording["told"]
    sleep = next(r for r in requests if r["service"] == "sleep")
    assert sleep["args"] == [1.0]
    woke = next(m for m, a in messages["/morsec/answers"] if a["id"] == sleep["id"])
    asked = next(m for m, r in messages["/morsec/requests"] if r["id"] == sleep["id"])
    assert woke.log_time - asked.log_time == pytest.approx(1e9, abs=2e7)  # a simulated second later


def test_foxglove_reader_opens_the_recording(recording, node_packages):
    """@mcap/core (Foxglove's reader) lists the channels and schemas and decodes a JSON message."""
    result = subprocess.run(["node", str(NODE_READER), str(recording["path"]), "robot.pose", "3"],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    theirs = json.loads(result.stdout)
    read = recording["read"]
    assert {c["topic"]: (c["schemaName"], c["schemaEncoding"], c["messageEncoding"]) for c in theirs["channels"]} == {
        topic: (schema.name, schema.encoding, channel.message_encoding)
        for topic, (channel, schema) in read["channels"].items()}
    assert int(theirs["messageCount"]) == read["summary"].statistics.message_count
    assert theirs["metadata"]["morsec"] == list(read["metadata"]["morsec"])
    ours = read["messages"]["robot.pose"][:3]
    assert [(int(m["logTime"]), m["data"]) for m in theirs["messages"]] == [(m.log_time, d) for m, d in ours]


# ------------------------------------------------------------------------------------------- how a run ends
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_run_stopped_by_a_signal_leaves_a_complete_recording(tmp_path, sig):
    source = scene_file(tmp_path, scene(strategy="best_effort"))
    path = tmp_path / "run.mcap"
    with Morsec(source, tmp_path, args=["--record", path]) as sim:
        time.sleep(1.5)
        sim.signal(sig)
        assert sim.wait(60) == 0, sim.output()
    read = read_all(path)
    poses = read["messages"]["robot.pose"]
    assert read["summary"].statistics.message_count == sum(len(m) for m in read["messages"].values())
    assert len(poses) >= 60  # a simulated second at 60 Hz at least, the last half second included
    assert (poses[-1][0].log_time - poses[0][0].log_time) / 1e9 >= 1.0


def test_a_killed_run_leaves_a_readable_recording_of_what_it_had_sent(tmp_path):
    """The writer process finishes the file when its input ends, the run's death included."""
    source = scene_file(tmp_path, scene(strategy="best_effort"))
    path = tmp_path / "run.mcap"
    with Morsec(source, tmp_path, args=["--record", path]) as sim:
        time.sleep(2.0)
        sim.signal(signal.SIGKILL)
        sim.wait(30)
    deadline = time.monotonic() + 30
    while True:  # the writer ends on its own, shortly after
        try:
            read = read_all(path)
            break
        except Exception:
            assert time.monotonic() < deadline, "the recording was never finished"
            time.sleep(0.2)
    assert len(read["messages"]["robot.pose"]) >= 30  # the batches sent every half second


# ------------------------------------------------------------------------------------------- a ROS scene
@pytest.mark.usefixtures("ros_master")
def test_a_builder_scene_streaming_to_ros_records_its_ros_streams_as_ros_carries_them(tmp_path):
    """Real ROS (a roscore): the pose's two ROS streams, named as MORSE scripts name them, recorded as they are
    published, and the recording made by the scene's env.record."""
    from morsec.app.project import build_scene
    source = tmp_path / "rover.py"
    source.write_text(ROVER_SCRIPT + "env.record('rover.mcap')\n", encoding="utf-8")
    build = build_scene(source, tmp_path / "build")
    result = subprocess.run([str(MORSEC), "run", str(build), "--duration", "1", "--time-strategy", "fixed_step",
                             "--port-base", "0", "--service-port", "0"], capture_output=True, text=True, timeout=120,
                            cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    read = read_all(tmp_path / "rover.mcap")
    assert {t: s.name for t, (_, s) in read["channels"].items() if s.encoding == "ros2msg"} == {
        "/rover/where": "geometry_msgs/msg/PoseStamped", "/tf": "tf2_msgs/msg/TFMessage",
        "/robot/motion": "geometry_msgs/msg/Twist"}
    where = read["messages"]["/rover/where"]
    assert len(where) == 60 and where[0][1].pose.position.x == pytest.approx(2.0, abs=0.05)
    transform = read["messages"]["/tf"][0][1].transforms[0]
    assert (transform.header.frame_id, transform.child_frame_id) == ("map", "base_link")


# ------------------------------------------------------------------------------------------- scenes and errors
def test_a_scene_records_every_run_with_env_record(tmp_path):
    source = scene_file(tmp_path, scene(environment={"record": {"file": "runs/scene.mcap", "services": True}}))
    out = tmp_path / "out"
    result = subprocess.run([str(MORSEC), "run", str(source), "--duration", "0.5", "--output-dir", str(out),
                             "--port-base", "0", "--service-port", "0"],
                            capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    read = read_all(out / "runs" / "scene.mcap")
    assert len(read["messages"]["/robot/pose"]) == 30 and "/morsec/requests" in read["channels"]


def test_a_builder_script_records_with_env_record(tmp_path):
    from morsec.app.project import build_scene
    source = tmp_path / "rover.py"
    source.write_text(textwrap.dedent("""
        from morse.builder import *
        robot = ATRV()
        pose = Pose()
        pose.add_stream('socket')
        robot.append(pose)
        env = Environment('empty')
        env.record('rover.mcap', services=True)
    """), encoding="utf-8")
    manifest = json.loads((build_scene(source, tmp_path / "build") / "manifest.json").read_text())
    assert manifest["scene"]["environment"]["record"] == {"file": "rover.mcap", "services": True}


@pytest.mark.parametrize("record, message", [
    ({"file": "/tmp/x.mcap"}, "a recording must be a relative path inside the run's output folder"),
    ({"file": "run.txt"}, "a recording is an MCAP file: its name ends with .mcap"),
])
def test_a_scene_naming_a_bad_recording_is_refused_where_it_says_so(tmp_path, record, message):
    source = scene_file(tmp_path, scene(environment={"record": record}))
    result = subprocess.run([str(MORSEC), "check", str(source)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2 and message in result.stderr and "scene.yaml:" in result.stderr, result.stderr
    assert "Traceback" not in result.stderr


def test_record_mistakes_on_the_command_line_are_one_line(tmp_path):
    source = scene_file(tmp_path, scene())
    alone = subprocess.run([str(MORSEC), "run", str(source), "--record-services"], capture_output=True, text=True,
                           timeout=60)
    assert alone.returncode == 2
    assert alone.stderr.strip() == ("error: --record-services records into the file --record names: "
                                    "give --record FILE.mcap")
    (tmp_path / "taken").write_text("a file, not a folder")
    unwritable = subprocess.run([str(MORSEC), "run", str(source), "--duration", "0.1", "--port-base", "0",
                                 "--service-port", "0", "--record", str(tmp_path / "taken" / "run.mcap")],
                                capture_output=True, text=True, timeout=120)
    assert unwritable.returncode == 2, unwritable.stderr
    assert unwritable.stderr.strip().startswith(f"error: cannot write the recording {tmp_path / 'taken' / 'run.mcap'}")
    assert "Traceback" not in unwritable.stderr


def test_a_recording_that_cannot_be_written_ends_the_run_saying_so(tmp_path):
    """/dev/full: every write fails (no space left), as on a full disk."""
    source = scene_file(tmp_path, scene())
    result = subprocess.run([str(MORSEC), "run", str(source), "--duration", "0.5", "--port-base", "0",
                             "--service-port", "0", "--record", "/dev/full"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 1, result.stderr
    lines = result.stderr.strip().splitlines()
    assert "ERROR morsec.record: cannot write the recording /dev/full: No space left on device" in lines
    assert lines[-1] == ("error: the recording /dev/full is incomplete: its writer ended with code 1 "
                         "(its error is above)")
    assert "Traceback" not in result.stderr
