"""What every camera sensor shares (MORSE's `morse.sensors.camera.Camera`): the camera model, the
offscreen renderers, depth images turned into points, and the capture state of MORSE's VideoCamera.

* **Geometry.** MORSE's cameras are Blender cameras: a 32 mm wide sensor across the *larger* image side
  and a lens of `cam_focal` mm (or a field of view `cam_fov` across that side). In pixels
  fx = fy = max(w, h) / 2 / tan(fov / 2) = max(w, h) * focal / 32, and the principal point is the image
  centre (w / 2, h / 2). The MJCF camera of a component looks along the component's +x with +z up
  (MuJoCo cameras look along their own -z, +y up: `xyaxes="0 -1 0 0 0 1"`), and its `fovy` is
  2 atan(h / 2 / fy): the intrinsic matrix is the one of the rendered picture, pixel for pixel.
* **Rendering.** `mujoco.Renderer` (EGL, else OSMesa: `morsec/__init__.py` chooses), one per image size
  and per simulation, shared by every camera of that size (`RendererPool`), opened when the sensor
  starts: a camera that cannot render stops the start of the simulation with `open_renderer`'s
  one-line message naming the missing system package. Each camera sets the clip planes
  (`cam_near`, `cam_far`) for its own render (MuJoCo has one pair per model: `vis.map.znear/zfar`,
  restored right after) and renders without shadows or reflections unless its `shadows` property is on.
* **Depth.** MuJoCo's depth buffer (reversed z) is linearised as mujoco.Renderer does (`linear_depth`):
  metres along the optical axis (planar depth, the z of the point in the camera frame), `cam_far` where
  nothing was drawn. Points are expressed in the
  optical frame of the camera: x right, y down, z forward (MORSE: "X and Y are in the image plane,
  and Z is the depth axis"), at pixel centres: x = z (u + 0.5 - cx) / fx, y = z (v + 0.5 - cy) / fy with
  u the column from the left and v the row from the top of the picture.
"""

from __future__ import annotations

import base64
import math
import weakref
from collections.abc import Callable
from typing import Any, ClassVar

import numpy as np
from pydantic import Field, model_validator

from morsec.component.contract import ComponentProperties, DataField, Sensor
from morsec.component.services import async_service, service
from morsec.errors import MorsecError

SENSOR_WIDTH_MM = 32.0  # Blender's camera sensor (MORSE's BLENDER_HORIZONTAL_APERTURE)
# the MJCF camera's axes in its component's frame: image x (right) = -y, image y (up) = +z; it looks along +x
XYAXES = "0 -1 0 0 0 1"
# optical frame (x right, y down, z forward) -> component frame (x forward, y left, z up)
OPTICAL_TO_COMPONENT = np.array([[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]])


# ------------------------------------------------------------------------------------------ geometry
def focal_pixels(width: int, height: int, focal: float, fov: float = 0.0) -> float:
    """fx = fy in pixels. `fov` (degrees, across the larger side) wins over `focal` (mm) when > 0."""
    half = max(width, height) / 2.0
    if fov > 0.0:
        return half / math.tan(math.radians(fov) / 2.0)
    return half * focal / (SENSOR_WIDTH_MM / 2.0)


def intrinsic_matrix(width: int, height: int, focal: float, fov: float = 0.0) -> list[list[float]]:
    """MORSE's 3x3 intrinsic matrix, row major: [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]."""
    f = focal_pixels(width, height, focal, fov)
    return [[f, 0.0, width / 2.0], [0.0, f, height / 2.0], [0.0, 0.0, 1.0]]


def fovy_degrees(width: int, height: int, focal: float, fov: float = 0.0) -> float:
    """MuJoCo's vertical field of view for that picture (MuJoCo takes the horizontal one from the aspect)."""
    return math.degrees(2.0 * math.atan(height / 2.0 / focal_pixels(width, height, focal, fov)))


