"""`morsec run --view web|native`: watch the running simulation.

web: MuJoCo Studio's web viewer (no display needed), on the simulation's bind address (127.0.0.1 by
default; Studio itself would listen on every interface). native: mujoco.viewer's window (needs a display).
Either is synced from the simulation loop at most `rate` times per wall-clock second."""

from __future__ import annotations

import os
import sys
import time
from typing import Literal

from morsec.errors import RuntimeFailure
from morsec.kits.mjcf_names import DEFAULT_CAMERA
from morsec.runtime.keys import KEYS, KeyState

# GLFW's key codes (the native viewer's key callback) of the keys components read
GLFW_KEYS = {265: "up", 264: "down", 263: "left", 262: "right", **{ord(k.upper()): k for k in KEYS if len(k) == 1}}


class View:
    def __init__(self, handle, sync, close, rate: float = 30.0):
        self._handle = handle
        self._sync = sync
        self._close = close
        self._period = 1.0 / rate
        self._next = 0.0

    def sync(self) -> None:
        now = time.perf_counter()
        if now >= self._next:
            self._next = now + self._period
            self._sync()

    def close(self) -> None:
        self._close()


ViewKind = Literal["web", "native"]


def open_view(kind: str, model, data, bind: str, port: int, display_options: dict,
              keys: KeyState | None = None) -> View:
    """Open a viewer of the simulation; the keys held in it go to `keys` (for MORSE's Keyboard actuator)."""
    keys = keys if keys is not None else KeyState()
    if kind == "native":
        return _native(model, data, display_options, keys)
    if kind == "web":
        return _web(model, data, bind, port, keys)
    raise RuntimeFailure(f"unknown view {kind!r}: use web or native")


def _native(model, data, display_options: dict, keys: KeyState) -> View:
    if sys.platform.startswith("linux") and not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        raise RuntimeFailure("--view native needs a display (DISPLAY is not set); use --view web, or run under Xvfb")
    import mujoco
    import mujoco.viewer
    try:
        viewer = mujoco.viewer.launch_passive(model, data, show_left_ui=False, show_right_ui=False,
                                              key_callback=lambda code: keys.tap(GLFW_KEYS.get(code, "")))
    except Exception as err:
        raise RuntimeFailure(f"cannot open the native viewer: {err}") from None
    with viewer.lock():
        if display_options.get("show_physics"):
            viewer.opt.geomgroup[3] = 1
            viewer.opt.flags[mujoco.mjtVisFlag.mjVIS_CONTACTPOINT] = 1
        camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, DEFAULT_CAMERA)
        if camera >= 0:
            viewer.cam.type = mujoco.mjtCamera.mjCAMERA_FIXED
            viewer.cam.fixedcamid = camera
    keys.source = "native"
    return View(viewer, viewer.sync, viewer.close)


def _key_reader(keys: KeyState):
    """A MuJoCo Studio viewer plugin reading, on each viewer frame, the keys held in the browser (they reach
    the viewer's ImGui context through Studio's UI socket, /ui) into `keys`."""
    from mujoco.studio import messages, plugin
    from mujoco.studio.dear_imgui import dear_imgui as imgui

    named = {"up": "UpArrow", "down": "DownArrow", "left": "LeftArrow", "right": "RightArrow"}
    watched = [(name, getattr(imgui.Key, named.get(name, name.upper()))) for name in KEYS]

    def on_update(self, event) -> None:
        keys.set_down(name for name, key in watched if imgui.IsKeyDown(key))

    # Studio finds a handler's message type in its annotation, resolved in this module's globals, where
    # Studio's modules (imported here only) are not: give it the class itself
    on_update.__annotations__["event"] = messages.UpdateEvent
    reader = type("KeyReader", (plugin.ViewerPlugin,), {"on_update": messages.handler(on_update)})
    return reader()


def _web(model, data, bind: str, port: int, keys: KeyState) -> View:
    try:
        from mujoco.studio import launch_passive, viewer_protocol
        from mujoco.studio.web import web_server
    except ImportError as err:
        raise RuntimeFailure(f"--view web needs MuJoCo Studio (pip install mujoco-studio): {err}") from None
    public = web_server.bind_public_socket
    # Studio binds every interface; morsec's servers listen where --bind says (127.0.0.1 by default).
    # The viewer binds from its own thread, so the override stays until the view closes.
    web_server.bind_public_socket = lambda host, p=0: public(bind, p)

    def close() -> None:
        handle.close()
        web_server.bind_public_socket = public

    try:
        handle = launch_passive.launch(viewer_protocol.ViewerConfig(gfx="web", http_port=port, title="morsec"),
                                       plugins=[_key_reader(keys)])
        handle.set_model(model, data=data)
    except OSError as err:
        web_server.bind_public_socket = public
        raise RuntimeFailure(f"cannot start the web viewer on {bind}:{port}: {err}") from None
    print(f"web viewer: http://{bind}:{port}/", flush=True)
    keys.source = "web"
    return View(handle, lambda: handle.sync(model, data), close)
