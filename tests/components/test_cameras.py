"""Cameras (video_camera, depth_camera, depth_video_camera, kinect, velodyne, vlp16, stereo_unit)
rendered headless by MuJoCo in running simulations, checked against numbers computable by hand: the pixels
a box of known size covers at a known distance, the depth of a wall, the points of a room's walls."""

from __future__ import annotations

import base64
import json
import math
import os
import socket
import subprocess
import sys
from pathlib import Path

import mujoco
import numpy as np
import pytest
from pydantic import ValidationError
from runtime_helpers import read_lines, stream_client

from morsec.component.catalogue import load_catalogue
from morsec.component.services import Request
from morsec.errors import RuntimeFailure
from morsec.kits.camera import CameraProperties, focal_pixels, fovy_degrees, intrinsic_matrix, optical_rotation
from morsec.testing import simulate

CATALOGUE = load_catalogue(Path(__file__).parent)
HEIGHT = 1.0  # of the fixed fake robot carrying the cameras
SMALL = "cam_width: 16, cam_height: 12"
# id: (builder name, frequency, cam_width, cam_height, cam_near, cam_far, Vertical_Flip)
CAMERAS = {
    "video_camera": ("VideoCamera", 20.0, 256, 256, 0.1, 100.0, True),
    "depth_camera": ("DepthCamera", 20.0, 256, 256, 1.0, 20.0, False),
    "depth_video_camera": ("DepthVideoCamera", 20.0, 256, 256, 1.0, 20.0, False),
    "semantic_camera": ("SemanticCamera", 20.0, 256, 256, 0.1, 100.0, True),
    "kinect": ("Kinect", 20.0, 128, 128, 0.1, 100.0, True),
    "velodyne": ("Velodyne", 20.0, 256, 256, 1.0, 20.0, False),
    "vlp16": ("VLP16_180", 10.0, 512, 256, 1.0, 20.0, False),
}


def holder_scene(components: str, objects: str = "", rotate=(0.0, 0.0, 0.0), env: str = "empty",
                 height: float = HEIGHT, at=(0.0, 0.0)) -> str:
    """A fixed fake robot at (x, y, height) carrying `components` (YAML flow mappings, one a line)."""
    comps = "\n".join(f"      - {c.strip()}" for c in components.strip().splitlines())
    objs = "\n".join(f"  - {o.strip()}" for o in objects.strip().splitlines())
    text = f"""environment: {{name: {env}, time: {{strategy: fixed_step}}}}
robots:
  - name: r
    type: fake_robot
    translate: [{at[0]}, {at[1]}, {height}]
    rotate: {list(rotate)}
    components:
{comps}
"""
    return text + (f"objects:\n{objs}\n" if objs else "")


def box(name: str, center, size, color=(1.0, 0.0, 0.0), properties: str = "") -> str:
    props = f", properties: {{{properties}}}" if properties else ""
    return (f"{{name: {name}, type: box, translate: {list(center)}, size: {list(size)}, "
            f"color: {list(color)}{props}}}")


def room(half: float = 3.0, height: float = 8.0) -> str:
    """Four walls whose inner faces are x = +-half and y = +-half, `height` tall from z = -1."""
    z = height / 2 - 1.0
    return "\n".join([
        box("east", (half + 0.5, 0.0, z), (1.0, 2 * half + 2, height), (0.7, 0.7, 0.7)),
        box("west", (-half - 0.5, 0.0, z), (1.0, 2 * half + 2, height), (0.7, 0.7, 0.7)),
        box("north", (0.0, half + 0.5, z), (2 * half, 1.0, height), (0.7, 0.7, 0.7)),
        box("south", (0.0, -half - 0.5, z), (2 * half, 1.0, height), (0.7, 0.7, 0.7)),
    ])


def grab_count(sim, fqn: str) -> list:
    """Record the simulated time of each picture a camera grabs."""
    instance = sim.component(fqn)
    calls = []
    grab = instance.grab

    def counted():
        calls.append(sim.time)
        grab()

    instance.grab = counted
    return calls


def call_async(sim, fqn: str, service: str, *args) -> list:
    """Start an asynchronous service as a client's request would, and run the frame with whose end it starts
    (MORSE's frame order, docs/running.md#time); the list receives (status, result)."""
    replies = []
    sim.sim.requests.handle(Request("1", fqn, service, list(args), lambda _id, status, result:
                                    replies.append((status, result))))
    sim.step()
    return replies


def red_mask(image: np.ndarray) -> np.ndarray:
    return (image[..., 0] > 128) & (image[..., 1] < 64) & (image[..., 2] < 64)


