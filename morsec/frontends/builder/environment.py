"""MORSE's Environment: the world, time, the viewer camera, global settings, and `create()`.

Constructing it names every component after the script's variables (MORSE's `_rename_components`),
so `robot.name` is final from then on (e.g. for `configure_multinode`'s distribution).
"""

from __future__ import annotations

import atexit
import os
import sys
from typing import Any

from morsec.frontends.builder import session as _session
from morsec.frontends.builder.components import AbstractComponent, _float, _plain, _vector


class TimeStrategies:
    """set_time_strategy(TimeStrategies.BestEffort | TimeStrategies.FixedSimulationStep)."""

    BestEffort = 0
    FixedSimulationStep = 1


_STRATEGIES = {0: "best_effort", 1: "fixed_step", "BestEffort": "best_effort", "FixedSimulationStep": "fixed_step",
               "best_effort": "best_effort", "fixed_step": "fixed_step"}


def morse_environment(filename: str, ids: list[str]) -> str | None:
    """The catalogue environment a MORSE script names, as MORSE's Environment() takes it: its path under
    MORSE's data/environments, with or without `.blend` and the `environments/` folder, or a path to MORSE's
    own file (`/usr/share/morse/data/environments/indoors-1/indoor-1.blend`); or only the file's name when one
    catalogue environment has it (`indoor-1`, `tum_kitchen.blend`). None: no catalogue environment."""
    text = filename.replace("\\", "/").removesuffix(".blend")
    if "environments/" in text:
        text = text.rsplit("environments/", 1)[1]
    if text in ids:
        return text
    if "/" in text:
        return None
    named = [eid for eid in ids if eid.rsplit("/", 1)[-1] == text]
    return named[0] if len(named) == 1 else None


