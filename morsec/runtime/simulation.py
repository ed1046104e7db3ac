"""The simulation: one MjModel/MjData, the components of a build folder, their middlewares, the loop.

Per frame: socket I/O (non-blocking, polled on this thread) -> actuators due -> physics sub-steps (between
which, while a client converses, `anytime` requests are answered: `_physics`) -> sensors
due (compute, modify, publish: sent) -> sleeps that ended (answers sent) -> the wall-clock wait, if any. A node
of a multinode world exchanges with its server first (runtime.multinode, the one hook at `frame`'s start)."""

from __future__ import annotations

import copy
import logging
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import mujoco
import numpy as np

from morsec.component.catalogue import load_class
from morsec.component.contract import SampledSensor
from morsec.constants import MAX_SPEED, PSEUDO_COMPONENTS, SLEEP_HOLD_GRACE, SLEEP_HOLD_WAIT
from morsec.errors import MorsecError, RuntimeFailure, Unsupported
from morsec.middleware.base import Middleware, RunContext
from morsec.middleware.poller import Poller
from morsec.middleware.registry import middleware
from morsec.runtime.clock import Clock, Periodic, SleepHold
from morsec.runtime.keys import KeyState
from morsec.runtime.requests import RequestManager, services_of
from morsec.runtime.robot import RobotHandle, free_joint, place
from morsec.runtime.supervision import Communication, Supervision, TimeServices
from morsec.scene.manifest import ComponentEntry, Manifest, RobotEntry, load_manifest

if TYPE_CHECKING:
    from morsec.middleware.record.recorder import Recorder
    from morsec.runtime.foxglove.server import FoxgloveServer  # imported only when a run asks for it
    from morsec.runtime.multinode import MultinodeLink
    from morsec.runtime.view import Status, View

log = logging.getLogger("morsec.runtime")

POLL_PERIOD = 0.0005  # s of wall time between socket polls when frames run faster than that
CONVERSATION = 0.01  # s of wall time after a request during which the sockets are polled every frame
# s of wall time after a request during which a loop waiting for the next frame polls without sleeping: a client
# that converses sends its next request within microseconds of reading an answer, and a process woken from
# sleep on an idle core is slower to answer it than the whole round trip (docs/running.md#performance)
SPIN_AFTER_REQUEST = 0.0005
# wall-clock s between a frame's sensor messages and the answers to the sleeps that ended at it, so that a client
# reading its sockets in any order (pymorse's polling thread) has the messages when it gets the answer
ANSWER_GAP = 0.002
# pymorse's polling thread waits on its sockets 10 ms at a time, and a socket it opens meanwhile joins at its next
# wait: the answers to sleeps leave at least READER_POLL (wall clock) after a client connected to a sensor stream,
# so that it has read the messages the stream sent it before (the frame its sleep ended at)
READER_POLL = 0.015
# while the loop has time to spare before its next frame, a frame's sensor messages leave MESSAGE_GAP apart (wall
# clock), within MESSAGE_SHARE of that time, the rest together: a client's polling thread (pymorse's) reads each
# before the next comes, so that `b.get(); a.last()` finds a's message of the frame when b's wakes get() (a sent
# first). Sent together, pymorse reads them in the order it opened their streams, and b's may wake get() first.
MESSAGE_GAP = 0.002
MESSAGE_SHARE = 0.5
MAX_POLL_WAIT = 1.0  # s: a long wait between frames is cut into polls no longer than this
PAUSED_POLL = 0.02  # s of wall time between two looks at a paused viewer (requests are served meanwhile)
DEBUG_FIELDS = 6  # a component's data fields listed by show_debug, at most


@dataclass
class RunOptions:
    strategy: str | None = None  # None: the scene's
    time_scale: float | None = None
    bind: str = "127.0.0.1"
    service_port: int | None = None
    port_base: int | None = None
    seed: int | None = None
    output_dir: Path = field(default_factory=Path.cwd)  # where text streams write
    view: str | None = None  # "web" | "native": watch the simulation
    view_port: int = 8080
    wait_for_client: bool = False  # no frame before a client's first request or stream connection (sweeps)
    foxglove: int | None = None  # serve the simulation on Foxglove's WebSocket protocol on this port (0: the OS's)
    record: Path | None = None  # an MCAP file recording every stream (morsec.middleware.record)
    record_services: bool = False  # ... and the service requests and answers
    node: str | None = None  # multinode: this node's name (None: $MORSE_NODE, else the host name)


@dataclass
class ComponentContext:
    sim: Simulation
    fqn: str
    body_id: int
    robot: RobotHandle
    properties: Any
    level: str | None
    frequency: float
    configuration: dict


@dataclass
class ComponentRuntime:
    fqn: str
    parent: str
    robot: str
    kind: str
    instance: Any
    schedule: Periodic
    defaults: list = field(default_factory=list)  # (name, default) of the data fields, for actuator input
    streams: list = field(default_factory=list)  # (middleware, direction), as `simulation details` reports them
    services: list = field(default_factory=list)  # the middlewares its services are exposed on
    in_streams: list = field(default_factory=list)
    out_streams: list = field(default_factory=list)
    echoes: list = field(default_factory=list)  # streams shown the commands its in_streams bring (--foxglove)
    modifiers: list = field(default_factory=list)
    recording: Any = None  # an actuator's tap in the recording, if one is made: the commands it takes
    # a SampledSensor's local_data dict itself: its timestamp written there computes nothing (local_data would)
    stamp: dict | None = None
    send_rank: tuple[int, int] = (1, 0)  # a sensor's: when its message leaves in a frame (set_send_ranks)
    active: bool = True
    stopped: bool = False
    errors: set = field(default_factory=set)

    def fail_once(self, err: Exception) -> None:
        key = f"{type(err).__name__}: {err}"
        if key not in self.errors:
            self.errors.add(key)
            log.error("%s: %s", self.fqn, key)


@dataclass
class RobotInfo:
    name: str
    type: str
    handle: RobotHandle


@dataclass
class SceneObject:
    """A robot or a passive object, with the property bag sensors read (Label, Object, Fire, tags ...)."""

    name: str
    body_id: int
    kind: str  # "robot" | "object"
    properties: dict

    def has(self, tag: str) -> bool:
        return bool(self.properties.get(tag)) or self.properties.get("Type") == tag


@dataclass
class Zone:
    name: str
    type: str
    center: np.ndarray
    half: np.ndarray
    properties: dict

    def contains(self, point) -> bool:
        return bool(np.all(np.abs(np.asarray(point) - self.center) <= self.half))


