"""The `simulation` pseudo-component: supervision services (reference §3.3)."""

from __future__ import annotations

import heapq
import itertools
import logging
import math
import time as _time
from typing import Any

import mujoco
import numpy as np

from morsec.component.services import async_service, service
from morsec.constants import (
    MAX_POSITION,
    PSEUDO_COMPONENTS,
    ROUND_TRIPS_COUNTED,
    SLEEP_ORDER_WAIT,
    SLEEP_WITH_PREVIOUS,
)
from morsec.kits.bounds import bounded
from morsec.kits.geometry import euler_to_quat, quat_to_matrix
from morsec.runtime.clock import Numbering, request_number

log = logging.getLogger("morsec.time")


class Supervision:
    def __init__(self, sim):
        self.sim = sim

    def interrupt(self) -> None:
        pass

    @service(anytime=True)
    def list_robots(self) -> list[str]:
        return [r.name for r in self.sim.robots]

    @service(anytime=True)
    def details(self) -> dict:
        """The scene's structure, in the shape pymorse reads."""
        sim = self.sim
        robots = []
        for robot in sim.robots:
            components = {}
            for comp in sim.components_of(robot.name):
                entry: dict = {"type": type(comp.instance).__name__}
                services = sim.requests.service_names(comp.fqn)
                if services:
                    entry["services"] = services
                    entry["service_interfaces"] = [[f"morsec.middleware.{m}"] for m in comp.services]
                streams = [[f"morsec.middleware.{middleware}", direction] for middleware, direction in comp.streams]
                if streams:
                    entry["stream_interfaces"] = streams
                components[comp.fqn] = entry
            robots.append({"name": robot.name, "type": robot.type, "components": components})
        return {"robots": robots, "environment": sim.scene["environment"]["name"]}

    @service
    def quit(self) -> None:
        self.sim.request_quit()

    @service
    def terminate(self) -> None:
        self.sim.request_quit(immediate=True)

    @service
    def reset_objects(self) -> str:
        self.sim.reset()
        return "Objects restored to initial position"

    @service
    def activate(self, component_name: str) -> None:
        self.sim.component(component_name).active = True

    @service
    def deactivate(self, component_name: str) -> None:
        self.sim.component(component_name).active = False

    @service
    def suspend_dynamics(self) -> None:
        self.sim.dynamics = False

    @service
    def restore_dynamics(self) -> None:
        self.sim.dynamics = True

    @service
    def set_log_level(self, component: str, level: str) -> None:
        import logging
        logging.getLogger(f"morsec.{component}").setLevel(str(level).upper())

    @service
    def get_scene_objects(self) -> dict:
        """{name: [children, [x, y, z], [qx, qy, qz, qw]]} for robots (children: components) and objects."""
        d = self.sim.data
        out = {}
        for name, body in self.sim.scene_bodies().items():
            children = {}
            for comp in self.sim.components_of(name):
                if comp.parent == name:
                    children[comp.fqn] = _entry(d, comp.instance.body_id, {})
            out[name] = _entry(d, body, children)
        return out

    @service
    def set_object_position(self, object_name: str, position, orientation=None) -> None:
        body = self.sim.scene_bodies().get(object_name)
        if body is None:
            raise ValueError(f"unknown object {object_name!r}")
        pos = bounded(position, MAX_POSITION, "a position (m)")
        if pos.shape != (3,):
            raise ValueError("position must be [x, y, z]")
        if orientation is None:
            rot = self.sim.data.xmat[body].reshape(3, 3).copy()
        else:
            rpy = bounded(orientation, MAX_POSITION, "an orientation (rad)")
            if rpy.shape != (3,):
                raise ValueError("orientation must be [roll, pitch, yaw]")
            rot = quat_to_matrix(euler_to_quat(*rpy))
        self.sim.place_body(body, pos, rot)

    @service
    def set_object_dynamics(self, object_name: str, state: bool) -> None:
        body = self.sim.scene_bodies().get(object_name)
        if body is None:
            raise ValueError(f"unknown object {object_name!r}")
        self.sim.set_frozen(body, not bool(state))


def _entry(d, body: int, children: dict) -> list:
    w, x, y, z = d.xquat[body]
    return [children, [float(v) for v in d.xpos[body]], [float(x), float(y), float(z), float(w)]]