class Environment(AbstractComponent):
    """Environment(filename, fastmode=False, ...): must be created once, after the robots."""

    _kind = "environment"

    def __init__(self, filename="empty", main_scene=None, fastmode=False, component_renaming=True,
                 auto_tune_time=True):
        self._start(register=False)
        session = self._session
        if session.environment is not None:
            first = session.environment._position[1]
            raise session.error(f"only one Environment per scene (the first one is at line {first})")
        session.environment = self
        self._created = False
        self._set_world(filename)
        if fastmode:
            self._put("fastmode", value=True)
        if not auto_tune_time:
            self._put("time", "auto_tune", value=False)
        if main_scene:
            session.morse_only(None, "Environment", {"main_scene": main_scene},
                               "(main_scene=) selects a scene of a .blend file")
        if not component_renaming:
            session.morse_only(None, "Environment", {"component_renaming": False},
                               "(component_renaming=False) is ignored: components are always named as MORSE names "
                               "them by default")
        session.scan(session.caller_frame())
        session.assign_names()
        if session.standalone:
            atexit.register(_create_at_exit, self)

    def _set_world(self, filename) -> None:
        text = str(filename)
        found = morse_environment(text, self._session.catalogue.ids("environments"))
        if found is not None:
            self._put("name", value=found)
            return
        if text.endswith(".blend") or os.path.isabs(text):
            from morsec.frontends.builder.components import asset_search_path, find_asset
            if find_asset(text, asset_search_path(self._session.script)) is not None:
                self._session.morse_only(None, "Environment", {"filename": text},
                                         "loads a Blender file; the scene uses the 'empty' environment instead")
                return
        # neither a catalogue environment nor a file: the scene's validation says so, with "did you mean"
        self._put("name", value=text.replace("\\", "/").removesuffix(".blend"))

    def _default_label(self) -> str:
        return "environment"

    def _emit_type(self) -> str | None:
        return None

    def _emit(self, prefix: tuple, smap) -> dict:
        if self._position[1]:
            smap.values[prefix] = (self._position[1], self._position[2] or 1)
            smap.keys[prefix] = smap.values[prefix]
        for path, pos in self._where.items():
            smap.values[prefix + path] = pos
            smap.keys[prefix + path] = pos
        import copy
        return copy.deepcopy(self._raw)

    # ---- camera

    def set_camera_location(self, location):
        """Viewer camera position [x, y, z], m."""
        self._put("camera", "location", value=_vector(location))

    def set_camera_rotation(self, rotation):
        """Viewer camera XYZ Euler rotation, rad (Blender camera convention: looks along -Z)."""
        self._put("camera", "rotation", value=_vector(rotation))

    def place_camera(self, location):
        """Deprecated MORSE name of set_camera_location."""
        self.set_camera_location(location)

    def aim_camera(self, rotation):
        """Deprecated MORSE name of set_camera_rotation."""
        self.set_camera_rotation(rotation)

    def set_camera_clip(self, clip_start=0.1, clip_end=100):
        self._put("camera", "clip", value=[_float(clip_start), _float(clip_end)])

    def set_camera_speed(self, speed=2.0):
        self._put("camera", "speed", value=_float(speed))

    def set_camera_focal_length(self, focal_length=20.0):
        self._put("camera", "focal", value=_float(focal_length))

    def select_display_camera(self, robot_camera):
        self._session.morse_only(None, "select_display_camera", {"robot_camera": robot_camera},
                                 "shows a camera on Blender's HUD")

    # ---- display

    def show_framerate(self, value=True):
        self._put("show_framerate", value=bool(value))

    def show_physics(self, value=True):
        self._put("show_physics", value=bool(value))

    def show_debug_properties(self, value=True):
        self._put("show_debug", value=bool(value))

    def show_debug(self, value=True):
        self.show_debug_properties(value)

    def set_viewport(self, viewport_shade="WIREFRAME", clip_end=1000):
        self._put("viewport", "shade", value=str(viewport_shade).upper())
        self._put("viewport", "clip_end", value=_float(clip_end))

    def set_auto_start(self, auto_start=True):
        self._put("auto_start", value=bool(auto_start))

    def fullscreen(self, fullscreen=True, desktop=True):
        self._put("fullscreen", value=bool(fullscreen))

    def set_debug(self, debug=True):
        self._put("debug", value=bool(debug))

    def set_stereo(self, mode="ANAGLYPH", eye_separation=0.1, stereo="STEREO"):
        """NONE, STEREO (with `mode`: ANAGLYPH, SIDEBYSIDE, ...) or DOME: `morsec render` draws SIDEBYSIDE;
        a run names the modes it cannot show (morsec.kits.display)."""
        stereo = str(stereo).upper()
        self._put("stereo", value=str(mode).upper() if stereo == "STEREO" else stereo)
        if eye_separation != 0.1:
            self._session.morse_only(None, "set_stereo", {"eye_separation": eye_separation},
                                     "(eye_separation=) has no effect: MuJoCo's eyes are 6.8 cm apart")

    # ---- physics and time

    def set_gravity(self, gravity=9.81):
        self._put("gravity", value=_float(gravity))

    def set_time_strategy(self, strategy):
        """TimeStrategies.BestEffort (follow the wall clock) or TimeStrategies.FixedSimulationStep."""
        self._put("time", "strategy", value=_STRATEGIES.get(strategy, strategy))

    def set_time_scale(self, slowdown_by=None, accelerate_by=None):
        """Simulated seconds per wall-clock second: accelerate_by=k or slowdown_by=k (exactly one)."""
        if (slowdown_by is None) == (accelerate_by is None):
            raise self._session.error("set_time_scale(): give exactly one of slowdown_by= or accelerate_by=")
        value = _float(accelerate_by if accelerate_by is not None else slowdown_by)
        if not isinstance(value, float) or value <= 0:
            raise self._session.error(f"set_time_scale(): the factor must be a positive number, got {value!r}")
        self._put("time", "scale", value=value if accelerate_by is not None else 1.0 / value)

    def simulator_frequency(self, base_frequency=60, logic_step_max=20, physics_step_max=20):
        """Main loop rate, Hz; as in MORSE, this turns off the automatic tuning of the rate."""
        self._put("time", "frequency", value=_float(base_frequency))
        self._put("time", "auto_tune", value=False)
        if logic_step_max != 20 or physics_step_max != 20:
            self._session.morse_only(None, "simulator_frequency", {"logic_step_max": logic_step_max,
                                                                   "physics_step_max": physics_step_max},
                                     "(logic_step_max=, physics_step_max=) bound Blender's frame catch-up")

    def use_relative_time(self, relative_time=True):
        self._put("time", "relative", value=bool(relative_time))

    def set_physics_step_sub(self, step_sub):
        self._put("time", "physics_substeps", value=_plain(step_sub))

    def use_vsync(self, vsync):
        self._session.morse_only(None, "use_vsync", {"vsync": vsync}, "is a Blender display setting")

    def use_internal_syncer(self):
        self._session.morse_only(None, "use_internal_syncer", {},
                                 "starts MORSE's morse_sync; use configure_stream_manager('socket', time_sync=True)")

    def set_random_seed(self, seed):
        """Seed of the noise modifiers (a morsec extension)."""
        self._put("seed", value=_plain(seed))

    def record(self, file, services=False):
        """Record every run's streams (and, with services=True, the service requests and answers) in this MCAP
        file, relative to the run's output folder (a morsec extension; `morsec run --record` overrides it)."""
        self._put("record", value={"file": str(file), "services": bool(services)})

    # ---- middleware, services, multinode

    def configure_multinode(self, protocol="socket", server_address="localhost", server_port="65000",
                            distribution=None):
        port = _plain(server_port)  # MORSE's default is the string '65000'
        entry: dict[str, Any] = {"protocol": protocol, "server_address": server_address,
                                 "server_port": int(port) if isinstance(port, str) and port.isdigit() else port}
        if distribution is not None:
            entry["distribution"] = {str(node): [r.name if isinstance(r, AbstractComponent) else r for r in robots]
                                     for node, robots in dict(distribution).items()}
        self._put("multinode", value=entry)

    def configure_stream_manager(self, stream_manager, **kwargs):
        """e.g. ('socket', time_sync=True, sync_port=12000)."""
        managers = self._raw.setdefault("stream_managers", {})
        managers.setdefault(stream_manager, {}).update({k: _plain(v) for k, v in kwargs.items()})
        self._mark("stream_managers", stream_manager)

    def add_service(self, datastream):
        """Expose the simulation supervision services on a middleware (socket is always on)."""
        middleware, _ = self._middleware_of(datastream, "add_service")
        self._append_to("services", middleware, unique=True)

    def configure_service(self, datastream):
        """Deprecated MORSE name of add_service."""
        self.add_service(datastream)

    def add_interface(self, datastream, **kwargs):
        """MORSE's AbstractComponent.add_interface on the environment: add_service (the supervision
        services on that middleware) + add_stream, which MORSE refused for an environment (it has no data
        to stream). So: `services`; stream options are accepted, recorded and warned about."""
        self.add_service(datastream)
        if kwargs:
            self._session.morse_only(None, "add_interface", {"datastream": datastream, **kwargs},
                                     "(stream options) has no effect: the environment streams no data")

    def properties(self, **kwargs):
        """Global properties: longitude, latitude, altitude, angle_against_north, UTMXOffset, ..."""
        for key, value in kwargs.items():
            self._put("properties", key, value=_plain(value))

    # ---- Blender-only settings: accepted, recorded

    def set_material_mode(self, material_mode="GLSL"):
        self._session.morse_only(None, "set_material_mode", {"material_mode": material_mode},
                                 "is a Blender material setting")

    def set_animation_record(self, record=True):
        self._session.morse_only(None, "set_animation_record", {"record": record}, "records a Blender animation")

    def set_horizon_color(self, color=(0.05, 0.22, 0.4)):
        self._session.morse_only(None, "set_horizon_color", {"color": color}, "is a Blender world setting")

    def set_ambient_color(self, color=(0.0, 0.0, 0.0)):
        self._session.morse_only(None, "set_ambient_color", {"color": color}, "is a Blender world setting")

    def enable_mist(self, enable=True):
        self._session.morse_only(None, "enable_mist", {"enable": enable}, "is a Blender world setting")

    def set_mist_settings(self, **kwargs):
        self._session.morse_only(None, "set_mist_settings", kwargs, "is a Blender world setting")

    def set_background_scene(self, scene):
        self._session.morse_only(None, "set_background_scene", {"scene": scene}, "is a Blender scene setting")

    def set_log_level(self, component, level):
        self._session.morse_only(None, "set_log_level", {"component": component, "level": level},
                                 "sets MORSE's Python loggers")

    def save(self, filepath=None, check_existing=False, compress=True):
        self._session.morse_only(None, "save", {"filepath": filepath}, "saves a .blend file; `morsec build` "
                                 "writes the build folder")

    # ---- the end

    def create(self, name=None):
        """End of the script: names are final. Run by `python script.py`, builds (or runs) the scene."""
        if name is not None:
            self._session.morse_only(None, "create", {"name": name},
                                     "(name=) names the multinode node: use `morsec run --node NAME` (or $MORSE_NODE)")
        frame = self._session.caller_frame()
        if frame is not None:
            self._session.scan(frame)
        self._session.assign_names()
        if self._created:
            return
        self._created = True
        if self._session.standalone:
            _session.finish_standalone(self._session)


def _create_at_exit(env: Environment) -> None:
    """MORSE calls create() when the Environment is deleted; a plain-Python script without create() builds."""
    if env._created or getattr(sys, "last_value", None) is not None:
        return
    try:
        env.create()
    except SystemExit as stop:
        code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
