"""`morsec run --foxglove` (docs/foxglove.md), watched by Foxglove's own client: `@foxglove/ws-protocol` from
npm, in a node script (tests/node/watch.mjs) that speaks the subprotocol foxglove-sdk's server does,
subscribes to every channel and decodes every message with its channel's schema, as the Foxglove app does.
The example scene and its builder twin are served; a client drives the rover on its socket stream while
Foxglove watches. Then the pieces on the Python side: the transform tree against MuJoCo's poses, the scene's
primitives of every geom kind, the errors a user meets."""

from __future__ import annotations

import base64
import json
import math
import os
import queue
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import jsonschema
import mujoco
import numpy as np
import pytest
from runtime_helpers import HOST, Morsec, free_port, occupy

from morsec.app.project import build_scene

REPO = Path(__file__).resolve().parent.parent
CLIENT_DIR = REPO / "tests" / "node"
WATCH = CLIENT_DIR / "watch.mjs"
MESSAGE_SCHEMAS = REPO / "schemas" / "messages"
EVENT_TIMEOUT = 60.0  # s: a scene with two cameras rendered on the CPU, on a loaded machine

# the example scene's channels: topic -> (message encoding, schema name, schema encoding)
CHANNELS = {
    "/tf": ("protobuf", "foxglove.FrameTransforms", "protobuf"),
    "/scene": ("protobuf", "foxglove.SceneUpdate", "protobuf"),
    "/rover/sick": ("protobuf", "foxglove.LaserScan", "protobuf"),
    "/rover/camera": ("protobuf", "foxglove.RawImage", "protobuf"),
    "/rover/depth": ("protobuf", "foxglove.PointCloud", "protobuf"),
    "/rover/pose": ("json", "morsec.sensors.pose", "jsonschema"),
    "/rover/odometry": ("json", "morsec.sensors.odometry.integrated", "jsonschema"),
    "/rover/motion": ("json", "morsec.actuators.motion_vw", "jsonschema"),
}


@pytest.fixture(scope="session")
def foxglove_client(node_packages) -> Path:
    """Foxglove's client (tests/node/watch.mjs), its packages installed."""
    return WATCH


