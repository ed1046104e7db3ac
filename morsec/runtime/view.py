"""`morsec run --view web|native`: watch the running simulation, drawn as the environment's display settings
say (morsec.kits.display: the viewport mode, show_physics, the camera, the frame rate and debug overlays,
auto_start's pause, fullscreen).

web: MuJoCo Studio's web viewer (no display needed), on the simulation's bind address (127.0.0.1 by
default; Studio itself would listen on every interface), with a morsec panel (run/pause, the overlays).
native: mujoco.viewer's window (needs a display). Either is synced from the simulation loop at most `rate`
times per wall-clock second; the loop runs no frame while the view is paused."""

from __future__ import annotations

import logging
import os
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from morsec.errors import RuntimeFailure
from morsec.kits import display
from morsec.kits.mjcf_names import DEFAULT_CAMERA
from morsec.runtime.keys import KEYS, KeyState

log = logging.getLogger("morsec.display")

# GLFW's key codes (the native viewer's key callback) of the keys components read
GLFW_KEYS = {265: "up", 264: "down", 263: "left", 262: "right", **{ord(k.upper()): k for k in KEYS if len(k) == 1}}
GLFW_SPACE = 32
FRAME_RATE_WINDOW = 0.5  # wall-clock s over which the frame rate shown is measured
WEB_READY_WAIT = 20.0  # wall-clock s the web viewer is given to take the model
CLOSE_WAIT = 5.0  # wall-clock s a closing native viewer is given to end its render thread


@dataclass
class Status:
    """What the overlays show, read from the simulation when the view syncs."""

    sim_time: float
    frames: int
    debug: list[tuple[str, str]] = field(default_factory=list)  # (name, value) rows, when show_debug


class View:
    """A viewer of the simulation. `paused` is the viewer's pause (space), which the loop obeys; `rows`, the
    overlay's rows by place ("framerate", "debug", "paused"), are recomputed at each sync."""

    kind = ""

    def __init__(self, environment: dict, status: Callable[[bool], Status], rate: float = 30.0):
        self.paused = not environment.get("auto_start", True)
        self.show_framerate = bool(environment.get("show_framerate"))
        self.show_debug = bool(environment.get("show_debug"))
        self.rows: dict[str, list[tuple[str, str]]] = {}
        self._status = status
        self._period = 1.0 / rate
        self._next = 0.0
        self._measured: tuple[float, int, float] | None = None  # (wall, frames, sim time) at the last measure
        self._rate = (0.0, 0.0)  # frames per wall-clock second, real-time factor

    def toggle_pause(self) -> None:
        self.paused = not self.paused
        log.info("%s", "paused" if self.paused else "running")

    def sync(self) -> None:
        now = time.perf_counter()
        if now >= self._next:
            self._next = now + self._period
            self.rows = self._overlay(now)
            self._push()

    def _overlay(self, now: float) -> dict[str, list[tuple[str, str]]]:
        status = self._status(self.show_debug)
        rows: dict[str, list[tuple[str, str]]] = {}
        if self.paused:
            rows["paused"] = [(f"PAUSED ({self.resume_hint})", "")]
        if self.show_framerate:
            if self._measured is None:
                self._measured = (now, status.frames, status.sim_time)
            wall, frames, sim_time = self._measured
            if now - wall >= FRAME_RATE_WINDOW:
                self._rate = ((status.frames - frames) / (now - wall), (status.sim_time - sim_time) / (now - wall))
                self._measured = (now, status.frames, status.sim_time)
            rows["framerate"] = [("frame rate", f"{self._rate[0]:.0f} Hz"),
                                 ("simulated time", f"{status.sim_time:.2f} s"),
                                 ("real-time factor", f"{self._rate[1]:.2f}")]
        if self.show_debug:
            rows["debug"] = status.debug
        return rows

    resume_hint = "space runs it"

    def _push(self) -> None:
        raise NotImplementedError

    def close(self) -> None:
        raise NotImplementedError


ViewKind = Literal["web", "native"]