def projected(K, corners_cam: np.ndarray) -> tuple[float, float, float, float]:
    """(u0, u1, v0, v1): the image rectangle (pixel-edge coordinates) of a box face given by its corners in
    the optical frame (x right, y down, z forward), projected with the intrinsic matrix K."""
    uv = (np.asarray(K) @ (corners_cam / corners_cam[:, 2:3]).T).T
    return uv[:, 0].min(), uv[:, 0].max(), uv[:, 1].min(), uv[:, 1].max()


def pixels_inside(width: int, height: int, rect) -> tuple[np.ndarray, np.ndarray]:
    """(surely in, surely out): pixels entirely inside the rectangle, and pixels entirely outside it."""
    u0, u1, v0, v1 = rect
    c, r = np.arange(width), np.arange(height)
    col_in, row_in = (c >= u0) & (c + 1 <= u1), (r >= v0) & (r + 1 <= v1)
    col_out, row_out = (c + 1 <= u0) | (c >= u1), (r + 1 <= v0) | (r >= v1)
    return row_in[:, None] & col_in[None, :], row_out[:, None] | col_out[None, :]


def check_mask(mask: np.ndarray, rect) -> None:
    """The mask holds every pixel entirely inside the projected rectangle and none entirely outside it."""
    surely_in, surely_out = pixels_inside(mask.shape[1], mask.shape[0], rect)
    assert surely_in.any()
    assert mask[surely_in].all() and not mask[surely_out].any()


# ---------------------------------------------------------------- catalogue and geometry

@pytest.mark.parametrize("cid", sorted(CAMERAS) + ["stereo_unit"])
def test_camera_folders_and_defaults(cid):
    cls = CATALOGUE.get("sensors", cid)
    assert (cls.folder / "README.md").is_file() and (cls.folder / "model.xml.j2").is_file()
    assert cls.doc() and cls.short_descr
    if cid == "stereo_unit":
        assert cls.builder_name == "StereoUnit" and "capture" in cls.services()
        return
    builder, freq, width, height, near, far, flip = CAMERAS[cid]
    assert cls.builder_name == builder and CATALOGUE.resolve("sensors", builder) == cid
    assert cls.frequency == freq
    p = cls.Properties()
    assert (p.cam_width, p.cam_height, p.cam_near, p.cam_far, p.Vertical_Flip) == (width, height, near, far, flip)
    assert p.cam_fov == 0.0 and p.capturing is True and p.shadows is False
    assert p.cam_focal == (27.7 if cid == "vlp16" else 35.0)
    if cid != "semantic_camera":
        assert "capture" in cls.services()


def test_intrinsics_follow_blenders_camera():
    # fx = fy = max(w, h) * focal / 32, principal point at the centre
    assert intrinsic_matrix(256, 256, 35.0) == [[280.0, 0.0, 128.0], [0.0, 280.0, 128.0], [0.0, 0.0, 1.0]]
    assert intrinsic_matrix(320, 240, 32.0)[0] == [320.0, 0.0, 160.0]
    assert focal_pixels(240, 320, 32.0) == 320.0  # the larger side carries the 32 mm sensor
    # cam_fov (across the larger side) wins over cam_focal: 90 deg across 320 pixels -> fx = 160
    assert focal_pixels(320, 240, 35.0, 90.0) == pytest.approx(160.0)
    # MuJoCo's fovy: the vertical field of view of that picture
    assert fovy_degrees(320, 240, 35.0, 90.0) == pytest.approx(math.degrees(2 * math.atan(120 / 160)))
    with pytest.raises(ValidationError, match="cam_far"):
        CameraProperties(cam_near=5.0, cam_far=2.0)


def test_optical_rotation_turns_about_the_vertical():
    # a point straight ahead of a camera turned 90 deg to the left is, for the camera not turned, on its
    # left: x = -1 (x right), y = 0 (down), z = 0 (forward)
    assert optical_rotation(math.pi / 2) @ [0.0, 0.0, 1.0] == pytest.approx([-1.0, 0.0, 0.0], abs=1e-12)