class Simulation:
    def __init__(self, build_dir: Path, options: RunOptions | None = None):
        self.options = options or RunOptions()
        build_dir = Path(build_dir)
        manifest = load_manifest(build_dir)
        self.multinode: MultinodeLink | None = None  # one node of several (runtime.multinode), when the scene says
        multinode = manifest.scene["environment"].get("multinode")
        if multinode is not None:  # this node runs its own robots' components only
            from morsec.runtime.multinode import NodePlan
            node_plan = NodePlan.of(multinode, self.options.node)
            manifest = node_plan.local(manifest)
        elif self.options.node:
            raise MorsecError(f"--node {self.options.node}: the scene is not split over nodes "
                              "(no environment.multinode, MORSE's configure_multinode)")
        try:
            self.model = mujoco.MjModel.from_xml_path(str(build_dir / "scene.xml"))
        except (OSError, ValueError) as err:
            raise RuntimeFailure(f"{build_dir}: not a usable build folder: {err}") from None
        self.data = mujoco.MjData(self.model)
        self.manifest = manifest
        self.streams_of: dict[str, list] = {}  # component -> its stream entries, in the manifest's order
        for stream in manifest.streams:
            self.streams_of.setdefault(stream.component, []).append(stream)
        self.scene = manifest.scene
        env = self.scene["environment"]
        self.substeps = manifest.loop.physics_substeps
        try:
            self.clock = Clock(manifest.loop.frequency, self.options.strategy or env["time"]["strategy"],
                               self.options.time_scale or float(env["time"]["scale"]), bool(env["time"]["relative"]))
        except ValueError as err:  # a build folder written by hand, or by an older morsec
            raise RuntimeFailure(f"{build_dir}: {err}") from None
        # fixed_step: a client between two of its sleeps has the loop follow the wall clock (best_effort does)
        self.hold = (SleepHold(SLEEP_HOLD_WAIT, SLEEP_HOLD_GRACE)
                     if self.clock.strategy == "fixed_step" else None)
        self.last_stream_input = 0.0  # simulated s: when the last message to an actuator stream arrived
        self.last_stream_input_wall = -float("inf")  # ... and when, on the wall clock
        self.last_reader_opened = -float("inf")  # wall clock: when a client last connected to a sensor stream
        # the frame's sensor messages, (send rank, streams, message), sent at the end of the frame by rank
        self.outbox: list[tuple[tuple[int, int], list, Any]] = []
        self.seed = self.options.seed if self.options.seed is not None else env.get("seed")
        self.client_came = not self.options.wait_for_client  # a client's request or stream connection was seen
        self.service_clients: set = set()  # --wait-for-client: the service clients that made requests
        self.loop_wall_time = 0.0  # wall-clock s from the first frame to the end of `run`
        self.quitting = False
        self.dynamics = True
        self.frozen: dict[int, tuple] = {}
        self.pinned: dict[int, tuple] = {}  # bodies held where an actuator put them, for this frame's physics
        # joints held exactly where a component put them, frame after frame, until it lets them go (an
        # armature at rest: MORSE's kinematic bones): {owner: (qpos indices, dof indices, values)}
        self.joint_holds: dict[Any, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}
        self._free_joints: dict[int, tuple[int, int] | None] = {}  # body -> free_joint(body), looked up once
        self.requests = RequestManager()
        self.requests.on_leave.append(self.client_left)
        self.keys = KeyState()  # the keys held in the viewer, if one is opened (MORSE's Keyboard reads them)
        self.poller = Poller()
        mujoco.mj_forward(self.model, self.data)
        # the bodies' world positions and rotations as the sensors of a frame read them (MjData's xpos and xmat,
        # copied as bytes when the frame's first sensor is due, if a sensor reads them: SampledSensor.reads_body_poses);
        # a sensor keeps the copy of its tick as its sample, and reads its own body's pose from it only when its
        # data is read (component.body_position): one copy a frame where each sensor's tick read its own pose
        self._pose_views = (self.data.xpos.data, self.data.xmat.data)
        self.body_poses = self.copy_body_poses()
        self._copy_poses = False  # whether a sensor reads them (set once the components started)
        self._poses_read = False  # the sensors of this frame are ticking on the copy (poses_changed takes it again)

        try:
            self.robots = [self._robot(r) for r in manifest.robots]
            handles = {r.name: r.handle for r in self.robots}
            self._handles = list(handles.values())
            self._geom_robot = self._robots_of_geoms()
            self._touching: set[int] | None = None  # this frame's, once asked for (see touching)
            # MuJoCo's list of contacts, taken once: it follows the contacts of every step (their number too),
            # and asking MjData for it at every frame cost more than reading it. So does a memoryview of their geom
            # pairs while their number stays the same (the contacts fill the start of MjData's arena: a view of
            # the first n shows the first n of every step), asked for again only when it changes; compared with
            # the pairs last looked at (a contiguous copy) item by item in C, it costs half of copying the strided
            # view's bytes to compare them
            self._contacts = self.data.contact
            self._contact_view = self._contacts.geom.data
            self._contact_seen = np.zeros((0, 2), dtype=np.int32).data  # the pairs last looked at,
            self._contact_touching: set[int] = set()  # and the robots touching then
            self.components: list[ComponentRuntime] = [self._component(c, handles) for c in manifest.components]
        except Unsupported:  # its line names the component's own file and line
            self.poller.close()
            raise
        except MorsecError as err:
            self.poller.close()
            raise RuntimeFailure(f"{build_dir}: {err}") from None
        self.by_name = {c.fqn: c for c in self.components}
        # actuators act in the reverse of the scene's order, as MORSE's did (Blender ran the logic of the object
        # created last first): of two actuators driving the same thing, the one declared first has the last
        # word (MORSE's ecef, feet and geodetic tests teleport with the first of two teleports)
        self.actuators = [c for c in reversed(self.components) if c.kind == "actuator"]
        # sensors that gather others' data (tick_last: compound) tick after them in each frame
        last = lambda c: bool(getattr(c.instance, "tick_last", False))  # noqa: E731
        self.sensors = [c for c in sorted(self.components, key=lambda c: (last(c), c.fqn)) if c.kind == "sensor"]
        self.objects = self._scene_objects()
        self.zones = [Zone(z["name"], z["type"], np.array(z["translate"], float), np.array(z["size"], float) / 2,
                           dict(z["properties"])) for z in self.scene["zones"]]
        self.initial_state = (self.data.qpos.copy(), self.data.qvel.copy(), self.data.act.copy(),
                              self.model.body_pos.copy(), self.model.body_quat.copy())
        self.stability = Stability(self.model, self.data, self.initial_state[0])
        for comp in self.components:
            try:
                comp.instance.start()
            except ValueError as err:  # a component that cannot work in this scene (missing geodetic properties ...)
                self.poller.close()
                raise RuntimeFailure(f"{comp.fqn}: {err}") from None
        set_send_ranks(self.components)  # after start: the sensors' computation modes resolved
        self._copy_poses = any(getattr(c.instance, "reads_body_poses", False) for c in self.sensors)

        self.time_services = TimeServices(self)
        self.requests.on_request.append(self.time_services.arrived)
        self.requests.frames = lambda: self.clock.frames
        self.requests.on_complete.append(self.async_answered)
        if self.hold is not None:  # fixed_step: commands start real-time phases, numbered requests
            self.requests.on_request.append(self.request_arrived)
        if self.options.wait_for_client:
            self.requests.on_request.append(self._client_request)
        for name, obj in (("simulation", Supervision(self)), ("time", self.time_services),
                          ("communication", Communication(self))):
            self.requests.expose(name, obj, services_of(obj))
        self.middlewares: dict[str, Middleware] = {}
        self._flushes: list[Callable[[], None]] = []  # the middlewares' flushes (Middleware.flushes), once open
        self._open_middlewares(manifest)
        self.foxglove: FoxgloveServer | None = None
        if self.options.foxglove is not None:
            try:
                self._open_foxglove(manifest, build_dir.name)
            except BaseException:
                self.close()
                raise
        self.recorder: Recorder | None = None
        record = self.options.record
        record_services = self.options.record_services
        if record is None and env.get("record"):  # the scene's env.record: in the run's output folder
            record = Path(self.options.output_dir) / env["record"]["file"]
            record_services = record_services or bool(env["record"]["services"])
        if record is not None:
            self._open_recording(manifest, Path(record), record_services)
        self.view: View | None = None
        if multinode is not None:
            from morsec.runtime.multinode import MultinodeLink
            try:
                self.multinode = MultinodeLink(self, node_plan)
            except BaseException:
                self.close()
                raise
        self._show(env)

    def _show(self, env: dict) -> None:
        """The environment's display settings (morsec.kits.display): set_debug's log level, the one warning
        naming those this run cannot show, and the viewer, if one was asked for."""
        from morsec.kits import display
        if env.get("debug"):
            logging.getLogger("morsec").setLevel(logging.DEBUG)
        shown_by = self.options.view or display.HEADLESS
        if (line := display.warning(env, shown_by)) is not None:
            logging.getLogger("morsec.display").warning(line)
        log.debug("%d robots, %d components, %g Hz, %s", len(self.robots), len(self.components),
                  self.clock.frequency, self.clock.strategy)
        if self.options.view:
            from morsec.runtime.view import open_view
            try:
                self.view = open_view(self.options.view, self.model, self.data, self.options.bind,
                                      self.options.view_port, env, self.keys, self.display_status)
            except BaseException:
                self.close()
                raise

    def display_status(self, debug: bool) -> Status:
        """What a viewer's overlays show: the time, the frames, and with `debug` (show_debug) each robot's
        pose and each component's data, as MORSE listed the game properties marked for debugging."""
        from morsec.runtime import view
        rows: list[tuple[str, str]] = []
        if debug:
            for robot in self.robots:
                pos, rot = robot.handle.pose()
                yaw = float(np.arctan2(rot[1, 0], rot[0, 0]))
                rows.append((robot.name, f"x {pos[0]:.2f}  y {pos[1]:.2f}  z {pos[2]:.2f}  yaw {yaw:.2f}"))
            for comp in self.components:
                shown = [f"{key} {text}" for key, value in comp.instance.local_data.items()
                         if key != "timestamp" and (text := _shown(value)) is not None]
                if shown:
                    rows.append((comp.fqn, "  ".join(shown[:DEBUG_FIELDS])))
        return view.Status(self.clock.elapsed, self.clock.frames, rows)

    # ---------------------------------------------------------------- construction
    def _robot(self, entry: RobotEntry) -> RobotInfo:
        cls = load_class(entry.component)
        handle = RobotHandle(self, entry.name, cls.Properties.model_validate(entry.properties))
        handle.friction = entry.friction
        handle.damping = float(getattr(cls, "damping", (0.0, 0.0))[0])
        return RobotInfo(entry.name, entry.builder_name, handle)

    def _component(self, entry: ComponentEntry, robots: dict[str, RobotHandle]) -> ComponentRuntime:
        cls = load_class(entry.component)
        impl = load_class(entry.component, entry.level_class)
        body = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, entry.fqn)
        if body < 0:
            raise RuntimeFailure(f"scene.xml has no body for component {entry.fqn}: rebuild the scene")
        streams = self.streams_of.get(entry.fqn, [])
        configuration = {"level": entry.level, "frequency": entry.frequency, "services": entry.services,
                         "streams": [{"middleware": s.middleware, "direction": s.direction, **s.endpoint}
                                     for s in streams],
                         "modifiers": [{"name": m.name, **m.params} for m in entry.modifiers]}
        context = ComponentContext(self, entry.fqn, body, robots[entry.robot],
                                   cls.Properties.model_validate(entry.properties), entry.level,
                                   entry.frequency, configuration)
        instance = impl(context)
        modifiers = []
        for k, spec in enumerate(entry.modifiers):
            mod_cls = load_class(spec.cls)
            modifiers.append(mod_cls(mod_cls.Params.model_validate(spec.params),
                                     self.rng_for(entry.fqn, k, spec.name), self))
        return ComponentRuntime(
            fqn=entry.fqn, parent=entry.parent, robot=entry.robot, kind=entry.kind, instance=instance,
            stamp=instance.local_dict if isinstance(instance, SampledSensor) else None,
            schedule=Periodic(entry.frequency, self.clock.dt),
            defaults=[(f.name, f.default) for f in impl.fields_at(entry.level)],
            streams=[(s.middleware, s.direction) for s in streams],
            services=list(entry.services),
            modifiers=modifiers,
        )

    def _open_middlewares(self, manifest: Manifest) -> None:
        opts = self.options
        context = RunContext(self.poller, self.requests, opts.bind, Path(opts.output_dir), opts.port_base,
                             opts.service_port, stream_opened=self.stream_opened, stream_heard=self.stream_heard,
                             stream_closed=self.stream_closed, reader_opened=self.reader_opened, now=self.clock.now,
                             frames=lambda: self.clock.frames)
        overlays = [(c.fqn, o) for c in manifest.components for o in c.overlays]
        used = sorted({s.middleware for s in manifest.streams} | {s.middleware for s in manifest.services}
                      | {o.middleware for _, o in overlays})
        try:
            for name in used:
                self.middlewares[name] = middleware(name)(context, manifest.stream_managers.get(name, {}))
            for stream in manifest.streams:
                comp = self.by_name[stream.component]
                opened = self.middlewares[stream.middleware].open_stream(comp.fqn, stream.direction, stream.endpoint)
                (comp.in_streams if stream.direction == "IN" else comp.out_streams).append(opened)
            for entry in manifest.services:
                for fqn in entry.components:
                    comp = self.by_name[fqn]
                    self.requests.expose(fqn, comp.instance, type(comp.instance).services())
                self.middlewares[entry.middleware].open_services(entry.endpoint)
            for fqn, overlay in overlays:  # the overlay calls the component's services, served or not
                comp = self.by_name[fqn]
                if fqn not in self.requests.exposed:
                    self.requests.expose(fqn, comp.instance, type(comp.instance).services())
                self.middlewares[overlay.middleware].open_overlay(fqn, comp.instance, overlay.cls, overlay.params)
        except OSError as err:
            self.close()
            raise RuntimeFailure(f"cannot open the simulation's sockets on {opts.bind}: "
                                 f"{err.strerror or err}") from None
        except MorsecError:  # a user's option that cannot work (exit 2), a damaged build (exit 1)
            self.close()
            raise
        except ValueError as err:
            self.close()
            raise RuntimeFailure(str(err)) from None
        for mw in self.middlewares.values():
            for pseudo, obj in mw.services().items():
                self.requests.expose_more(pseudo, obj, services_of(obj))
        self._flushes = [flush for mw in self.middlewares.values() for flush in mw.flushes()]
        locks = [mw.lockstep() for mw in self.middlewares.values()]
        self.sync = next((lock for lock in locks if lock is not None), None)

    def _open_foxglove(self, manifest: Manifest, name: str) -> None:
        """`--foxglove`: every sensor's messages, and the commands the actuators' streams bring, also go to
        Foxglove's channels (built only while a client subscribes), besides the world it draws."""
        try:
            from morsec.runtime.foxglove.server import FoxgloveServer
        except ImportError as err:
            if not (err.name or "").startswith("foxglove"):
                raise
            raise MorsecError("--foxglove needs the foxglove-sdk package: pip install foxglove-sdk (or "
                              "pip install 'morsec[foxglove]')") from None
        assert self.options.foxglove is not None
        self.foxglove = server = FoxgloveServer(self.model, self.options.bind, self.options.foxglove, f"morsec {name}")
        for entry in manifest.components:
            comp = self.by_name[entry.fqn]
            if comp.kind == "actuator" and not comp.in_streams:
                continue  # nothing reaches it from outside
            streams = server.streams_for(entry.fqn, type(comp.instance), entry.level, comp.instance.properties)
            (comp.out_streams if comp.kind == "sensor" else comp.echoes).extend(streams)

    def _open_recording(self, manifest: Manifest, path: Path, services: bool) -> None:
        """Every component with a stream recorded (its messages, or the commands it takes), in simulated time."""
        import json

        from morsec import __version__
        from morsec.component.catalogue import type_lineage
        from morsec.middleware.base import StreamRequest
        from morsec.middleware.record.channels import plan_stream
        from morsec.middleware.record.recorder import Recorder
        plans, taps = [], []
        for entry in manifest.components:
            streams = self.streams_of.get(entry.fqn)
            if not streams:
                continue
            cls = load_class(entry.component, entry.component.name)  # a Device: its message schema
            ref = entry.component
            schema = f"morsec/{ref.kind}/{ref.id}" + (f"/{entry.level}" if entry.level else "")
            for direction in dict.fromkeys(s.direction for s in streams):
                request = StreamRequest(entry.fqn, direction, {}, type_lineage(cls), dict(entry.properties))
                ros = [s.endpoint for s in streams if s.middleware == "ros" and s.direction == direction]
                plans.append(plan_stream(request, schema, cls.message_schema(entry.level), ros))
                taps.append((self.by_name[entry.fqn], direction))
                for note in plans[-1].notes:
                    log.warning("%s: %s", entry.fqn, note)
        details = self.requests.exposed["simulation"].obj.details()
        metadata = {"morsec": {
            "version": __version__, "frequency": repr(manifest.loop.frequency),
            "time": "simulated",  # log times: the simulated time of each message, in ns
            "time_origin": "start" if self.clock.origin == 0.0 else "unix_epoch",  # environment.time.relative
            "details": json.dumps(details),
            "streams": json.dumps([s.model_dump(mode="json") for s in manifest.streams])}}
        try:
            recorder = self.recorder = Recorder(path, self.clock.now, plans, metadata, services=services)
        except MorsecError:
            self.close()
            raise
        for index, (comp, direction) in enumerate(taps):
            tap = recorder.stream(index)
            if direction == "OUT":
                comp.out_streams.append(tap)
            else:
                comp.recording = tap
        if services:
            recorder.watch(self.requests.on_request)
            self.requests.on_leave.append(recorder.forget)

    def _scene_objects(self) -> list[SceneObject]:
        out = []
        for r in self.scene["robots"]:
            body = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, r["name"])
            out.append(SceneObject(r["name"], body, "robot",
                                   {"Robot_Tag": True, **r["properties"], **r.get("tags", {})}))
        for o in self.scene["objects"]:
            body = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, o["name"])
            out.append(SceneObject(o["name"], body, "object", dict(o["properties"])))
        # a component with tags (game properties its type does not declare) is something sensors look for too
        for entry in self.manifest.components:
            if entry.tags:
                body = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, entry.fqn)
                out.append(SceneObject(entry.fqn, body, "component", dict(entry.tags)))
        return out

    def _robots_of_geoms(self) -> list[int]:
        """The index in self.robots of the robot each geom is part of (-1: none). Robots are children of the
        world body, never of one another: a geom is part of one robot at most."""
        owner = np.full(self.model.ngeom, -1, dtype=int)
        for index, robot in enumerate(self.robots):
            owner[np.isin(self.model.geom_bodyid, robot.handle.bodies)] = index
            robot.handle.index = index
        return owner.tolist()

    # ---------------------------------------------------------------- queries used by components
    def touching(self) -> set[int]:
        """The robots (their index in self.robots) that touch something not part of them in the contacts
        MuJoCo found last: found once for all robots until the contacts change (the same geom pairs as the
        last time they were looked at: the same robots, found again only when they differ)."""
        if self._touching is None:
            view = self._contact_view
            if len(view) != self.data.ncon:
                view = self._contact_view = self._contacts.geom.data
            if view != self._contact_seen:
                seen = np.array(view)
                self._contact_seen = seen.data
                touching = set()
                owner = self._geom_robot
                for first, second in seen.tolist():  # ncon of them, a few a robot: no numpy
                    if owner[first] != owner[second]:
                        touching.add(owner[first])
                        touching.add(owner[second])
                touching.discard(-1)  # a geom of no robot
                self._contact_touching = touching
            self._touching = self._contact_touching
        return self._touching

    def objects_with(self, tag: str) -> list[SceneObject]:
        """Robots and objects whose property `tag` is truthy (or whose Type is `tag`)."""
        return [o for o in self.objects if o.has(tag)]

    def zones_at(self, point, zone_type: str | None = None) -> list[Zone]:
        return [z for z in self.zones if (zone_type is None or z.type == zone_type) and z.contains(point)]

    @property
    def geo(self):
        """The scene's geodetic frame (environment longitude/latitude/altitude); ValueError if not set."""
        if getattr(self, "_geo", None) is None:
            from morsec.kits.geodesy import GeoFrame
            self._geo = GeoFrame.from_properties(self.scene["environment"]["properties"])
        return self._geo

    def rng_for(self, *key: str | int) -> np.random.Generator:
        """An independent random stream per (component, modifier): same seed, same numbers, whatever else
        the scene holds. Without a seed, fresh entropy."""
        import zlib
        if self.seed is None:
            return np.random.default_rng()
        return np.random.default_rng([self.seed] + [zlib.crc32(str(k).encode()) for k in key])

    # ---------------------------------------------------------------- queries used by services
    def components_of(self, robot: str) -> list[ComponentRuntime]:
        return [c for c in self.components if c.robot == robot]

    def component(self, name: str) -> ComponentRuntime:
        if name not in self.by_name:
            raise ValueError(f"unknown component {name!r}")
        return self.by_name[name]

    def copy_body_poses(self) -> tuple[bytes, bytes]:
        """The bodies' world positions and rotations now: MjData's xpos and xmat, as bytes (morsec.component's
        body_position and body_rotation read one body's)."""
        xpos, xmat = self._pose_views
        return bytes(xpos), bytes(xmat)

    def scene_bodies(self) -> dict[str, int]:
        names = [r["name"] for r in self.scene["robots"]] + [o["name"] for o in self.scene["objects"]]
        return {n: mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, n) for n in names}

    # ---------------------------------------------------------------- state changes from services
    def sleep_ended(self, request) -> None:
        """A client's last running `time sleep` ended: in fixed_step, until its next sleep starts, the loop
        follows the wall clock (SleepHold); not while a lockstep client paces the loop."""
        if self.hold is not None and not (self.sync is not None and self.sync.engaged):
            self.hold.arm(request.client)

    def async_answered(self, request) -> None:
        """An asynchronous request was answered (a waypoint reached ...): in fixed_step, a client with nothing
        else running has the wall clock until its next sleep, as after a sleep (`goto(...).result(); goto(...);
        sleep(1)`: the robot does not coast on for hundreds of frames in between)."""
        if (request.component not in PSEUDO_COMPONENTS and not self.requests.by_client.get(request.client)
                and not self.time_services.sleeping.get(request.client)):
            self.sleep_ended(request)

    def sleep_started(self, request) -> None:
        if self.hold is not None:
            self.hold.release(request.client)

    def request_arrived(self, request) -> None:
        """fixed_step: a service request arrived, before it is handled."""
        self.time_services.heard(request)
        if self.hold is not None:
            self.hold.greet(request.client)
            if request.component not in PSEUDO_COMPONENTS and not self.time_services.sleeping.get(request.client):
                self.hold.wake(request.client, SLEEP_HOLD_WAIT)  # a command: its sleep may follow

    def stream_heard(self, connection) -> None:
        """A message arrived on an actuator stream connection (whose client's it is cannot be told)."""
        self.last_stream_input = self.clock.elapsed  # a sleep is never counted from before it
        self.last_stream_input_wall = time.perf_counter()
        if self.hold is not None:
            self.hold.stream_heard(connection)

    def _client_request(self, request) -> None:
        """--wait-for-client: time starts with the first request, and the simulation ends when the last service
        client that made requests has gone (the run's client ended)."""
        self.client_came = True
        self.service_clients.add(request.client)

    def stream_opened(self, connection) -> None:
        self.client_came = True
        if self.hold is not None and not (self.sync is not None and self.sync.engaged):
            self.hold.stream_opened(connection)

    def reader_opened(self) -> None:
        self.client_came = True
        self.last_reader_opened = time.perf_counter()

    def stream_closed(self, connection) -> None:
        if self.hold is not None:
            self.hold.stream_closed(connection)

    def client_left(self, client) -> None:
        if self.hold is not None:
            self.hold.forget(client)
        self.time_services.left(client)
        if client in self.service_clients:
            self.service_clients.discard(client)
            if not self.service_clients:
                self.request_quit()

    def request_quit(self, immediate: bool = False) -> None:
        self.quitting = True
        self.immediate = immediate

    def reset(self) -> None:
        qpos, qvel, act, body_pos, body_quat = self.initial_state
        self.data.qpos[:] = qpos
        self.data.qvel[:] = qvel
        self.data.act[:] = act
        self.model.body_pos[:] = body_pos
        self.model.body_quat[:] = body_quat
        mujoco.mj_forward(self.model, self.data)
        self._touching = None
        for comp in self.components:
            try:
                comp.instance.reset()
            except Exception as err:
                comp.fail_once(err)

    def place_body(self, body: int, pos, rot) -> None:
        place(self.model, self.data, body, pos, rot)
        if body in self.frozen:
            self.set_frozen(body, True)  # frozen where it was put
        self.poses_changed()

    def poses_changed(self) -> None:
        """Bodies were moved outside the physics, their kinematics computed (a teleport, a service, a component's
        tick): while the frame's sensors tick, the copy of the bodies' poses is taken again for those that tick
        after; at any other time nothing (the next frame's sensors take their own copy: a fleet's teleports
        copy nothing)."""
        if self._poses_read:
            self.body_poses = self.copy_body_poses()

    def pin(self, body: int) -> None:
        """Hold a body where it is through this frame's physics (a teleport: MORSE's sensors read the pose
        the teleport set, before physics moved it)."""
        if body not in self._free_joints:
            self._free_joints[body] = free_joint(self.model, body)
        joint = self._free_joints[body]
        if joint is not None:
            adr, dof = joint
            self.pinned[body] = (adr, dof, self.data.qpos[adr:adr + 7].copy())

    def set_frozen(self, body: int, frozen: bool) -> None:
        joint = free_joint(self.model, body)
        if joint is None:
            return  # static bodies are frozen already
        if frozen:
            adr, dof = joint
            self.frozen[body] = (adr, dof, self.data.qpos[adr:adr + 7].copy())
        else:
            self.frozen.pop(body, None)

    # ---------------------------------------------------------------- the loop
    def announce(self, out=sys.stdout) -> None:
        """SCENE INITIALIZED, then the servers (services, lockstep) and every stream's endpoint."""
        lines = ["SCENE INITIALIZED"]
        streams = []
        pseudo = f"simulation, time, communication{', components' if len(self.requests.exposed) > 3 else ''}"
        for name, mw in sorted(self.middlewares.items()):
            for what, direction, where in mw.describe():
                if direction:
                    streams.append((what, direction, name, where))
                else:
                    lines.append(f"  {what:<14} {where}" + (f"  ({pseudo})" if what == "services" else ""))
        if self.foxglove is not None:
            lines.append(f"  {'foxglove':<14} {self.foxglove.url}  (open in Foxglove: {self.foxglove.app_url})")
        if self.recorder is not None:
            lines.append(f"  {'recording':<14} {self.recorder.path}")
        width = max([len(c.fqn) for c in self.components] + [10])
        for fqn, direction, name, where in sorted(streams, key=lambda row: row[0]):
            lines.append(f"  {fqn:<{width}}  {direction:<3}  {name:<6}  {where}")
        if self.multinode is not None:
            lines.append(self.multinode.describe())
        if self.view is not None and self.view.paused:
            lines.append(f"PAUSED (auto_start is false): in the viewer, {self.view.resume_hint}")
        out.write("\n".join(lines) + "\n")
        out.flush()

    def run(self, duration: float | None = None) -> None:
        next_poll = 0.0
        started = None
        end = float("inf") if duration is None else duration - 1e-9
        # the loop stood still (a viewer's pause, a client awaited, a new actuator stream's first message
        # awaited): that wall-clock time is not owed, the frame after the next one comes a frame's time later
        # (a burst of two frames would run one between a stream's message and the client's reply to it)
        stood_still = False
        # read at every frame, and none of them replaced while the simulation runs
        clock, requests, poller, time_services = self.clock, self.requests, self.poller, self.time_services
        sync, hold, view = self.sync, self.hold, self.view
        try:
            while not self.quitting:
                if clock.elapsed >= end:
                    break
                # sockets are polled every frame, but at most every POLL_PERIOD of wall time: a fixed_step
                # loop runs frames far faster than any client can tell apart (lockstep polls every frame, and
                # so does a loop that answered a request within CONVERSATION: the client waits on its answers)
                now = time.perf_counter()
                if (now >= next_poll or now - requests.last_request < CONVERSATION
                        or (sync is not None and sync.engaged)):
                    poller.poll(0.0)
                    next_poll = now + POLL_PERIOD
                if self.quitting:
                    break
                if not self.client_came:  # --wait-for-client: time starts with the client
                    if sync is not None and sync.engaged:
                        self.client_came = True
                    else:
                        poller.poll(MAX_POLL_WAIT / 20)
                        self._flush()
                        stood_still = True
                        continue
                if view is not None and view.paused:  # the viewer's pause (space): no frame runs
                    view.sync()
                    self._pause(PAUSED_POLL)
                    stood_still = True
                    continue
                if stood_still:  # the wall clock's pace from now
                    clock.restart()
                    stood_still = False
                if sync is not None and sync.engaged:
                    if not sync.take():
                        poller.poll(0.01)
                        self._flush()
                        continue
                elif hold is not None and hold.opened:
                    held = hold.holding()  # a new actuator stream: its first message applies at this frame
                    if held > 0:
                        poller.poll(min(held, MAX_POLL_WAIT))
                        self._flush()
                        stood_still = True
                        continue
                if started is None:
                    started = time.perf_counter()
                self.frame(spread=True)  # ends with a flush
                if view is not None:
                    view.sync()
                # a sleep ends at this frame: its answer leaves ANSWER_GAP after the frame's messages
                if time_services.sleepers and time_services.ending():
                    gap = max(ANSWER_GAP, self.last_reader_opened + READER_POLL - time.perf_counter())
                    self._pause(gap)
                    if gap > ANSWER_GAP:  # the next frame a frame's time after the answers, as usual: a client
                        clock.restart_a_frame_later()  # calling get() after its answer gets its message
                if time_services.sleepers or time_services.deferred or requests.waiting:  # else nothing to answer
                    self.answer()
                    self._flush()  # the answers (what the frame queued left with its own flush)
                # fixed_step with no client between two sleeps, and not paced since: no wait (usually, at every
                # frame: _delay would say 0 through two calls)
                if hold is None or hold.awake or clock.paced:
                    delay = self._delay()
                    if delay > 0:
                        self._wait(delay)
        finally:
            if started is not None:
                self.loop_wall_time = time.perf_counter() - started
            self.close()

    def _delay(self) -> float:
        """Wall-clock seconds before the next frame: best_effort's, or fixed_step's (none, or the wall
        clock's pace while a client is between two sleeps; a lockstep client paces the loop itself)."""
        return self.clock.delay(self._paced())

    def _paced(self) -> bool:
        """Whether fixed_step follows the wall clock now: a client is between two sleeps (SleepHold), and no
        lockstep client paces the loop."""
        hold = self.hold
        return (hold is not None and bool(hold.awake) and not (self.sync is not None and self.sync.engaged)
                and hold.pacing())

    def _wait(self, delay: float) -> None:
        while delay > 0 and not self.quitting:
            self._poll(min(delay, MAX_POLL_WAIT))
            self._flush()
            delay = self._delay()  # asked again: a request may have changed the time scale, a client slept

    def _pause(self, seconds: float) -> None:
        """Poll the sockets for `seconds` of wall time (requests are handled; no frame runs)."""
        until = time.perf_counter() + seconds
        while (left := until - time.perf_counter()) > 0 and not self.quitting:
            self._poll(left)
            self._flush()

    def _poll(self, timeout: float) -> None:
        """Wait up to `timeout` for the sockets, and serve them; without sleeping while a client converses
        (SPIN_AFTER_REQUEST): its next request is a few microseconds away."""
        if time.perf_counter() - self.requests.last_request < SPIN_AFTER_REQUEST:
            timeout = 0.0
        self.poller.poll(timeout)

    def frame(self, spread: bool = False) -> None:
        """One frame: the physics and the components (step), then the sensors' messages sent (with `spread`,
        MESSAGE_GAP apart while the loop has time to spare). The answers to the sleeps that ended at this frame
        leave ANSWER_GAP later (`time_services.wake` in `run`): a client holding such an answer has had this
        frame's messages for a while, whatever order its polling thread reads its sockets in."""
        if self.multinode is not None:  # the other nodes' robots placed; held here while this node runs ahead
            self.multinode.exchange()
        self.step()
        if self.outbox:  # else no stream has a reader
            self._send_sensor_messages(self._spare() * MESSAGE_SHARE if spread else 0.0)
        self._flush()

    def answer(self) -> None:
        """The end of a frame, after its messages: the sleeps that ended at it answered, the components'
        asynchronous services that arrived before it started (MORSE's frame order, docs/running.md#time)."""
        time_services, requests = self.time_services, self.requests
        if time_services.sleepers or time_services.deferred:  # else nothing to wake (usually, at every frame)
            time_services.wake()
        if requests.waiting:
            requests.start_waiting(self.clock.frames)

    def step(self) -> None:
        m, d = self.model, self.data
        t = self.clock.elapsed
        handles = self._handles
        for handle in handles:
            if handle.sampled is not None:
                handle.resume_held()
        self.stability.remember()
        self._touching = None  # contacts may have changed since the last frame (a service's reset, recover)
        self._tick_actuators(t)
        if self.dynamics:
            self._physics(m, d)
            self.stability.check(m, d)
        else:
            d.qvel[:] = 0.0
            mujoco.mj_forward(m, d)
        self._touching = None
        if self.frozen or self.pinned:
            for adr, dof, qpos in (*self.frozen.values(), *self.pinned.values()):
                d.qpos[adr:adr + 7] = qpos
                d.qvel[dof:dof + 6] = 0.0
            self.pinned.clear()
        for qpos_index, dof_index, values in self.joint_holds.values():
            d.qpos[qpos_index] = values
            d.qvel[dof_index] = 0.0
        sampled = False
        for handle in handles:
            if handle.ticks and handle.sample_tick_end():
                sampled = True
        self.clock.tick()
        self._tick_sensors(sampled)

    def _physics(self, m, d) -> None:
        """The frame's physics sub-steps, in one call; while a client converses (a request within CONVERSATION),
        one at a time, the service connections read after each and the requests of `anytime` services
        (`time now`: they read and change nothing a frame changes, ServiceInfo.anytime) answered there: a frame
        run back to back with the next (fixed_step) no longer holds such an answer until its end. The others
        wait for the frame's end, as always. The same steps in the same order: the same physics, bit for bit
        (mj_step's nstep repeats mj_step). Not in the first frame: its start is time 0 with relative time,
        which MORSE's answer cannot carry (a falsy result is left out: pymorse's `sim.time()` would be None)."""
        if time.perf_counter() - self.requests.last_request >= CONVERSATION or not self.clock.frames:
            mujoco.mj_step(m, d, self.substeps)  # nstep positional: the binding parses a keyword at 1.7k instructions
            return
        middlewares = self.middlewares.values()
        for _ in range(self.substeps):
            mujoco.mj_step(m, d)
            for mw in middlewares:
                mw.answer_anytime()

    def _flush(self) -> None:
        for flush in self._flushes:
            flush()
        if self.foxglove is not None:  # also while no frame runs (a client awaited, lockstep): Foxglove still sees
            self.foxglove.frame(self.data, self.clock.now())

    def _send_sensor_messages(self, within: float = 0.0) -> None:
        """Publish the frame's sensor messages, before the answers to the sleeps that ended at this frame: a
        client whose sleep ended reads this frame's data with `last()`. They leave in the order of
        `set_send_ranks`, MESSAGE_GAP apart for `within` wall-clock seconds (requests are served meanwhile), the
        rest together."""
        outbox, self.outbox = self.outbox, []
        if len(outbox) > 1:
            outbox.sort(key=lambda item: item[0])
        until = time.perf_counter() + within
        for k, (_, streams, message) in enumerate(outbox):
            if k and time.perf_counter() + MESSAGE_GAP <= until:
                self._pause(MESSAGE_GAP)
            for stream in streams:
                stream.publish(message)

    def _spare(self) -> float:
        """Wall-clock seconds before the next frame is due: none while fixed_step runs free or a lockstep
        client paces the loop."""
        if self.sync is not None and self.sync.engaged:
            return 0.0
        return self.clock.spare(self._paced())

    # the components' ticks: one call a frame for all actuators, one for all sensors (a call per component was
    # a tenth of a fleet's Python)
    def _tick_actuators(self, t: float) -> None:
        """The actuators due at simulated time t: the last message each stream received applied, then their
        default_action."""
        frames = self.clock.frames
        for comp in self.actuators:
            if not (comp.active and (comp.schedule.every_frame or comp.schedule.due(t))):
                continue
            message = None
            for stream in comp.in_streams:
                received = stream.take(frames)
                if received is not None:
                    message = received
            if message is not None and comp.recording is not None:
                comp.recording.publish(message)
            try:
                if message is not None:
                    self.receive(comp, message)
                    for echo in comp.echoes:
                        if echo.listening:
                            echo.publish(message, self.clock.now())
                comp.instance.default_action()
            except Unsupported:  # the component needs what morsec does not do: the run stops, with its line
                raise
            except Exception as err:  # a bad command must not stop the simulation
                comp.fail_once(err)

    @staticmethod
    def receive(comp: ComponentRuntime, message: dict) -> None:
        """A client's message to an actuator: it replaces the whole data dict (unsent fields take their
        defaults), then the input modifiers run on it."""
        local = comp.instance.local_data
        local.clear()
        for name, default in comp.defaults:
            local[name] = copy.deepcopy(default)
        local.update(message)
        for modifier in comp.modifiers:
            modifier.modify(local)

    def _tick_sensors(self, sampled: bool) -> None:
        """The sensors due at this frame's end: the kinematics of the state the physics left computed once, before
        the first (`sampled`: with the velocities sample_tick_end set), then each one's tick stamped, its
        default_action, its modifiers, and its message queued when a stream has a reader."""
        clock = self.clock
        t, now = clock.elapsed, None
        for comp in self.sensors:
            if not (comp.active and (comp.schedule.every_frame or comp.schedule.due(t))):
                continue
            if now is None:  # the first sensor due
                mujoco.mj_kinematics(self.model, self.data)
                if sampled:  # the velocities the sensors read (d.cvel) follow the ones just sampled
                    mujoco.mj_comPos(self.model, self.data)
                    mujoco.mj_comVel(self.model, self.data)
                if self._copy_poses:
                    self.body_poses = self.copy_body_poses()
                    self._poses_read = True
                now = clock.now()
            inst = comp.instance
            (inst.local_data if comp.stamp is None else comp.stamp)["timestamp"] = now
            try:
                inst.default_action()
                if comp.modifiers:  # a SampledSensor's deferrable ones draw here and apply when its data is read
                    inst.apply_modifiers(comp.modifiers)
            except Unsupported:
                raise
            except Exception as err:
                comp.fail_once(err)
                continue
            listening = None  # the streams with a reader, each asked once
            for stream in comp.out_streams:
                if stream.listening:
                    if listening is None:
                        listening = [stream]
                    else:
                        listening.append(stream)
            if listening is None:
                continue  # no stream has a reader: no message built (local_data stays readable: SampledSensor)
            try:  # a SampledSensor computes here: its errors are the sensor's, as its tick's are
                message = inst.serialize()  # local_data, or the sensor's own format; None: nothing this tick
            except Unsupported:
                raise
            except Exception as err:
                comp.fail_once(err)
                continue
            if message is not None:
                self.outbox.append((comp.send_rank, listening, message))
        self._poses_read = False

    def close(self) -> None:
        view = getattr(self, "view", None)  # None: closed, or __init__ stopped before opening it
        if view is not None:
            view.close()
            self.view = None
        for comp in getattr(self, "components", []):
            if not comp.stopped:  # once: free what start took (renderers)
                comp.stopped = True
                try:
                    comp.instance.finalize()
                except Exception as err:
                    comp.fail_once(err)
            comp.in_streams, comp.out_streams, comp.echoes = [], [], []
        for mw in getattr(self, "middlewares", {}).values():
            mw.close()
        self.middlewares, self._flushes = {}, []
        foxglove = getattr(self, "foxglove", None)
        if foxglove is not None:
            foxglove.close()
            self.foxglove = None
        link = getattr(self, "multinode", None)  # None: not a node, or __init__ stopped before connecting
        if link is not None:
            link.close()
        self.poller.close()
        recorder = getattr(self, "recorder", None)
        if recorder is not None:  # last: it waits for its writer to finish the file
            self.recorder = None
            recorder.close()