def open_view(kind: str, model, data, bind: str, port: int, environment: dict,
              keys: KeyState | None = None, status: Callable[[bool], Status] | None = None) -> View:
    """Open a viewer of the simulation; the keys held in it go to `keys` (for MORSE's Keyboard actuator)."""
    keys = keys if keys is not None else KeyState()
    status = status or (lambda debug: Status(float(data.time), 0))
    if kind == "native":
        return NativeView(model, data, environment, keys, status)
    if kind == "web":
        return WebView(model, data, bind, port, environment, keys, status)
    raise RuntimeFailure(f"unknown view {kind!r}: use web or native")


class NativeView(View):
    kind = "native"

    def __init__(self, model, data, environment: dict, keys: KeyState, status: Callable[[bool], Status]):
        super().__init__(environment, status)
        if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
            raise RuntimeFailure("--view native needs a display (DISPLAY is not set); use --view web, or run under "
                                 "Xvfb")
        import mujoco
        import mujoco.viewer

        def key(code: int) -> None:
            if code == GLFW_SPACE:
                self.toggle_pause()
            keys.tap(GLFW_KEYS.get(code, ""))

        before = set(threading.enumerate())
        try:
            self.viewer = mujoco.viewer.launch_passive(model, data, show_left_ui=False, show_right_ui=False,
                                                       key_callback=key)
        except Exception as err:
            raise RuntimeFailure(f"cannot open the native viewer: {err}") from None
        # the viewer's render thread: close() waits for it, or the process could exit while it still draws
        # (a segmentation fault at exit, one run in two)
        self._threads = [t for t in threading.enumerate() if t not in before]
        self._mujoco = mujoco
        look = display.look(environment)
        with self.viewer.lock():
            self.viewer.opt.geomgroup[:] = look.option.geomgroup
            self.viewer.opt.flags[:] = look.option.flags
            for flag, value in look.flags.items():  # the viewer copies its user scene's flags into its own
                self.viewer.user_scn.flags[flag] = value
            camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, DEFAULT_CAMERA)
            if camera >= 0:
                self.viewer.cam.type = mujoco.mjtCamera.mjCAMERA_FIXED
                self.viewer.cam.fixedcamid = camera
        if environment.get("fullscreen"):
            from morsec.runtime.x11 import press_in_own_windows
            # mujoco.viewer has no call for it: its own full-screen key (F5), sent to its window
            if not press_in_own_windows(X11_F5):
                log.warning("fullscreen: cannot reach the viewer's window (full screen needs X11); the window "
                            "stays as it is")
        keys.source = "native"
        self.sync()

    def _push(self) -> None:
        mj = self._mujoco
        place = {"paused": mj.mjtGridPos.mjGRID_TOP, "framerate": mj.mjtGridPos.mjGRID_TOPRIGHT,
                 "debug": mj.mjtGridPos.mjGRID_BOTTOMLEFT}
        texts = [(mj.mjtFontScale.mjFONTSCALE_150, place[where], "\n".join(n for n, _ in rows),
                  "\n".join(v for _, v in rows)) for where, rows in self.rows.items() if rows]
        if texts:
            self.viewer.set_texts(texts)
        else:
            self.viewer.clear_texts()
        self.viewer.sync()

    def close(self) -> None:
        self.viewer.close()
        for thread in self._threads:
            thread.join(CLOSE_WAIT)


X11_F5 = 0xFFC2  # the X keysym of F5