def test_mjcf_camera_looks_along_the_components_x(tmp_path):
    scene = holder_scene("{name: cam, type: video_camera, translate: [0.1, 0.2, 0.3], rotate: [0.0, 0.0, 0.5],"
                         " properties: {cam_width: 64, cam_height: 48, cam_focal: 32.0}}")
    with simulate(scene, tmp_path) as sim:
        xml = (tmp_path / "build-scene" / "scene.xml").read_text()
        assert '<camera name="r.cam" xyaxes="0 -1 0 0 0 1" fovy="41.11209044"' in xml  # 2 atan(24 / 64)
        m, d = sim.sim.model, sim.sim.data
        mujoco.mj_camlight(m, d)
        cam = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_CAMERA, "r.cam")
        view = -d.cam_xmat[cam].reshape(3, 3)[:, 2]  # a MuJoCo camera looks along its -z
        assert view == pytest.approx([math.cos(0.5), math.sin(0.5), 0.0], abs=1e-9)
        assert d.cam_xpos[cam] == pytest.approx([0.1, 0.2, HEIGHT + 0.3], abs=1e-9)


# ---------------------------------------------------------------- video_camera

@pytest.mark.parametrize("lens", ["cam_focal: 32.0", "cam_fov: 53.13010235415598"])
@pytest.mark.parametrize("yaw", [0.0, math.pi / 2])
def test_box_covers_the_predicted_pixels(tmp_path, lens, yaw):
    """A 1 x 1 x 0.75 m red box whose near face is 4 m ahead: its corners projected with the intrinsic
    matrix (fx = 64 either way: 64 * 32 / 32, or 32 / tan(26.57 deg)) bound exactly the red pixels. The
    face's edges fall on pixel borders (u = 32 -+ 8, v = 20 and 32): every pixel is in or out."""
    center = (4.5 * math.cos(yaw), 4.5 * math.sin(yaw), 0.875)
    scene = holder_scene(f"{{name: cam, type: video_camera, properties: {{cam_width: 64, cam_height: 48, {lens}}}}}",
                         box("target", center, (1.0, 1.0, 0.75)), rotate=(0.0, 0.0, yaw))
    with simulate(scene, tmp_path) as sim:
        sim.step(3)
        data = sim.data("r.cam")
        K = data["intrinsic_matrix"]
        assert np.asarray(K) == pytest.approx(np.array([[64.0, 0.0, 32.0], [0.0, 64.0, 24.0], [0.0, 0.0, 1.0]]))
        image = data["image"]
        assert image.shape == (48, 64, 4) and image.dtype == np.uint8 and (image[..., 3] == 255).all()
        # near face corners in the optical frame: x right = -y_left, y down = -(z - HEIGHT), z = 4
        face = np.array([[-sy, -(z - HEIGHT), 4.0] for sy in (-0.5, 0.5) for z in (0.5, 1.25)])
        rect = projected(K, face)
        assert rect == pytest.approx((24.0, 40.0, 20.0, 32.0))
        surely_in, surely_out = pixels_inside(64, 48, rect)
        assert surely_in.sum() == 16 * 12 and (surely_in | surely_out).all()  # no pixel half covered
        assert (red_mask(image) == surely_in).all()


def test_vertical_flip_puts_the_bottom_row_first(tmp_path):
    """The box is below the optical axis: 0.1 to 0.9 m high, 4 m ahead of a camera 1 m up with fx = 32, its
    rows are v = 12 + 32 (1 - z) / 4, from 12.8 to 19.2: rows 13 to 18 with Vertical_Flip (default: row 0
    is the top of the picture); without, the picture is upside down."""
    lens = "cam_width: 32, cam_height: 24, cam_focal: 32.0"
    cams = f"""{{name: up, type: video_camera, properties: {{{lens}}}}}
               {{name: down, type: video_camera, properties: {{{lens}, Vertical_Flip: false}}}}"""
    with simulate(holder_scene(cams, box("target", (4.5, 0.0, 0.5), (1.0, 1.0, 0.8))), tmp_path) as sim:
        sim.step(3)
        up, down = sim.data("r.up")["image"], sim.data("r.down")["image"]
        assert list(np.nonzero(red_mask(up).any(axis=1))[0]) == [13, 14, 15, 16, 17, 18]
        assert (down == up[::-1]).all()


def step_until(sim, done, frames: int = 60) -> None:
    for _ in range(frames):
        if done():
            return
        sim.step()
    raise AssertionError("never happened")