class Watcher:
    """The node script's events, read on a thread."""

    def __init__(self, url: str):
        self.proc = subprocess.Popen(["node", str(WATCH), url, "--until-stdin-closes", "--seconds", "300"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True)
        self.events: list[dict] = []
        self.fresh: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            event = json.loads(line)
            self.events.append(event)
            self.fresh.put(event)
        self.fresh.put(None)

    def wait_for(self, what: str, predicate, timeout: float = EVENT_TIMEOUT) -> dict:
        """The first event (seen before or to come) for which `predicate` is true."""
        for event in list(self.events):
            if predicate(event):
                return event
        deadline = time.monotonic() + timeout
        while (left := deadline - time.monotonic()) > 0:
            try:
                event = self.fresh.get(timeout=left)
            except queue.Empty:
                break
            if event is None:
                break
            if predicate(event):
                return event
        errors = [e for e in self.events if e["event"] == "error"]
        raise AssertionError(f"Foxglove's client saw no {what} within {timeout} s (errors: {errors[:3]}, "
                             f"stderr: {self.stderr()})")

    def message(self, topic: str, predicate=lambda m: True, timeout: float = EVENT_TIMEOUT) -> dict:
        return self.wait_for(f"message on {topic}", lambda e: e["event"] == "message" and e["topic"] == topic
                             and predicate(e["message"]), timeout)

    def channels(self) -> dict[str, dict]:
        return {e["channel"]["topic"]: e["channel"] for e in self.events if e["event"] == "advertise"}

    def stderr(self) -> str:
        if self.proc.poll() is None:
            return ""
        return self.proc.stderr.read()[-2000:]

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.stdin.close()
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait(5)


def message_schema(kind: str, cid: str, level: str | None = None) -> dict:
    """The checked-in message schema (`morsec schema --messages`) of a component, at `level`."""
    document = json.loads((MESSAGE_SCHEMAS / kind / f"{cid}.schema.json").read_text(encoding="utf-8"))
    if level is None:
        return document
    return {"$schema": document["$schema"], **document["$defs"][level]}


def near(a: float, b: float, tolerance: float = 1e-6) -> bool:
    return abs(a - b) <= tolerance


@pytest.mark.parametrize("scene", ["foxglove_rover.yaml", "foxglove_rover.py"])
def test_foxglove_client_watches_the_rover_driven_by_a_client(scene, foxglove_client, tmp_path):
    port = free_port()
    with Morsec(REPO / "scenes" / scene, tmp_path, args=("--foxglove", "--foxglove-port", port)) as sim:
        (line,) = [x for x in sim.stdout if x.startswith("  foxglove ")]
        assert line.startswith(f"  foxglove       ws://{HOST}:{port}  (open in Foxglove: https://")
        watcher = Watcher(f"ws://{HOST}:{port}")
        try:
            # the subprotocol foxglove-sdk speaks, the simulated clock, and the channels, each with its schema
            opened = watcher.wait_for("connection", lambda e: e["event"] == "open")
            assert opened["protocol"] == "foxglove.sdk.v1"
            info = watcher.wait_for("server info", lambda e: e["event"] == "serverInfo")
            assert "time" in info["capabilities"] and info["name"].startswith("morsec ")
            watcher.wait_for("every channel", lambda e: CHANNELS.keys() <= watcher.channels().keys())
            channels = watcher.channels()
            for topic, (encoding, schema_name, schema_encoding) in CHANNELS.items():
                got = channels[topic]
                assert (got["encoding"], got["schemaName"], got["schemaEncoding"]) == (encoding, schema_name,
                                                                                       schema_encoding), topic
            assert channels["/rover/pose"]["schema"] == message_schema("sensors", "pose")
            assert channels["/rover/odometry"]["schema"] == message_schema("sensors", "odometry", "integrated")
            assert channels["/rover/motion"]["schema"] == message_schema("actuators", "motion_vw")
            assert not [e for e in watcher.events if e["event"] == "error"]

            # the laser, at rest, sees the room's east wall (x = 15 m) 14.5 m ahead of it
            scan = watcher.message("/rover/sick")["message"]
            assert len(scan["ranges"]) == 181 and scan["frameId"] == "rover.sick"
            assert near(scan["startAngle"], -math.pi / 2) and near(scan["endAngle"], math.pi / 2)
            assert abs(scan["ranges"][90] - 14.5) < 0.05

            # the scene: the room (floor and walls), the boxes, the rover's bodies, each locked to its frame
            scene_update = watcher.message("/scene")["message"]
            entities = {e["id"]: e for e in scene_update["entities"]}
            assert {"world", "RedBox", "BlueBox", "GreenBox", "rover", "rover/wheel_fl"} <= entities.keys()
            assert all(e["frameLocked"] and e["frameId"] == e["id"] for e in entities.values())
            assert len(entities["world"]["cubes"]) >= 5  # the floor and four walls
            assert len(entities["RedBox"]["cubes"]) == 1

            # cameras: an RGBA picture, and the depth camera's points in its optical frame
            image = watcher.message("/rover/camera")["message"]
            assert (image["width"], image["height"], image["encoding"], image["step"]) == (160, 120, "rgba8", 640)
            assert image["data"]["bytes"] == 160 * 120 * 4 and image["frameId"] == "rover.camera"
            cloud = watcher.message("/rover/depth")["message"]
            assert cloud["pointStride"] == 12 and [f["name"] for f in cloud["fields"]] == ["x", "y", "z"]
            assert {f["type"] for f in cloud["fields"]} == {"FLOAT32"}
            assert cloud["data"]["bytes"] > 0 and cloud["data"]["bytes"] % 12 == 0
            assert cloud["pose"]["orientation"] == {"x": -0.5, "y": 0.5, "z": -0.5, "w": 0.5}

            # JSON streams: valid against their schema, logged at their simulated timestamp
            first = watcher.message("/rover/pose")
            jsonschema.validate(first["message"], channels["/rover/pose"]["schema"])
            assert abs(int(first["logTime"]) - first["message"]["timestamp"] * 1e9) < 1e3
            watcher.wait_for("time", lambda e: e["event"] == "time")

            # a client drives the rover on its socket stream: Foxglove sees the command and the pose move
            with sim.stream("rover.motion") as motion:
                motion.send('{"v": 1.0, "w": 0.0}\n')
                command = watcher.message("/rover/motion")["message"]
                assert command == {"v": 1.0, "w": 0.0}
                moved = watcher.message("/rover/pose", lambda m: m["x"] > 0.5)
            assert moved["message"]["timestamp"] > first["message"]["timestamp"]

            # the transform tree: the rover in the world where the pose sensor says, its parts on it
            tf = watcher.message("/tf", lambda m: any(t["childFrameId"] == "rover" and t["translation"]["x"] > 0.5
                                                      for t in m["transforms"]))
            transforms = {t["childFrameId"]: t for t in tf["message"]["transforms"]}
            parents = {child: t["parentFrameId"] for child, t in transforms.items()}
            assert parents["rover"] == "world"
            assert {parents[c] for c in ("rover.sick", "rover.camera", "rover.pose", "rover/wheel_fl")} == {"rover"}
            sick = transforms["rover.sick"]["translation"]
            assert near(sick["x"], 0.5) and near(sick["y"], 0.0) and near(sick["z"], 0.4)
            pose = watcher.message("/rover/pose", lambda m: abs(m["timestamp"] * 1e9 - int(tf["logTime"])) < 1e3)
            assert abs(transforms["rover"]["translation"]["x"] - pose["message"]["x"]) < 1e-3
        finally:
            watcher.close()


SENSOR_KINDS = """\
environment: {name: empty, time: {strategy: best_effort}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: ldmrs, type: sick_ld_mrs, translate: [0.5, 0.0, 0.4]}
      - {name: upright, type: video_camera, translate: [0.6, 0.0, 0.6], properties: {cam_width: 64, cam_height: 48}}
      - name: flipped
        type: video_camera
        translate: [0.6, 0.0, 0.6]
        properties: {cam_width: 64, cam_height: 48, Vertical_Flip: false}
      - {name: depth_image, type: depth_video_camera, translate: [0.6, 0.0, 0.7], properties: {cam_width: 64, cam_height: 48}}
      - {name: kinect, type: kinect, translate: [0.6, 0.0, 0.8], properties: {cam_width: 32, cam_height: 24}}
"""


def test_foxglove_client_decodes_every_kind_of_sensor(foxglove_client, tmp_path):
    """A layered laser as a point cloud, depth pictures in metres, a kinect's two pictures, and pictures
    delivered bottom row first (Vertical_Flip: false) turned back: top row first, as Foxglove draws them."""
    port = free_port()
    scene = tmp_path / "kinds.yaml"
    scene.write_text(SENSOR_KINDS, encoding="utf-8")
    with Morsec(scene, tmp_path, args=("--foxglove", "--foxglove-port", port)):
        watcher = Watcher(f"ws://{HOST}:{port}")
        try:
            expected = {"/robot/ldmrs": "foxglove.PointCloud", "/robot/upright": "foxglove.RawImage",
                        "/robot/flipped": "foxglove.RawImage", "/robot/depth_image": "foxglove.RawImage",
                        "/robot/kinect/rgb": "foxglove.RawImage", "/robot/kinect/depth": "foxglove.RawImage"}
            watcher.wait_for("every channel", lambda e: expected.keys() <= watcher.channels().keys())
            assert {t: watcher.channels()[t]["schemaName"] for t in expected} == expected
            assert "/robot/kinect" not in watcher.channels()

            cloud = watcher.message("/robot/ldmrs")["message"]
            assert cloud["data"]["bytes"] == 1604 * 12 and cloud["frameId"] == "robot.ldmrs"  # 4 layers of 401 rays

            upright = watcher.message("/robot/upright")["message"]
            flipped = watcher.message("/robot/flipped")["message"]
            assert flipped["encoding"] == "rgba8" and flipped["data"]["bytes"] == 64 * 48 * 4
            assert flipped["data"]["head"] == upright["data"]["head"], "the same top row, whichever way delivered"

            depth = watcher.message("/robot/depth_image")["message"]
            assert (depth["encoding"], depth["step"], depth["data"]["bytes"]) == ("32FC1", 64 * 4, 64 * 48 * 4)
            top_row = np.frombuffer(base64.b64decode(depth["data"]["head"]), dtype="<f4")
            assert np.all(top_row == 20.0), "the top row sees the sky: cam_far (depth pictures come bottom row first)"

            rgb = watcher.message("/robot/kinect/rgb")["message"]
            kinect_depth = watcher.message("/robot/kinect/depth")["message"]
            assert (rgb["encoding"], rgb["width"], rgb["height"]) == ("rgba8", 32, 24)
            assert (kinect_depth["encoding"], kinect_depth["data"]["bytes"]) == ("32FC1", 32 * 24 * 4)
        finally:
            watcher.close()


def test_optical_frame_of_a_camera_turned_by_yaw():
    """A camera's optical axes (x right, y down, z forward) in its component's frame, turned by yaw."""
    from morsec.runtime.foxglove.streams import optical_quaternion

    for yaw in (0.0, math.radians(60), -math.radians(60)):
        x, y, z, w = optical_quaternion(yaw)
        rotation = np.array(_matrix((w, x, y, z)))
        forward, left = np.array([math.cos(yaw), math.sin(yaw), 0.0]), np.array([-math.sin(yaw), math.cos(yaw), 0.0])
        assert np.allclose(rotation @ [0, 0, 1], forward)  # optical z: where the camera looks
        assert np.allclose(rotation @ [1, 0, 0], -left)  # optical x: to the right
        assert np.allclose(rotation @ [0, 1, 0], [0, 0, -1])  # optical y: down


# ---------------------------------------------------------------- the Python side

def test_body_frames_compose_back_to_mujocos_world_poses(tmp_path):
    """Each body's transform in its parent's frame, chained from the world, gives the pose MuJoCo computed."""
    from morsec.runtime.foxglove.world import BodyFrames

    model = mujoco.MjModel.from_xml_string("""
    <mujoco><worldbody>
      <body name="base" pos="1 2 0.5" euler="0.3 -0.2 1.1"><freejoint/><geom size="0.1"/>
        <body name="arm" pos="0.2 0 0.3" euler="0 0.4 0"><joint type="hinge" axis="0 0 1"/><geom size="0.05"/>
          <body name="hand" pos="0 0.5 0"><joint type="hinge" axis="1 0 0"/><geom size="0.02"/></body>
        </body>
      </body>
    </worldbody></mujoco>""")
    data = mujoco.MjData(model)
    data.qpos[:] = [0.5, -1.0, 2.0, *np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2]),
                    0.7, -1.2]
    mujoco.mj_kinematics(model, data)
    frames = BodyFrames(model)
    translation, rotation = frames.relative(data)
    assert frames.names == ["world", "base", "arm", "hand"]
    world_pos = {0: np.zeros(3)}
    world_quat = {0: np.array([1.0, 0, 0, 0])}
    for i, (child, parent) in enumerate(zip(frames.child, frames.parent)):
        moved = np.zeros(3)
        mujoco.mju_rotVecQuat(moved, translation[i], world_quat[parent])
        world_pos[child] = world_pos[parent] + moved
        world_quat[child] = np.zeros(4)
        mujoco.mju_mulQuat(world_quat[child], world_quat[parent], rotation[i])
        assert np.allclose(world_pos[child], data.xpos[child], atol=1e-12)
        same = np.isclose(abs(np.dot(world_quat[child], data.xquat[child])), 1.0, atol=1e-12)
        assert same, (child, world_quat[child], data.xquat[child])
    assert [(frames.names[p], frames.names[c]) for c, p in zip(frames.child, frames.parent)] == [
        ("world", "base"), ("base", "arm"), ("arm", "hand")]


