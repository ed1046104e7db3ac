"""The `simulation` pseudo-component: supervision services (reference §3.3)."""

from __future__ import annotations

import heapq
import itertools
import math

import mujoco
import numpy as np

from morsec.component.services import async_service, service
from morsec.constants import MAX_POSITION
from morsec.kits.bounds import bounded
from morsec.kits.geometry import euler_to_quat, quat_to_matrix


class Supervision:
    def __init__(self, sim):
        self.sim = sim

    def interrupt(self) -> None:
        pass

    @service
    def list_robots(self) -> list[str]:
        return [r.name for r in self.sim.robots]

    @service
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
    the first one only, a sleep costs log(n) to schedule and to wake."""

    def __init__(self, sim):
        self.sim = sim
        self.sleepers: list = []  # heap of (deadline in simulated seconds, order, request)
        self.order = itertools.count()  # ties wake in the order they were asked
        self.abandoned_sleepers = 0  # entries of requests no longer running (cancelled, client gone)

    def interrupt(self) -> None:
        pass

    @service
    def now(self) -> float:
        return self.sim.clock.now()

    @service
    def mode(self) -> str:
        return "Fixed Simulation Step" if self.sim.clock.strategy == "fixed_step" else "Best Effort"

    @service
    def statistics(self) -> dict:
        return {**self.sim.clock.statistics(), "sleeping_requests": len(self.sleepers)}

    @service
    def set_time_scale(self, value: float) -> bool:
        self.sim.clock.set_scale(value)  # ValueError beyond [MIN_TIME_SCALE, MAX_TIME_SCALE]
        return True

    @async_service
    def sleep(self, time: float) -> None:
        delay = float(time)
        if not math.isfinite(delay):
            raise ValueError("sleep time must be a finite number of seconds")
        deadline = self.sim.clock.elapsed + max(0.0, delay)
        heapq.heappush(self.sleepers, (deadline, next(self.order), self.sim.requests.current))
        self.wake()

    sleep._morsec_concurrent = True

    def wake(self) -> None:
        sleepers = self.sleepers
        due = self.sim.clock.elapsed + 1e-9
        while sleepers and sleepers[0][0] <= due:
            request = heapq.heappop(sleepers)[2]
            if self.sim.requests.is_running(request):
                self.sim.requests.complete("time", "SUCCESS", None, request)
            else:
                self.abandoned_sleepers -= 1

    def abandoned(self, requests: list) -> None:
        """Sleeping requests were cancelled or their client left: once most of the heap is such requests,
        it is rebuilt without them (memory goes with the clients, at a cost linear overall)."""
        self.abandoned_sleepers += len(requests)
        if self.abandoned_sleepers * 2 > len(self.sleepers):
            self.sleepers = [entry for entry in self.sleepers if self.sim.requests.is_running(entry[2])]
            heapq.heapify(self.sleepers)
            self.abandoned_sleepers = 0


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