def test_capture_grabs_n_pictures_then_answers(tmp_path):
    scene = holder_scene("{name: cam, type: video_camera, services: [socket], "
                         "properties: {cam_width: 16, cam_height: 12}}")
    with simulate(scene, tmp_path) as sim:
        cam = sim.component("r.cam")
        grabs = grab_count(sim, "r.cam")
        sim.step(6)
        assert len(grabs) >= 2 and cam.capturing  # capturing by default, at 20 Hz
        replies = call_async(sim, "r.cam", "capture", 3)
        before = len(grabs)  # (the frame with whose end the capture started grabbed as before)
        step_until(sim, lambda: replies)
        assert replies == [("SUCCESS", None)] and len(grabs) == before + 3  # answered with the third picture
        assert sim.data("r.cam")["timestamp"] == sim.sim.clock.now()
        sim.step(12)  # MORSE: after capture(n) the camera is idle until the next capture
        assert len(grabs) == before + 3 and not cam.capturing and cam.serialize() is None
        assert call_async(sim, "r.cam", "capture", 0) == [("SUCCESS", None)]  # as it starts
        replies = call_async(sim, "r.cam", "capture", -1)  # until cancelled
        sim.step(12)
        assert len(grabs) >= before + 6 and replies == [] and cam.capturing
        cam.properties.capturing = False  # MORSE's Space key
        grabbed = len(grabs)
        sim.step(12)
        assert len(grabs) == grabbed and cam.serialize() is None


def test_a_second_capture_while_one_runs_fails(tmp_path):
    """MORSE's asynchronous services without an interruption policy: the second request fails."""
    scene = holder_scene("{name: cam, type: video_camera, services: [socket], "
                         "properties: {cam_width: 16, cam_height: 12}}")
    with simulate(scene, tmp_path) as sim:
        first = call_async(sim, "r.cam", "capture", 2)
        second = call_async(sim, "r.cam", "capture", 1)
        assert second and second[0][0] == "FAILED" and "already running" in second[0][1]
        step_until(sim, lambda: first)
        assert first == [("SUCCESS", None)]



def test_socket_message_is_morses_and_silent_when_not_capturing(tmp_path):
    scene = holder_scene("{name: cam, type: video_camera, streams: [socket], "
                         "properties: {cam_width: 8, cam_height: 6}}",
                         box("target", (4.5, 0.0, 1.0), (1.0, 1.0, 1.0)))
    with simulate(scene, tmp_path) as sim:
        client = stream_client(sim, "r.cam")
        sim.step(3)
        line = read_lines(client)[-1]  # the last picture
        message = json.loads(line)
        assert list(message) == ["timestamp", "height", "width", "image", "intrinsic_matrix"]
        data = sim.data("r.cam")
        assert message["timestamp"] == data["timestamp"]
        assert (message["height"], message["width"]) == (6, 8)
        image = np.frombuffer(base64.b64decode(message["image"]), dtype=np.uint8).reshape(6, 8, 4)
        assert (image == data["image"]).all()
        assert message["intrinsic_matrix"] == [[8 * 35 / 32, 0.0, 4.0], [0.0, 8 * 35 / 32, 3.0], [0.0, 0.0, 1.0]]
        assert b'"timestamp": ' in line  # Python's default separators, as MORSE
        # the same message answers get_local_data
        assert sim.call("r.cam", "get_local_data")["image"] == message["image"]

        sim.call("r.cam", "set_property", "capturing", False)
        sim.step(9)
        client.settimeout(0.3)
        with pytest.raises(socket.timeout):
            client.recv(1 << 20)  # MORSE's empty message: nothing at all
        client.close()


def test_shadows_are_off_unless_asked(tmp_path):
    """The sandbox's sun (direction (-0.2, 0.2, -1), it casts shadows) throws the shadow of crate_1 (x 3.5..4.5,
    y 2.5..3.5, 1 m high) onto the floor strip y 3.5..3.7 beside it. Two cameras 2.5 m above the floor look
    straight down at that strip (picture up = +x, right = -y): with `shadows` on the strip is much darker
    than the floor next to it in the same checker square (y 3.8..3.9); off (default) they are alike."""
    width, at = 96, (3.4, 3.6, 2.5)
    fx = width * 35 / 32
    look_down = "rotate: [0.0, 1.5707963267948966, 0.0]"
    size = f"cam_width: {width}, cam_height: {width}"
    cams = f"""{{name: plain, type: video_camera, {look_down}, properties: {{{size}}}}}
               {{name: shaded, type: video_camera, {look_down}, properties: {{{size}, shadows: true}}}}"""

    def pixel(x, y):  # a floor point's pixel (row, column)
        return int(width / 2 - fx * (x - at[0]) / at[2]), int(width / 2 - fx * (y - at[1]) / at[2])

    with simulate(holder_scene(cams, env="sandbox", height=at[2], at=at[:2]), tmp_path) as sim:
        sim.step(3)
        ratios = {}
        for name in ("plain", "shaded"):
            brightness = sim.data(f"r.{name}")["image"][..., :3].astype(float).sum(axis=2)
            shadow = np.mean([brightness[pixel(x, y)] for x in (3.6, 3.75, 3.9) for y in (3.58, 3.65)])
            lit = np.mean([brightness[pixel(x, y)] for x in (3.6, 3.75, 3.9) for y in (3.8, 3.9)])
            ratios[name] = shadow / lit
        assert ratios["plain"] == pytest.approx(1.0, abs=0.05)
        assert ratios["shaded"] < 0.75