MESH = "0 0 0  1 0 0  0 1 0  0 0 1"  # a tetrahedron


def test_scene_draws_every_geom_kind_in_its_bodys_frame(tmp_path):
    from morsec.runtime.foxglove.world import SceneGeometry

    model = mujoco.MjModel.from_xml_string(f"""
    <mujoco>
      <asset><mesh name="tetra" vertex="{MESH}"/></asset>
      <worldbody>
        <geom type="plane" size="0 0 1" rgba="0.2 0.3 0.4 1"/>
        <body name="thing" pos="0 0 1">
          <geom type="box" size="0.1 0.2 0.3" pos="1 0 0" rgba="1 0 0 1"/>
          <geom type="sphere" size="0.25"/>
          <geom type="ellipsoid" size="0.1 0.2 0.3"/>
          <geom type="cylinder" size="0.1 0.4"/>
          <geom type="capsule" size="0.1 0.4" euler="90 0 0"/>
          <geom type="mesh" mesh="tetra"/>
          <geom type="box" size="1 1 1" group="3"/>
          <geom type="box" size="1 1 1" rgba="1 1 1 0"/>
        </body>
      </worldbody>
    </mujoco>""")
    geometry = SceneGeometry(model)
    assert set(geometry.bodies) == {"world", "thing"}
    geometry.message(3.5)  # foxglove-sdk's SceneUpdate of it
    world, thing = geometry.bodies["world"], geometry.bodies["thing"]
    (floor,) = world
    assert floor.kind == "cube" and floor.size[:2] == (100.0, 100.0)  # an infinite plane, drawn 100 m wide
    assert floor.rgba == pytest.approx((0.2, 0.3, 0.4, 1.0))
    kinds = [s.kind for s in thing]
    assert kinds.count("cube") == 1, "collision-only (group 3) and invisible geoms are not drawn"
    (box,) = [s for s in thing if s.kind == "cube"]
    assert box.size == pytest.approx((0.2, 0.4, 0.6)) and box.position == (1.0, 0.0, 0.0)
    spheres = [s for s in thing if s.kind == "sphere"]  # the sphere, the ellipsoid, the capsule's two ends
    assert sorted(round(s.size[2], 6) for s in spheres) == [0.2, 0.2, 0.5, 0.6]
    ends = sorted(round(s.position[1], 6) for s in spheres if s.size[2] == pytest.approx(0.2))
    assert ends == [-0.4, 0.4]  # the capsule lies along y: its ends' centres 0.4 m either side
    cylinders = [s for s in thing if s.kind == "cylinder"]
    assert len(cylinders) == 2 and all(c.size[2] == pytest.approx(0.8) for c in cylinders)
    (mesh,) = [s for s in thing if s.kind == "model"]
    count = struct.unpack_from("<I", mesh.data, 80)[0]
    triangles = np.frombuffer(mesh.data, dtype=[("n", "<f4", 3), ("p", "<f4", (3, 3)), ("a", "<u2")], offset=84)
    assert count == len(triangles) == 4
    body_points = triangles["p"].reshape(-1, 3) @ np.array(_matrix(mesh.quat)).T + np.array(mesh.position)
    corners = np.array(MESH.split(), float).reshape(-1, 3)
    assert all(np.min(np.linalg.norm(corners - p, axis=1)) < 1e-5 for p in body_points)