def optical_rotation(yaw: float) -> np.ndarray:
    """Rotation of points from the optical frame of a camera turned by `yaw` (rad, about the component's
    +z, to the left) into the optical frame of the camera not turned."""
    c, s = math.cos(yaw), math.sin(yaw)
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return OPTICAL_TO_COMPONENT.T @ rz @ OPTICAL_TO_COMPONENT


# fields of the cameras' socket messages, declared once
PICTURE_SIZE = (
    DataField("height", 0, "int", "picture height, pixels (cam_height)"),
    DataField("width", 0, "int", "picture width, pixels (cam_width)"),
)
INTRINSIC_MATRIX = DataField("intrinsic_matrix", [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "mat3",
                             "intrinsic calibration matrix of the picture, row major: [[fx, 0, cx], [0, fy, cy], "
                             "[0, 0, 1]], pixels: fx = fy = max(w, h) * cam_focal / 32 (a 32 mm sensor across the "
                             "larger side, Blender's), or max(w, h) / 2 / tan(cam_fov / 2) when cam_fov is set; "
                             "cx = w / 2, cy = h / 2")


class CameraProperties(ComponentProperties):
    """MORSE's Camera properties (`camera.py`), with the VideoCamera builder's defaults."""

    cam_width: int = Field(256, ge=1, description="image width, pixels (read at start; at most the scene's "
                           "offscreen buffer, 1920)")
    cam_height: int = Field(256, ge=1, description="image height, pixels (read at start; at most the scene's "
                            "offscreen buffer, 1080)")
    cam_focal: float = Field(35.0, gt=0, description="focal length, mm, for a 32 mm sensor across the larger "
                             "image side (read at start); 35 is MORSE's builder default (its core default 25 is "
                             "not used)")
    cam_fov: float = Field(0.0, ge=0, lt=180, description="field of view across the larger image side, deg; "
                           "0: not set (MORSE's None), cam_focal decides; when set it wins over cam_focal")
    cam_near: float = Field(0.1, gt=0, description="near clipping distance, m: nothing nearer is drawn")
    cam_far: float = Field(100.0, gt=0, description="far clipping distance, m: nothing farther is drawn")
    Vertical_Flip: bool = Field(True, description="true: the image's first row is the top of the picture; false: "
                                "the bottom (OpenGL's order)")
    capturing: bool = Field(True, description="grab images (MORSE toggles it with the Space key; here "
                            "set_property); false: no image, no message")
    retrieve_depth: bool = Field(False, description="MORSE's switch to a depth buffer; accepted, no effect: "
                                 "the component type decides what is rendered (depth_camera, depth_video_camera)")
    retrieve_zbuffer: bool = Field(False, description="MORSE's raw z-buffer switch; accepted, no effect")
    shadows: bool = Field(False, description="render shadows and reflections (off by default: sensor cameras "
                          "render without them, faster; MuJoCo's viewer draws them)")

    @model_validator(mode="after")
    def _clip_planes(self):
        if self.cam_far <= self.cam_near:
            raise ValueError(f"cam_far ({self.cam_far}) must be larger than cam_near ({self.cam_near})")
        return self

    # derived values, for the MJCF template (`properties.fovy`) and the sensor
    @property
    def focal_pixels(self) -> float:
        return focal_pixels(self.cam_width, self.cam_height, self.cam_focal, self.cam_fov)

    @property
    def fovy(self) -> float:
        return fovy_degrees(self.cam_width, self.cam_height, self.cam_focal, self.cam_fov)

    @property
    def intrinsic_matrix(self) -> list[list[float]]:
        return intrinsic_matrix(self.cam_width, self.cam_height, self.cam_focal, self.cam_fov)


class DepthCameraProperties(CameraProperties):
    """MORSE's DepthCamera builder defaults: clip planes 1 and 20 m, depth, no vertical flip."""

    cam_near: float = Field(1.0, gt=0, description="near clipping distance, m: nothing closer is seen")
    cam_far: float = Field(20.0, gt=0, description="far clipping distance, m: nothing farther is seen")
    retrieve_depth: bool = Field(True, description="MORSE's depth switch; accepted, no effect")
    Vertical_Flip: bool = Field(False, description="true: the image's first row is the top of the picture; false: "
                                "the bottom (OpenGL's order, MORSE's depth default)")


# ------------------------------------------------------------------------------------------ rendering
class RendererPool:
    """The offscreen renderers of one simulation: one `mujoco.Renderer` per image size, shared by every
    camera of that size (cameras render one after the other, on the loop thread)."""

    def __init__(self, model):
        self.model = model
        self.renderers: dict[tuple[int, int], Any] = {}

    def get(self, width: int, height: int):
        key = (int(width), int(height))
        renderer = self.renderers.get(key)
        if renderer is None:
            from morsec.kits.render import open_renderer
            renderer = open_renderer(self.model, key[0], key[1])
            self.renderers[key] = renderer
        return renderer

    def close(self) -> None:
        for renderer in self.renderers.values():
            renderer.close()
        self.renderers.clear()


_POOLS: weakref.WeakKeyDictionary[Any, RendererPool] = weakref.WeakKeyDictionary()


def renderer_pool(sim) -> RendererPool:
    pool = _POOLS.get(sim)
    if pool is None:
        pool = _POOLS[sim] = RendererPool(sim.model)
    return pool


def close_renderers(sim) -> None:
    pool = _POOLS.pop(sim, None)
    if pool is not None:
        pool.close()


_OPTION = None


def _scene_option():
    """What sensor cameras see: MuJoCo's default visualisation (geom groups 0-2, no sites, no contacts)."""
    global _OPTION
    if _OPTION is None:
        import mujoco
        _OPTION = mujoco.MjvOption()
    return _OPTION


class CameraView:
    """One MJCF camera of a component with its picture size and intrinsics, rendering through the pool."""

    def __init__(self, sim, camera: str, width: int, height: int, focal: float, fov: float = 0.0):
        import mujoco
        self.sim = sim
        self.name = camera
        self.id = mujoco.mj_name2id(sim.model, mujoco.mjtObj.mjOBJ_CAMERA, camera)
        if self.id < 0:
            raise ValueError(f"scene.xml has no camera {camera!r}: rebuild the scene")
        self.width, self.height = int(width), int(height)
        self.fx = focal_pixels(self.width, self.height, focal, fov)
        self.matrix = intrinsic_matrix(self.width, self.height, focal, fov)
        # the picture is what the intrinsics say, whatever fovy scene.xml was written with
        sim.model.cam_fovy[self.id] = fovy_degrees(self.width, self.height, focal, fov)
        try:
            self.renderer = renderer_pool(sim).get(self.width, self.height)
        except MorsecError as err:  # the simulation's start reports it as "<component>: <message>"
            raise ValueError(" ".join(err.message.split())) from None

    @classmethod
    def of(cls, sim, camera: str, p: CameraProperties) -> CameraView:
        return cls(sim, camera, p.cam_width, p.cam_height, p.cam_focal, p.cam_fov)

    def _render(self, depth: bool, near: float, far: float, effects: bool) -> np.ndarray:
        """One picture in OpenGL's row order (bottom row first): h x w x 3 uint8 RGB, or h x w float32
        depth in metres along the optical axis (`far` where nothing was drawn)."""
        import mujoco
        m, d, r = self.sim.model, self.sim.data, self.renderer
        # the loop runs mj_kinematics before sensors; camera poses come from mj_camlight
        mujoco.mj_camlight(m, d)
        vis, extent = m.vis.map, float(m.stat.extent)
        saved = (vis.znear, vis.zfar)
        vis.znear, vis.zfar = near / extent, far / extent
        try:
            r.update_scene(d, camera=self.id, scene_option=_scene_option())
            flags = r.scene.flags
            flags[mujoco.mjtRndFlag.mjRND_SHADOW] = bool(effects)
            flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = bool(effects)
            gl = _gl_parts(r)
            if gl is None:  # a renderer without the classic internals: its own readback (top row first)
                if depth:
                    r.enable_depth_rendering()
                else:
                    r.disable_depth_rendering()
                return np.ascontiguousarray(r.render()[::-1])
            context, rect, gl_context = gl
            # depth: MuJoCo's segmentation mode draws flat colours, no lighting (mujoco.Renderer does the same)
            flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = depth
            flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = depth
            try:
                if gl_context is not None:
                    gl_context.make_current()
                mujoco.mjr_render(rect, r.scene, context)
                if not depth:
                    rgb = np.empty((self.height, self.width, 3), dtype=np.uint8)
                    mujoco.mjr_readPixels(rgb, None, rect, context)
                    return rgb
                buf = np.empty((self.height, self.width), dtype=np.float32)
                mujoco.mjr_readPixels(None, buf, rect, context)
                return linear_depth(buf, float(vis.znear) * extent, float(vis.zfar) * extent)
            finally:
                flags[mujoco.mjtRndFlag.mjRND_SEGMENT] = 0
                flags[mujoco.mjtRndFlag.mjRND_IDCOLOR] = 0
        finally:
            vis.znear, vis.zfar = saved

    def rgba(self, p: CameraProperties) -> np.ndarray:
        """A fresh RGBA picture, height x width x 4 uint8, alpha 255, rows as `Vertical_Flip` says."""
        rgb = self._render(False, p.cam_near, p.cam_far, p.shadows)
        image = np.empty((self.height, self.width, 4), dtype=np.uint8)
        image[..., :3] = rgb[::-1] if p.Vertical_Flip else rgb
        image[..., 3] = 255
        return image

    def depth(self, p: CameraProperties) -> np.ndarray:
        """A fresh depth image, height x width float32, metres along the optical axis (cam_far: nothing),
        rows as `Vertical_Flip` says (true: a reversed view of the buffer)."""
        depth = self._render(True, p.cam_near, p.cam_far, False)
        return depth[::-1] if p.Vertical_Flip else depth


def _gl_parts(renderer):
    """(MjrContext, MjrRect, GL context or None) of a classic mujoco.Renderer, to read its buffers without
    the copies and the float64 depth conversion of Renderer.render(); None for another renderer."""
    context, rect = getattr(renderer, "_mjr_context", None), getattr(renderer, "_rect", None)
    if context is None or rect is None:
        return None
    return context, rect, getattr(renderer, "_gl_context", None)


def linear_depth(buffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """MuJoCo's depth buffer (reversed z: 1 at the near plane, 0 at the far one, `readDepthMap` ZEROFAR)
    to metres along the optical axis, in place: z = far near / (b (far - near) + near). This is
    mujoco.Renderer's conversion, in float32 (relative error ~1e-7)."""
    near, far = np.float32(near), np.float32(far)
    np.multiply(buffer, far - near, out=buffer)
    buffer += near
    np.divide(far * near, buffer, out=buffer)
    return buffer


# ------------------------------------------------------------------------------------------ depth -> points
def parse_keep_list(text: str, height: int) -> list[int]:
    """MORSE's `keep_list` ("[1, 17, 34]" or "1, 17, 34"): the image rows kept; empty: every row."""
    text = text.strip().strip("[]()").strip()
    if not text:
        return list(range(height))
    try:
        rows = [int(item) for item in text.split(",") if item.strip()]
    except ValueError:
        raise ValueError(f"keep_list must list row numbers, e.g. '[1, 17, 34]' (got {text!r})") from None
    bad = [r for r in rows if not 0 <= r < height]
    if bad:
        raise ValueError(f"keep_list rows {bad} are outside the image (0..{height - 1})")
    return rows


def pixel_rays(width: int, height: int, fx: float, rows: list[int], vertical_flip: bool) -> np.ndarray:
    """2 x (len(rows) * width) float32: for each kept pixel, in row-major order, x and y of its point at depth
    1 in the optical frame: (u + 0.5 - cx) / fx and (v + 0.5 - cy) / fy. `rows` index the image as
    delivered (top first when `vertical_flip`, bottom first otherwise)."""
    rows_arr = np.asarray(rows, dtype=np.float64)
    v = rows_arr if vertical_flip else (height - 1 - rows_arr)  # row from the top of the picture
    u = np.arange(width, dtype=np.float64)
    x = np.broadcast_to((u + 0.5 - width / 2.0) / fx, (len(rows), width))
    y = np.broadcast_to(((v + 0.5 - height / 2.0) / fx)[:, None], (len(rows), width))
    return np.ascontiguousarray(np.stack([x.reshape(-1), y.reshape(-1)]), dtype=np.float32)


def depth_points(depth: np.ndarray, rows: list[int] | None, rays: np.ndarray, far: float,
                 keep_resolution: bool) -> np.ndarray:
    """Points (N x 3 float32, optical frame) of the kept rows (None: all) of a depth image, `rays` from
    `pixel_rays`. Pixels that saw nothing within `far` are dropped (MORSE), or NaN when `keep_resolution`
    (one point per kept pixel)."""
    z = np.ascontiguousarray((depth if rows is None else depth[rows]).reshape(-1), dtype=np.float32)
    points = np.empty((len(z), 3), dtype=np.float32)
    np.multiply(rays[0], z, out=points[:, 0])  # column by column: 2x faster than broadcasting N x 3
    np.multiply(rays[1], z, out=points[:, 1])
    points[:, 2] = z
    hit = z < far * (1.0 - 1e-4)
    if hit.all():
        return points
    if keep_resolution:
        points[~hit] = np.nan
        return points
    return points[hit]


def b64(array) -> str:
    """Base64 text of an array's bytes (row-major, native little-endian on every platform MuJoCo runs on);
    "" before the first picture."""
    if array is None:
        return ""
    if isinstance(array, (bytes, bytearray)):
        return base64.b64encode(array).decode("ascii")
    return base64.b64encode(np.ascontiguousarray(array).tobytes()).decode("ascii")


# ------------------------------------------------------------------------------------------ capture
class CameraSensor(Sensor):
    """MORSE's VideoCamera capture logic, for every sensor that grabs pictures.

    A tick grabs when the `capturing` property is on and no `capture(n)` count has run out: `capture(n)`
    grabs n pictures (one per tick, at the sensor's frequency), then completes and stops grabbing (as
    MORSE: the camera is then idle until the next `capture`); n < 0 grabs until cancelled; n = 0
    completes at once and stops grabbing. A tick that did not grab publishes nothing (MORSE's empty
    message). Subclasses implement `grab()` (render, fill `local_data`) and `message()` (the socket
    message)."""

    Properties: ClassVar[type[ComponentProperties]] = CameraProperties
    frequency = 20.0

    def start(self) -> None:
        self.capturing = False  # did the last tick grab a picture
        self._n = -1  # pictures left to grab; negative: no limit
        self._done: Callable[[], None] | None = None

    def finalize(self) -> None:
        close_renderers(self.sim)

    # ---- the tick
    def default_action(self) -> None:
        if not (self.properties.capturing and self._n != 0):
            self.capturing = False
            return
        self.grab()
        self.capturing = True
        if self._n > 0:
            self._n -= 1
            if self._n == 0:
                self._finish()

    def grab(self) -> None:
        raise NotImplementedError

    # ---- capture(n)
    def start_capture(self, n: int, done: Callable[[], None] | None = None) -> None:
        """Grab `n` pictures, then call `done` (a stereo unit drives its cameras with this)."""
        self._n = int(n)
        self._done = done
        if self._n == 0:
            self._finish()

    def _finish(self) -> None:
        done, self._done = self._done, None
        if done is not None:
            done()

    @async_service
    def capture(self, n: int) -> None:
        """Grab `n` pictures (one per tick), then answer SUCCESS and stop grabbing; n < 0: until cancelled."""
        self.start_capture(n, lambda: self.completed("SUCCESS"))

    def interrupt(self) -> None:
        self._n = 0
        self._done = None

    # ---- what goes on the wire
    def message(self) -> dict:
        raise NotImplementedError

    def serialize(self) -> dict | None:
        return self.message() if self.capturing else None

    @service
    def get_local_data(self) -> dict:
        """The last data this camera computed, as its socket message (pictures in base64)."""
        return self.message()