class TimeServices:
    """The `time` pseudo-component. Sleeping requests wait in a heap ordered by deadline: a frame looks at
    the first one only, a sleep costs log(n) to schedule and to wake.

    fixed_step runs frames a hundred times faster than real time or more, so a client's round trip, or
    the milliseconds between two of its requests, would be seconds of simulated time. So, in fixed_step,
    for a client whose request ids are numbers (pymorse, morsec.client: 0, 1, 2 ...), a sleep counts from
    the frame where the request numbered just before it arrived, if that was a command (a component's
    service) less than SLEEP_WITH_PREVIOUS (wall clock) before, and no actuator stream message came in
    between: `rotate(...); sleep(1)` measures one second of the rotation; a sleep that follows a message
    to an actuator stream counts from that message. If that request has
    not arrived yet, the sleep starts when it does (within SLEEP_ORDER_WAIT): pymorse sends a component's
    service calls from a thread pool and `sleep` from the caller's thread, and `set_speed(1, 0); sleep(2)`
    sometimes reaches the simulation as sleep, then set_speed, tens of milliseconds later. And when a
    client's last running sleep ends, the loop follows the wall clock until its next (runtime.clock.SleepHold)."""

    def __init__(self, sim):
        self.sim = sim
        self.sleepers: list = []  # heap of (deadline in simulated seconds, order, request)
        self.order = itertools.count()  # ties wake in the order they were asked
        self.abandoned_sleepers = 0  # entries of requests no longer running (cancelled, client gone)
        self.sleeping: dict = {}  # client -> how many of its sleeps are running (started or not)
        self.numbering: dict[Any, Numbering | None] = {}  # client -> its numbered requests (None: not numbered)
        self.deferred: dict[Any, list] = {}  # client -> [(number, seconds, request, wall deadline)] not started
        self.woke: dict[Any, float] = {}  # client -> when (simulated s) a sleep of it last ended (numbered ones)
        self.first: dict[Any, float] = {}  # client -> when (simulated s) its first request came: no sleep counts before
        self.trips: dict[Any, _Trips] = {}  # client -> its round trips since its last command, between two frames

    def interrupt(self) -> None:
        pass

    @service(anytime=True)
    def now(self) -> float:
        return self.sim.clock.now()

    @service(anytime=True)
    def mode(self) -> str:
        return "Fixed Simulation Step" if self.sim.clock.strategy == "fixed_step" else "Best Effort"

    @service(anytime=True)
    def statistics(self) -> dict:
        hold = self.sim.hold
        return {**self.sim.clock.statistics(), "sleeping_requests": len(self.sleepers),
                "sleep_holds": hold.holds if hold else 0, "sleep_holds_overtime": hold.overtime if hold else 0}

    @service
    def set_time_scale(self, value: float) -> bool:
        self.sim.clock.set_scale(value)  # ValueError beyond [MIN_TIME_SCALE, MAX_TIME_SCALE]
        return True

    @async_service
    def sleep(self, time: float) -> None:
        delay = float(time)
        if not math.isfinite(delay):
            raise ValueError("sleep time must be a finite number of seconds")
        request = self.sim.requests.current
        client = request.client
        self.sleeping[client] = self.sleeping.get(client, 0) + 1
        number = request_number(request.id)
        numbering = self.numbering.get(client)
        if number is None or numbering is None:
            self._start(request, delay, since=self._after_stream_command(client))
        elif not numbering.all_before(number):  # the request before it is still on its way: wait for it
            self.deferred.setdefault(client, []).append(
                (number, delay, request, _time.perf_counter() + SLEEP_ORDER_WAIT))
        else:
            previous = numbering.arrivals.get(number - 1)
            if previous is None or not previous[2] or _time.perf_counter() - previous[1] > SLEEP_WITH_PREVIOUS:
                self._start(request, delay, since=self._after_stream_command(client))
            else:  # not before its previous sleep ended, nor before a message to an actuator stream (whose?)
                self._start(request, delay, since=max(previous[0], self.woke.get(client, previous[0]),
                                                      self.sim.last_stream_input))

    sleep._morsec_concurrent = True

    def _after_stream_command(self, client) -> float | None:
        """fixed_step: a sleep that follows a message to an actuator stream by less than SLEEP_WITH_PREVIOUS
        (wall clock) counts from the frame that message arrived at (`publish(cmd); sleep(t)` measures t of
        the command), not before the client's previous sleep ended; None: from now, also when the message
        came before the client's first request (another client's: pymorse opens its streams after its
        service connection)."""
        sim = self.sim
        if sim.hold is None or _time.perf_counter() - sim.last_stream_input_wall > SLEEP_WITH_PREVIOUS:
            return None
        if sim.last_stream_input < self.first.get(client, -math.inf):
            return None
        return max(sim.last_stream_input, self.woke.get(client, sim.last_stream_input))

    def arrived(self, request) -> None:
        """A request arrived (both strategies, before it is handled). MORSE read a client's socket once a frame:
        a request the client sent after the answer to its previous one was read a frame later. morsec answers
        at once, so the frames a client's round trips took are counted instead: from its last command (a
        component's service; the frames before it do not move what the command does), each request read after
        the previous one was answered, with no frame run in between, counts one (ROUND_TRIPS_COUNTED at most),
        and the client's next sleep starts that many frames later (`stop().result(); get_status().result();
        sleep(0.2)` sleeps from two frames after the stop, as MORSE's)."""
        client = request.client
        if client is None:
            return
        frames, poll = self.sim.clock.frames, self.sim.poller.polls
        trips = self.trips.get(client)
        if trips is None or trips.frames != frames:
            trips = self.trips[client] = _Trips(frames)
        elif (trips.since is not None and poll != trips.poll and trips.last is not None
              and not self.sim.requests.pending(trips.last)):
            trips.count = min(trips.count + 1, ROUND_TRIPS_COUNTED)
        if request.component not in PSEUDO_COMPONENTS:
            trips.count, trips.since = 0, _time.perf_counter()
        trips.poll, trips.last = poll, request

    def _round_trips(self, client) -> int:
        """The frames the client's round trips since its last command took in MORSE (see arrived); none once a
        frame ran, or after a message to an actuator stream (a command too, whose sender cannot be told)."""
        trips = self.trips.get(client)
        if (trips is None or trips.since is None or trips.frames != self.sim.clock.frames
                or self.sim.last_stream_input_wall > trips.since):
            return 0
        return trips.count

    def _start(self, request, delay: float, since: float | None = None) -> None:
        """The sleep counts from the end of the frame after `since` (simulated s: when the request before it
        arrived), else after now: MORSE read a request at the logic of the frame after the messages and answers
        a client replies to, and set its alarm from that frame's time (docs/running.md#time). The alarm rings
        at the first frame after that one whose time is past it, within half a frame (MORSE's time_isafter)."""
        self.sim.sleep_started(request)
        dt = self.sim.clock.dt
        read = (self.sim.clock.elapsed if since is None else since) + dt * (1 + self._round_trips(request.client))
        due = read + max(dt / 2, max(0.0, delay) - dt / 2)  # answered at the end of the first frame past `due`
        heapq.heappush(self.sleepers, (due, next(self.order), request))
        self.wake()

    def heard(self, request) -> bool:
        """fixed_step: a request arrived (before it is handled): numbered ones may let a sleep start.
        Whether every request its client numbered before it has arrived (True when not numbered)."""
        client, number = request.client, request_number(request.id)
        if client is not None:
            self.first.setdefault(client, self.sim.clock.elapsed)
        if client is None or number is None:
            return True
        numbering = self.numbering.get(client, _UNSEEN)
        if numbering is None:
            return True
        if numbering is _UNSEEN:
            numbering = self.numbering[client] = Numbering(number)
        command = request.component not in PSEUDO_COMPONENTS
        if not numbering.saw(number, self.sim.clock.elapsed, _time.perf_counter(), command):
            self._unnumbered(client)
            return True
        if client in self.deferred:
            self._start_ready(client)
        return numbering.all_before(number)

    def _start_ready(self, client) -> None:
        numbering = self.numbering.get(client)
        waiting = self.deferred.pop(client)
        ready = [entry for entry in waiting if numbering is None or numbering.all_before(entry[0])]
        rest = [entry for entry in waiting if entry not in ready]
        if rest:
            self.deferred[client] = rest
        for _, delay, request, _ in sorted(ready, key=lambda entry: entry[0]):
            self._start(request, delay)

    def _unnumbered(self, client) -> None:
        """The client's ids are not a sequence (a gap that stays, numbers far ahead): its sleeps start
        when they arrive from now on."""
        self.numbering[client] = None
        if client in self.deferred:
            log.info("a client's sleep waited %g s for requests it numbered before it, in vain: its requests "
                     "are taken as they arrive from now on", SLEEP_ORDER_WAIT)
            self._start_ready(client)

    def ending(self) -> bool:
        """Whether a sleep ends at this frame (its answer then leaves after the frame's wait)."""
        return bool(self.sleepers) and self.sleepers[0][0] < self.sim.clock.elapsed

    def wake(self) -> None:
        """Answer the sleeps whose time has come."""
        if self.deferred:
            now = _time.perf_counter()
            for client in [c for c, waiting in self.deferred.items() if min(e[3] for e in waiting) <= now]:
                self._unnumbered(client)
        sleepers = self.sleepers
        now = self.sim.clock.elapsed
        while sleepers and sleepers[0][0] < now:
            request = heapq.heappop(sleepers)[2]
            if self.sim.requests.is_running(request):
                self.sim.requests.complete("time", "SUCCESS", None, request)
                if request.client in self.numbering:
                    self.woke[request.client] = self.sim.clock.elapsed
                if self._awake(request.client):
                    self.sim.sleep_ended(request)  # fixed_step: real time until its next sleep
            else:
                self.abandoned_sleepers -= 1

    def _awake(self, client) -> bool:
        """One sleep of the client is over: whether it was its last one running."""
        left = self.sleeping[client] - 1
        if left:
            self.sleeping[client] = left
            return False
        del self.sleeping[client]
        return True

    def abandoned(self, requests: list) -> None:
        """Sleeping requests were cancelled or their client left: once most of the heap is such requests,
        it is rebuilt without them (memory goes with the clients, at a cost linear overall)."""
        for request in requests:
            self._awake(request.client)
            waiting = self.deferred.get(request.client)
            if waiting and any(entry[2] is request for entry in waiting):  # not started: not in the heap
                waiting[:] = [entry for entry in waiting if entry[2] is not request]
                if not waiting:
                    del self.deferred[request.client]
            else:
                self.abandoned_sleepers += 1
        if self.abandoned_sleepers * 2 > len(self.sleepers):
            self.sleepers = [entry for entry in self.sleepers if self.sim.requests.is_running(entry[2])]
            heapq.heapify(self.sleepers)
            self.abandoned_sleepers = 0

    def left(self, client) -> None:
        """The client went away (its running sleeps were abandoned already)."""
        self.numbering.pop(client, None)
        self.deferred.pop(client, None)
        self.woke.pop(client, None)
        self.first.pop(client, None)
        self.trips.pop(client, None)