class WebView(View):
    kind = "web"
    resume_hint = "space or the Run button runs it"

    def __init__(self, model, data, bind: str, port: int, environment: dict, keys: KeyState,
                 status: Callable[[bool], Status]):
        super().__init__(environment, status)
        try:
            from mujoco.studio import launch_passive, viewer_protocol
            from mujoco.studio.web import web_server
        except ImportError as err:
            raise RuntimeFailure(f"--view web needs MuJoCo Studio (pip install mujoco-studio): {err}") from None
        public = web_server.bind_public_socket
        # Studio binds every interface; morsec's servers listen where --bind says (127.0.0.1 by default).
        # The viewer binds from its own thread, so the override stays until the view closes.
        web_server.bind_public_socket = lambda host, p=0: public(bind, p)
        self._restore = lambda: setattr(web_server, "bind_public_socket", public)
        self.panel = _panel(self, keys, environment)
        try:
            self.handle = launch_passive.launch(
                viewer_protocol.ViewerConfig(gfx="web", http_port=port, title="morsec"), plugins=[self.panel])
            self.handle.set_model(model, data=data)
        except OSError as err:
            self._restore()
            raise RuntimeFailure(f"cannot start the web viewer on {bind}:{port}: {err}") from None
        self._model, self._data = model, data
        # ready once the viewer thread has the model: a browser on /ui before then could meet Studio's UI half
        # set up (ImGui's "font atlas is not built"), which closes the viewer
        end = time.monotonic() + WEB_READY_WAIT
        while not self.panel.model_shown and time.monotonic() < end:
            time.sleep(0.02)
        print(f"web viewer: http://{bind}:{port}/", flush=True)
        keys.source = "web"

    def _push(self) -> None:
        self.handle.sync(self._model, self._data)

    def close(self) -> None:
        self.handle.close()
        self._restore()


def _panel(view: View, keys: KeyState, environment: dict):
    """A MuJoCo Studio viewer plugin: on each viewer frame, reads the keys held in the browser (they reach the
    viewer's ImGui context through Studio's UI socket, /ui) into `keys`, space into the view's pause, and
    draws morsec's panel (run/pause, the overlays); once the model is in the viewer, draws it as the display
    settings say. `drawn` holds the panel's last rows, `looks` the viewer options set (read back by tests)."""
    import mujoco
    from mujoco.studio import messages, plugin
    from mujoco.studio.dear_imgui import dear_imgui as imgui

    named = {"up": "UpArrow", "down": "DownArrow", "left": "LeftArrow", "right": "RightArrow"}
    watched = [(name, getattr(imgui.Key, named.get(name, name.upper()))) for name in KEYS]
    look = display.look(environment)

    def on_model(self, event) -> None:
        viewer = self.viewer
        viewer.vis_options.geomgroup[:] = look.option.geomgroup
        viewer.vis_options.flags[:] = look.option.flags
        flags = list(viewer.render_flags.flags)  # a copy: set back whole (in mjtRndFlag's order)
        for flag, value in look.flags.items():
            flags[flag] = value
        viewer.render_flags.flags = flags
        camera = mujoco.mj_name2id(event.model, mujoco.mjtObj.mjOBJ_CAMERA, DEFAULT_CAMERA)
        if camera >= 0:
            viewer.camera.type = mujoco.mjtCamera.mjCAMERA_FIXED
            viewer.camera.fixedcamid = camera
            viewer.camera_index = camera
        self.model_shown = True

    def on_update(self, event) -> None:
        keys.set_down(name for name, key in watched if imgui.IsKeyDown(key))
        if imgui.IsKeyPressed(imgui.Key.Space, False):
            view.toggle_pause()

    def on_gui(self, event) -> None:
        imgui.SetNextWindowPos(imgui.Vec2(10, 10), imgui.Cond.FirstUseEver)
        imgui.Begin("morsec", None, imgui.WindowFlags.AlwaysAutoResize)
        if imgui.Button("Run" if view.paused else "Pause"):
            view.toggle_pause()
        drawn = []
        for rows in view.rows.values():
            imgui.Separator()
            for name, value in rows:
                imgui.TextUnformatted(f"{name}: {value}" if value else name)
                drawn.append((name, value))
        imgui.End()
        self.drawn = drawn

    # Studio finds a handler's message type in its annotation, resolved in this module's globals, where
    # Studio's modules (imported here only) are not: give it the class itself
    on_model.__annotations__["event"] = messages.PostModelEvent
    on_update.__annotations__["event"] = messages.UpdateEvent
    on_gui.__annotations__["event"] = messages.BuildGuiEvent
    members = {"on_model": messages.handler(on_model), "on_update": messages.handler(on_update),
               "on_gui": messages.handler(on_gui), "drawn": (), "model_shown": False}
    return type("MorsecPanel", (plugin.ViewerPlugin,), members)()