def _matrix(quat) -> list[float]:
    out = np.zeros(9)
    mujoco.mju_quat2Mat(out, np.asarray(quat, float))
    return out.reshape(3, 3).tolist()


def test_json_streams_send_nan_as_null():
    import foxglove

    from morsec.runtime.foxglove.streams import JsonStream

    stream = JsonStream("robot.gps", foxglove.Context(), "/robot/gps", "morsec.sensors.gps", {"type": "object"})
    try:
        sent = stream.convert({"timestamp": 1.0, "x": float("nan"), "list": np.array([1.0, np.inf])})
        assert json.loads(sent) == {"timestamp": 1.0, "x": None, "list": [1.0, None]}
    finally:
        stream.close()


def _run(tmp_path: Path, *args: str, python: list[str] | None = None) -> subprocess.CompletedProcess:
    build = build_scene(REPO / "scenes" / "foxglove_rover.yaml", tmp_path / "build")
    command = (python or [str(Path(sys.executable).with_name("morsec"))]) + [
        "run", str(build), "--duration", "0.5", "--time-strategy", "fixed_step", "--port-base", "0",
        "--service-port", "0", *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=120, env=dict(os.environ))


def test_a_busy_foxglove_port_is_one_line(tmp_path):
    port = free_port()
    holder = occupy(port)
    try:
        result = _run(tmp_path, "--foxglove", "--foxglove-port", str(port))
    finally:
        holder.close()
    assert result.returncode == 1
    assert result.stderr.strip().splitlines() == [
        f"error: --foxglove: cannot serve on {HOST}:{port}: Address already in use (os error 98) (--foxglove-port "
        "picks another port, 0 one the OS picks)"]


def test_foxglove_without_the_sdk_says_what_to_install(tmp_path):
    hide = "import sys; sys.modules['foxglove'] = None; from morsec.cli import main; main(sys.argv[1:])"
    result = _run(tmp_path, "--foxglove", "--foxglove-port", "0", python=[sys.executable, "-c", hide])
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [
        "error: --foxglove needs the foxglove-sdk package: pip install foxglove-sdk (or pip install "
        "'morsec[foxglove]')"]