def set_send_ranks(components: list[ComponentRuntime]) -> None:
    """Each sensor's `send_rank`: the order a frame's sensor messages leave in (lowest rank first), the
    order in which MORSE's messages carrying the same actuator decision left. MORSE ran each object's logic,
    the object created last first, then the physics step; morsec's sensors all read after it. So a MORSE
    sensor reading its robot's velocities (ComputationMode Velocity), run after an actuator created after it
    had set them, sent that decision in the frame it was made, and every other sensor a frame later, in the
    pose the physics made of it: those velocity sensors first, then the others, each group the sensor created
    last first. Left a little apart in this order, `b.get(); a.last()` reads one frame in both streams when a
    leaves before b, as MORSE's accelerometer test (accel_pi before accel) and attitude test (attitude before
    attitude_pos) read."""
    order = {c.fqn: index for index, c in enumerate(components)}
    last_driver: dict[str, int] = {}  # robot -> the index of its last actuator driving its velocities
    for c in components:
        if c.kind == "actuator" and getattr(c.instance, "base_servo", False):
            last_driver[c.robot] = order[c.fqn]
    for c in components:
        if c.kind == "sensor":
            ahead = getattr(c.instance, "mode", None) == "Velocity" and last_driver.get(c.robot, -1) > order[c.fqn]
            c.send_rank = (0 if ahead else 1, -order[c.fqn])


