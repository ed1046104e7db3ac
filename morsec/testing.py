"""Run a scene in-process for tests: build into a temporary folder, step it, read components' data.

    from morsec.testing import simulate
    with simulate(SCENE_YAML, tmp_path) as sim:
        sim.run_for(2.0)
        assert sim.data("robot.pose")["x"] > 1.9

Its servers listen on free ports (the OS picks them), so tests run side by side."""

from __future__ import annotations

import contextlib
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import yaml

from morsec.app.project import build_scene
from morsec.component.catalogue import load_catalogue
from morsec.runtime.simulation import RunOptions, Simulation


class Harness:
    def __init__(self, sim: Simulation):
        self.sim = sim

    @property
    def time(self) -> float:
        return self.sim.clock.elapsed

    def step(self, frames: int = 1) -> None:
        for _ in range(frames):
            self.sim.frame()
            self.sim.answer()

    def run_for(self, seconds: float) -> None:
        self.step(int(round(seconds * self.sim.clock.frequency)))

    def component(self, fqn: str) -> Any:
        return self.sim.component(fqn).instance

    def data(self, fqn: str) -> dict:
        return dict(self.component(fqn).local_data)

    def command(self, fqn: str, **values) -> None:
        """What a client's message on an actuator's stream does, at once: replace its data (unsent fields
        take their defaults) and run its input modifiers."""
        self.sim.receive(self.sim.component(fqn), values)

    def call(self, fqn: str, service: str, *args) -> Any:
        """Call a component's service method directly (synchronous services)."""
        return getattr(self.component(fqn), service)(*args)

    def client(self) -> ServiceClient:
        """A client sending service requests as one on the socket would (asynchronous ones, cancel)."""
        return ServiceClient(self)

    def body_pose(self, name: str):
        import mujoco
        body = mujoco.mj_name2id(self.sim.model, mujoco.mjtObj.mjOBJ_BODY, name)
        return self.sim.data.xpos[body].copy(), self.sim.data.xmat[body].reshape(3, 3).copy()

    def yaw(self, name: str) -> float:
        _, rot = self.body_pose(name)
        return math.atan2(rot[1, 0], rot[0, 0])


class ServiceClient:
    """Service requests through the simulation's request manager, as a socket client sends them:
    `replies[rid]` is (status, result) once answered, `times[rid]` the simulated time it came at."""

    def __init__(self, harness: Harness):
        self.harness = harness
        self.replies: dict[str, tuple[str, Any]] = {}
        self.times: dict[str, float] = {}
        self.count = 0

    def send(self, component: str, service: str, *args) -> str:
        from morsec.component.services import Request
        self.count += 1
        rid = f"r{self.count}"
        self.harness.sim.requests.handle(Request(rid, component, service, list(args), self._reply, client=self))
        return rid

    def _reply(self, rid: str, status: str, result: Any) -> None:
        self.replies[rid] = (status, result)
        self.times[rid] = self.harness.time

    def call(self, component: str, service: str, *args) -> Any:
        """A synchronous service's result; AssertionError if it did not answer SUCCESS at once."""
        rid = self.send(component, service, *args)
        status, result = self.replies.pop(rid, ("no answer", None))
        assert status == "SUCCESS", (service, status, result)
        return result

    def cancel(self, rid: str) -> None:
        self.harness.sim.requests.cancel(self, rid)

    def wait(self, rid: str, seconds: float = 10.0) -> tuple[str, Any, float]:
        """Step until `rid` is answered (at most `seconds`): (status, result, simulated time of the answer)."""
        for _ in range(int(seconds * self.harness.sim.clock.frequency)):
            if rid in self.replies:
                break
            self.harness.step()
        status, result = self.replies[rid]
        return status, result, self.times[rid]


@contextlib.contextmanager
def simulate(scene: str | dict, tmp_path: Path, *, project: Path | None = None, seed: int | None = None,
             name: str = "scene") -> Iterator[Harness]:
    """`project`: a folder of a morsec project whose components the scene uses (default: the current one)."""
    tmp_path = Path(tmp_path)
    text = scene if isinstance(scene, str) else yaml.safe_dump(scene, sort_keys=False)
    source = tmp_path / f"{name}.yaml"
    source.write_text(text)
    cat = load_catalogue(Path(project) if project is not None else Path.cwd())
    build_dir = build_scene(source, tmp_path / f"build-{name}", cat)
    options = RunOptions(strategy="fixed_step", seed=seed, output_dir=tmp_path, service_port=0, port_base=0)
    sim = Simulation(build_dir, options)
    try:
        yield Harness(sim)
    finally:
        sim.close()