def test_a_camera_that_cannot_render_fails_the_start(tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise RuntimeError("eglInitialize failed\n(no EGL display)")

    monkeypatch.setattr(mujoco, "Renderer", broken)
    scene = holder_scene("{name: cam, type: video_camera, properties: {cam_width: 16, cam_height: 12}}")
    with pytest.raises(RuntimeFailure) as err:
        with simulate(scene, tmp_path):
            pass
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith("r.cam: cannot render with MUJOCO_GL=")
    assert "eglInitialize failed (no EGL display)" in message and "install lib" in message


def test_morsec_run_says_which_package_is_missing(tmp_path):
    """`morsec run` with a GL backend that cannot work here (GLFW without a display): exit code 1 and one
    error line naming the camera and the system packages."""
    (tmp_path / "s.yaml").write_text(holder_scene(
        "{name: cam, type: video_camera, properties: {cam_width: 16, cam_height: 12}}"))
    env = {k: v for k, v in os.environ.items() if k not in ("PYOPENGL_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY")}
    env.update(MUJOCO_GL="glfw", PYTHONWARNINGS="ignore")
    result = subprocess.run([sys.executable, "-m", "morsec", "run", "s.yaml", "--duration", "0.1",
                             "--time-strategy", "fixed_step", "--service-port", "0"],
                            cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert result.returncode == 1, result.stderr
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert len(errors) == 1, result.stderr
    assert errors[0].startswith("error: r.cam: cannot render with MUJOCO_GL=glfw")
    assert "install libegl1 or libosmesa6" in errors[0]


def test_offscreen_buffer_limit_is_reported(tmp_path):
    scene = holder_scene("{name: cam, type: video_camera, properties: {cam_width: 4000, cam_height: 100}}")
    with pytest.raises(RuntimeFailure, match=r"r.cam: image 4000x100 is larger than the scene's offscreen buffer"):
        with simulate(scene, tmp_path):
            pass


# ---------------------------------------------------------------- depth cameras

def test_depth_camera_points_on_a_wall(tmp_path):
    """A wall whose face is 3 m ahead fills the view: every pixel gives a point with z = 3 (within 1 cm),
    x and y as the pixel's ray says; keep_list keeps 3 rows; nothing within 2.5 m gives no point."""
    cams = """{name: dense, type: depth_camera, properties: {cam_width: 32, cam_height: 24}}
              {name: sparse, type: depth_camera, properties: {cam_width: 32, cam_height: 24, keep_list: "[0, 11, 23]"}}
              {name: short, type: depth_camera, properties: {cam_width: 32, cam_height: 24, cam_far: 2.5}}"""
    wall = box("wall", (3.5, 0.0, 1.0), (1.0, 20.0, 10.0), (0.7, 0.7, 0.7))
    with simulate(holder_scene(cams, wall), tmp_path) as sim:
        sim.step(3)
        dense = sim.data("r.dense")
        points = dense["points"]
        assert dense["nb_points"] == 32 * 24 and points.shape == (768, 3) and points.dtype == np.float32
        assert np.abs(points[:, 2] - 3.0).max() < 0.01
        fx = 32 * 35 / 32
        u, v = np.meshgrid(np.arange(32) + 0.5, np.arange(24) + 0.5)
        v = v[::-1]  # Vertical_Flip false (depth default): the first row is the bottom of the picture
        assert points[:, 0] == pytest.approx((3.0 * (u - 16) / fx).ravel(), abs=0.01)
        assert points[:, 1] == pytest.approx((3.0 * (v - 12) / fx).ravel(), abs=0.01)
        assert points[0, 0] < 0 and points[0, 1] > 0  # first point: bottom left (x right, y down)

        sparse = sim.data("r.sparse")
        assert sparse["nb_points"] == 3 * 32
        assert sparse["points"][32:64] == pytest.approx(points[11 * 32:12 * 32])
        assert sim.data("r.short")["nb_points"] == 0


def test_depth_camera_keep_resolution_and_socket_points(tmp_path):
    """The wall only fills the lower half (the camera is at its top edge): without keep_resolution only
    the lower rows give points; with it every pixel does, NaN above the edge."""
    size = "cam_width: 16, cam_height: 12"
    cams = f"""{{name: organized, type: depth_camera, streams: [socket], properties: {{{size}, keep_resolution: true}}}}
               {{name: plain, type: depth_camera, properties: {{{size}}}}}"""
    wall = box("wall", (3.5, 0.0, 0.0), (1.0, 20.0, 2.0), (0.7, 0.7, 0.7))  # top edge at z = 1 (the camera's)
    with simulate(holder_scene(cams, wall, env="empty"), tmp_path) as sim:
        client = stream_client(sim, "r.organized")
        sim.step(3)
        organized, plain = sim.data("r.organized"), sim.data("r.plain")
        assert organized["nb_points"] == 16 * 12
        rows = organized["points"].reshape(12, 16, 3)
        assert not np.isnan(rows[:6]).any() and np.isnan(rows[6:]).all()  # bottom rows first
        assert plain["nb_points"] == 16 * 6
        message = json.loads(read_lines(client)[-1])
        assert list(message) == ["timestamp", "height", "width", "points", "intrinsic_matrix"]
        decoded = np.frombuffer(base64.b64decode(message["points"]), dtype=np.float32).reshape(-1, 3)
        assert np.array_equal(decoded, organized["points"], equal_nan=True)
        client.close()


def test_depth_video_camera_gives_depth_along_the_optical_axis(tmp_path):
    """Depth is planar (z in the camera frame), not the distance to the pixel's point: a wall 3 m ahead
    reads 3.0 in every pixel, corners included; nothing within cam_far reads cam_far."""
    cams = """{name: depth, type: depth_video_camera, properties: {cam_width: 16, cam_height: 12}}
              {name: far, type: depth_video_camera, properties: {cam_width: 16, cam_height: 12, cam_far: 2.0}}"""
    wall = box("wall", (3.5, 0.0, 1.0), (1.0, 20.0, 10.0), (0.7, 0.7, 0.7))
    with simulate(holder_scene(cams, wall), tmp_path) as sim:
        sim.step(3)
        image = sim.data("r.depth")["image"]
        assert image.shape == (12, 16) and image.dtype == np.float32
        assert np.abs(image - 3.0).max() < 0.01
        assert (sim.data("r.far")["image"] == pytest.approx(2.0, abs=1e-3))


def test_kinect_pair_sees_the_box_from_two_places(tmp_path):
    """The RGB camera is 8 cm left of the component, the depth camera 8 cm right, both 6 cm forward and
    4 cm up: a box straight ahead (its face 3 m from the component) appears 64 * 0.08 / 2.94 = 1.7 pixels
    right of the centre in the RGB picture and as much left in the depth picture, whose depth is the box's
    (2.94 m) there and the wall's (5.94 m) elsewhere. The holder is 3 m up: no floor in view."""
    scene = holder_scene("{name: kinect, type: kinect, properties: {cam_width: 64, cam_height: 48, cam_focal: 32.0}}",
                         box("target", (3.5, 0.0, 3.04), (1.0, 0.5, 0.5)) + "\n"
                         + box("wall", (6.5, 0.0, 3.0), (1.0, 20.0, 10.0), (0.7, 0.7, 0.7)), height=3.0)
    with simulate(scene, tmp_path) as sim:
        sim.step(3)
        data = sim.data("r.kinect")
        rgb, depth = data["rgb"]["image"], data["depth"]["image"]
        assert rgb.shape == (48, 64, 4) and depth.shape == (48, 64)
        assert data["rgb"]["intrinsic_matrix"] == data["depth"]["intrinsic_matrix"]
        assert np.asarray(data["rgb"]["intrinsic_matrix"]) == pytest.approx(
            np.array([[64.0, 0.0, 32.0], [0.0, 64.0, 24.0], [0.0, 0.0, 1.0]]))
        d = 3.0 - 0.06
        for mask, camera_y in ((red_mask(rgb), 0.08), (depth < 4.0, -0.08)):
            face = np.array([[-(sy - camera_y), -(z - 3.04), d] for sy in (-0.25, 0.25) for z in (2.79, 3.29)])
            rect = projected(data["rgb"]["intrinsic_matrix"], face)
            assert (rect[0] + rect[1]) / 2 == pytest.approx(32 + 64 * camera_y / d)  # 1.7 pixels off centre
            check_mask(mask, rect)
        assert depth[21:27, 30:34] == pytest.approx(np.full((6, 4), d), abs=0.01)
        assert depth[:, :5] == pytest.approx(np.full((48, 5), 6.0 - 0.06), abs=0.01)
        message = sim.component("r.kinect").message()
        assert list(message) == ["timestamp", "rgb", "depth"]
        assert list(message["depth"]) == ["timestamp", "height", "width", "image", "intrinsic_matrix"]
        decoded = np.frombuffer(base64.b64decode(message["depth"]["image"]), dtype=np.float32).reshape(48, 64)
        assert (decoded == depth).all()


def _azimuths(points: np.ndarray) -> np.ndarray:
    """Azimuth (rad, from the component's +x, to the left) of optical-frame points: atan2(-x, z)."""
    return np.arctan2(-points[:, 0], points[:, 2])


def _on_walls(points: np.ndarray, half: float = 3.0) -> np.ndarray:
    """max(|forward|, |left|) of optical-frame points: `half` for points on the room's walls."""
    return np.maximum(np.abs(points[:, 2]), np.abs(points[:, 0]))


def test_velodyne_depth_turns_and_keeps_its_frame(tmp_path):
    """In a 6 x 6 m room, the k-th picture (k = 0 first) looks at azimuth k * rotation: its points all lie
    on the walls and, in the fixed mounting frame, within half a field of view of that azimuth."""
    scene = holder_scene("{name: velo, type: velodyne, properties: {cam_width: 32, cam_height: 16, "
                         "rotation: 1.0}}", room(), height=2.0)
    fov = 2 * math.atan(16 / 35)  # across the 32 pixels
    with simulate(scene, tmp_path) as sim:
        velo = sim.component("r.velo")
        assert CATALOGUE.get("sensors", "velodyne").Properties().rotation == pytest.approx(fov)
        grabs = grab_count(sim, "r.velo")
        seen = set()
        for _ in range(8):
            sim.step(3)
            k = len(grabs) - 1  # the last picture
            assert velo.azimuth == pytest.approx(((k + 1) * 1.0) % (2 * math.pi))  # turned after it
            data = sim.data("r.velo")
            points = data["points"]
            assert data["nb_points"] == 32 * 16
            assert np.abs(_on_walls(points) - 3.0).max() < 0.02
            azimuth = (k * 1.0 + math.pi) % (2 * math.pi) - math.pi
            offset = (_azimuths(points) - azimuth + math.pi) % (2 * math.pi) - math.pi
            assert np.abs(offset).max() < fov / 2 + 0.02
            seen.add(k)
        assert len(seen) >= 6


def test_vlp16_merges_three_cameras_in_the_middle_ones_frame(tmp_path):
    scene = holder_scene("{name: vlp, type: vlp16, properties: {cam_width: 64, cam_height: 32, "
                         "keep_list: '[2, 10, 16, 22, 29]'}}", room(), height=2.0)
    with simulate(scene, tmp_path) as sim:
        assert CATALOGUE.get("sensors", "vlp16").Properties().keep_list.count(",") == 15  # 16 rows
        sim.step(6)
        data = sim.data("r.vlp")
        points = data["points"]
        assert data["nb_points"] == 3 * 64 * 5 and not np.isnan(points).any()
        assert np.abs(_on_walls(points) - 3.0).max() < 0.02
        azimuth = _azimuths(points)
        fx = 64 * 27.7 / 32
        half = math.atan(32 / fx)  # 30 deg
        for i in range(3):  # camera i covers azimuths (i - 1) * 60 deg +- 30 deg, camera 0 first
            part = azimuth[i * 320:(i + 1) * 320]
            assert np.abs(part - (i - 1) * math.pi / 3).max() < half + 0.02
        # kept row 16 (rows counted from the bottom: Vertical_Flip false) is row 15 from the top, half a
        # pixel above the axis: y = 3 (15.5 - 16) / fx on the wall ahead
        middle = points[320:640].reshape(5, 64, 3)
        assert middle[2, 32, 1] == pytest.approx(3.0 * (15.5 - 16) / fx, abs=0.01)


# ---------------------------------------------------------------- stereo_unit

def test_stereo_unit_captures_with_all_its_cameras(tmp_path):
    scene = f"""environment: {{name: empty, time: {{strategy: fixed_step}}}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, {HEIGHT}]
    components:
      - name: stereo
        type: stereo_unit
        translate: [0.0, 0.0, 0.2]
        services: [socket]
        components:
          - {{name: left, type: video_camera, translate: [0.0, 0.2, 0.0], properties: {{{SMALL}}}}}
          - {{name: right, type: video_camera, translate: [0.0, -0.2, 0.0], properties: {{{SMALL}}}}}
      - {{name: lonely, type: stereo_unit, services: [socket]}}
"""
    with simulate(scene, tmp_path) as sim:
        left, right = grab_count(sim, "r.stereo.left"), grab_count(sim, "r.stereo.right")
        assert sim.component("r.stereo.left").position() == pytest.approx([0.0, 0.2, HEIGHT + 0.2])
        sim.step(3)
        assert len(left) == len(right) >= 1  # capturing by default
        replies = call_async(sim, "r.stereo", "capture", 2)
        before = len(left)
        step_until(sim, lambda: len(left) == before + 1)
        assert replies == [] and len(right) == before + 1
        step_until(sim, lambda: replies)
        assert replies == [("SUCCESS", None)] and len(left) == len(right) == before + 2
        sim.step(12)
        assert len(left) == len(right) == before + 2  # both idle after their capture
        failed = call_async(sim, "r.lonely", "capture", 1)
        assert failed[0][0] == "FAILED" and "no camera" in failed[0][1]


def test_bad_clip_planes_are_scene_errors(build_yaml):
    from morsec.errors import SceneError
    with pytest.raises(SceneError, match=r"scene.yaml:\d+:\d+: .*cam_far \(2.0\) must be larger than cam_near \(5.0\)"):
        build_yaml(holder_scene("{name: cam, type: video_camera, properties: {cam_near: 5.0, cam_far: 2.0}}"))
    with pytest.raises(SceneError, match=r"depth_far \(0.5\) must be larger than depth_near \(1.0\)"):
        build_yaml(holder_scene("{name: k, type: kinect, properties: {depth_far: 0.5}}"))


def test_text_stream_writes_the_camera_message(tmp_path):
    scene = holder_scene("{name: cam, type: video_camera, streams: [text], properties: {cam_width: 4, cam_height: 2}}")
    with simulate(scene, tmp_path) as sim:
        sim.step(3)
        image = sim.data("r.cam")["image"]
    text = next(tmp_path.glob("*.txt")).read_text()
    assert f"image = {base64.b64encode(image.tobytes()).decode()}\n" in text
    assert "height = 2\nwidth = 4\n" in text


def test_cameras_render_when_mujoco_was_imported_first(tmp_path):
    """MuJoCo picks its GL backend when first imported; a program that imported it before morsec got GLFW
    (needs a display). The cameras still render, with the headless backend morsec chose."""
    (tmp_path / "s.yaml").write_text(holder_scene(f"{{name: cam, type: video_camera, properties: {{{SMALL}}}}}"))
    script = f"""
import mujoco
import morsec
from pathlib import Path
from morsec.testing import simulate
with simulate(Path({str(tmp_path / "s.yaml")!r}).read_text(), Path({str(tmp_path)!r})) as sim:
    sim.step(3)
    print(sim.data("r.cam")["image"].shape)
"""
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM", "DISPLAY")}
    result = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "(12, 16, 4)"


def _horizontal_shift(before: np.ndarray, after: np.ndarray, largest: int) -> int:
    """The shift (pixels, positive: content moved right) that best lines `after` up with `before`."""
    a = before[..., :3].astype(float).mean(axis=2)
    b = after[..., :3].astype(float).mean(axis=2)
    errors = {s: float(np.mean((a[:, max(0, -s):a.shape[1] - max(0, s)] - b[:, max(0, s):b.shape[1] - max(0, -s)]) ** 2))
              for s in range(-largest, largest + 1)}
    return min(errors, key=errors.get)


def test_the_camera_sees_the_room_turn_as_the_robot_turns(tmp_path):
    """The intent of MORSE's base/video_camera_testing.py (which compares with pictures Blender rendered):
    a camera on a robot that turns left by a small angle sees the room move right in its picture, by the
    focal length times the tangent of the angle; turning right moves it left."""
    width, turn = 128, 0.12
    scene = holder_scene(f"""{{name: cam, type: video_camera, properties: {{cam_width: {width}, cam_height: 96}}}}
                             {{name: tele, type: teleport}}""", env="indoors-1/boxes", at=(-8.0, 0.0))
    shots = {}
    with simulate(scene, tmp_path) as sim:
        for yaw in (0.0, turn, -turn):
            sim.command("r.tele", x=-8.0, y=0.0, z=HEIGHT, roll=0.0, pitch=0.0, yaw=yaw)
            sim.step(3)
            shots[yaw] = sim.data("r.cam")["image"].copy()
    expected = focal_pixels(width, 96, 35.0) * math.tan(turn)
    assert _horizontal_shift(shots[0.0], shots[turn], 40) == pytest.approx(expected, abs=3)
    assert _horizontal_shift(shots[0.0], shots[-turn], 40) == pytest.approx(-expected, abs=3)