class Stability:
    """MuJoCo resets the whole world (every robot back to its start) when a value of its state is NaN, Inf
    or huge. That reset is turned off; instead, after a frame that made MuJoCo warn, only the robots and
    objects whose state went bad are put back where they were before the frame, at rest, and the others
    keep what the frame did to them. Per frame: two array copies and three counters read (well under 1 us)."""

    BAD_QPOS = int(mujoco.mjtWarning.mjWARN_BADQPOS)
    BAD_QVEL = int(mujoco.mjtWarning.mjWARN_BADQVEL)
    BAD_QACC = int(mujoco.mjtWarning.mjWARN_BADQACC)
    assert BAD_QVEL == BAD_QPOS + 1 and BAD_QACC == BAD_QPOS + 2

    def __init__(self, model, data, initial_qpos: np.ndarray):
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_AUTORESET)
        self.initial_qpos = initial_qpos
        # the state before the frame, qpos and qvel, copied through memoryviews of both sides (MjData's arrays
        # stay put): a slice assignment of memoryviews is a plain copy, cheaper than a numpy or MuJoCo call
        self.model, self.data = model, data
        self.qpos, self.qvel = np.zeros(model.nq), np.zeros(model.nv)
        self._copies = ((self.qpos.data, data.qpos.data), (self.qvel.data, data.qvel.data))  # (.data: a memoryview)
        self.remember()
        # a view of MuJoCo's three counters of bad values (they follow one another): reading it costs nothing
        self.numbers = data.warning.number[self.BAD_QPOS:self.BAD_QACC + 1]
        self.warnings = self.numbers.tolist()  # as last seen: a frame that changes them made MuJoCo warn
        self.qpos_root = np.zeros(model.nq, dtype=int)  # the root body (robot or object) of each qpos entry
        for j in range(model.njnt):
            end = model.jnt_qposadr[j + 1] if j + 1 < model.njnt else model.nq
            self.qpos_root[model.jnt_qposadr[j]:end] = model.body_rootid[model.jnt_bodyid[j]]
        self.dof_root = model.body_rootid[model.dof_bodyid].astype(int)
        self.reported: set[int] = set()

    def remember(self) -> None:
        (qpos, live_qpos), (qvel, live_qvel) = self._copies
        qpos[:] = live_qpos
        qvel[:] = live_qvel

    def check(self, model, data) -> None:
        warnings = self.numbers.tolist()
        if warnings != self.warnings:
            self.warnings = warnings
            self.recover(model, data)

    def recover(self, model, data) -> None:
        bad_roots = set(self.qpos_root[~_sane(data.qpos)].tolist())
        # after a warning, a body going faster than anything simulated goes is as bad as a NaN: left with such
        # a velocity, MuJoCo's next step may crash outright (robots piled up at one place, MuJoCo 4.0)
        wild = np.abs(data.qvel) > MAX_SPEED
        bad_roots |= set(self.dof_root[~(_sane(data.qvel) & _sane(data.qacc)) | wild].tolist())
        for root in sorted(bad_roots):
            qpos = self.qpos_root == root
            previous = self.qpos[qpos]
            data.qpos[qpos] = previous if np.all(_sane(previous)) else self.initial_qpos[qpos]
            dofs = self.dof_root == root
            data.qvel[dofs] = 0.0
            data.qacc_warmstart[dofs] = 0.0
            data.xfrc_applied[model.body_rootid == root] = 0.0
            if root not in self.reported:  # once: a command that keeps doing it would fill the log
                self.reported.add(root)
                log.warning("%s: its state became unstable (NaN, Inf or huge values): put back where it was "
                            "before the frame, at rest", mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, root))
        data.qacc_warmstart[~_sane(data.qacc_warmstart)] = 0.0
        mujoco.mj_forward(model, data)


def _sane(values: np.ndarray) -> np.ndarray:
    """Which values MuJoCo accepts in its state (finite, within mjMAXVAL)."""
    return np.abs(values) <= mujoco.mjMAXVAL


def _shown(value: Any) -> str | None:
    """A data field as show_debug lists it: numbers, flags, short text and short vectors; None for the rest
    (images, point clouds, nested records)."""
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, (int, float, np.integer, np.floating)):
        return f"{float(value):.3g}"
    if isinstance(value, str):
        return value if len(value) <= 24 else value[:21] + "..."
    if isinstance(value, (list, tuple, np.ndarray)) and 0 < len(value) <= 4 \
            and all(isinstance(v, (int, float, np.integer, np.floating)) for v in value):
        return "[" + ", ".join(f"{float(v):.3g}" for v in value) + "]"
    return None