_UNSEEN: Any = object()


class _Trips:
    """A client's requests between two frames (TimeServices.arrived)."""

    def __init__(self, frames: int):
        self.frames = frames  # the frame count they came after
        self.count = 0  # round trips since the last command
        self.since: float | None = None  # wall clock of the last command; None: none in this window
        self.poll = -1  # the poll that read the last request
        self.last = None  # the last request


class Communication:
    """The `communication` pseudo-component."""

    def __init__(self, sim):
        self.sim = sim

    def interrupt(self) -> None:
        pass

    @service
    def distance_and_view(self, robot1: str, robot2: str) -> list:
        bodies = self.sim.scene_bodies()
        for name in (robot1, robot2):
            if name not in bodies:
                raise ValueError(f"unknown robot {name!r}")
        m, d = self.sim.model, self.sim.data
        a, b = bodies[robot1], bodies[robot2]
        pa, pb = d.xpos[a].copy(), d.xpos[b].copy()
        delta = pb - pa
        distance = float(np.linalg.norm(delta))
        if distance == 0:
            return [0.0, True]
        direction = delta / distance
        origin, travelled = pa.copy(), 0.0
        geom = np.zeros(1, dtype=np.int32)
        for _ in range(8):  # step past the first robot's own geoms
            hit = mujoco.mj_ray(m, d, origin, direction, None, 1, -1, geom)
            if hit < 0 or travelled + hit >= distance:
                return [distance, True]
            root = m.body_rootid[m.geom_bodyid[geom[0]]]
            if root == m.body_rootid[b]:
                return [distance, True]
            if root != m.body_rootid[a]:
                return [distance, False]
            travelled += hit + 1e-4
            origin = pa + direction * travelled
        return [distance, False]
