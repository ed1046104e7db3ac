"""What a sweep adds to each variant's scene so that morsec can measure its runs from their streams: for each
robot the metrics name, a pose sensor at its origin (or the robot's own pose sensor the metrics name) and a
collision sensor, each with a CSV text stream into the run's output folder; and timestamps from 0
(`environment.time.relative`), so that a message's time is the simulated time, the same in every run.

Sensors change nothing in the physics (their bodies have no mass and no contacts) and each modifier draws from
its own random stream (named after its component), so the sensors added leave the scene's noise as it was."""

from __future__ import annotations

from typing import Any

from morsec.app.sweep.metrics import COLLISION_SENSOR, POSE_SENSOR, collision_file, pose_file
from morsec.app.sweep.spec import MetricSpec, Sweep
from morsec.errors import did_you_mean


def check(sweep: Sweep, scene: dict, cat) -> None:
    """Every robot, pose sensor and zone the metrics name is in the scene; else an error at its place."""
    seen: set[str] = set()
    robots = _items(scene.get("robots"))
    zones = [name for name in (_name(z) for z in _items(scene.get("zones"))) if name]
    for i, metric in enumerate(sweep.spec.metrics):
        robot = _find(robots, metric.robot)
        if robot is None:
            known = [n for n in (_name(r) for r in robots) if n]
            raise sweep.error(f"the scene has no robot {metric.robot!r}{_hint(metric.robot, known)}", "metrics", i,
                              "robot")
        if metric.robot in seen:
            raise sweep.error(f"robot {metric.robot!r} is measured twice", "metrics", i, "robot")
        seen.add(metric.robot)
        components = list(_components(robot))
        if metric.pose is not None:
            sensor = _find(components, metric.pose)
            if sensor is None:
                known = [n for n in (_name(c) for c in components) if n]
                raise sweep.error(f"robot {metric.robot!r} has no component {metric.pose!r}"
                                  f"{_hint(metric.pose, known)}", "metrics", i, "pose")
            if cat.resolve("sensors", str(sensor.get("type"))) != "pose":
                raise sweep.error(f"{metric.robot}.{metric.pose} is a {sensor.get('type')!r}, not a pose sensor",
                                  "metrics", i, "pose")
        for name in (POSE_SENSOR, COLLISION_SENSOR):
            if _find(components, name) is not None:
                raise sweep.error(f"robot {metric.robot!r} has a component named {name!r}: the sweep's own "
                                  "sensors have that name; rename it", "metrics", i, "robot")
        for j, zone in enumerate(metric.zones):
            if zone not in zones:
                raise sweep.error(f"the scene has no zone {zone!r}{_hint(zone, zones)}", "metrics", i, "zones", j)


def add_sensors(metrics: list[MetricSpec], scene: dict) -> None:
    """Add the metrics' sensors and streams to a variant's scene data (in place); relative timestamps."""
    env = scene.setdefault("environment", {})
    env.setdefault("time", {})["relative"] = True
    robots = _items(scene.get("robots"))
    for metric in metrics:
        robot = _find(robots, metric.robot)
        if robot is None:  # a variant renamed it: the metrics say nothing of it
            continue
        components = robot.setdefault("components", [])
        pose = _stream(pose_file(metric.robot))
        if metric.pose is None:
            components.append({"name": POSE_SENSOR, "type": "pose", "streams": [pose]})
        else:
            sensor = _find(list(_components(robot)), metric.pose)
            if sensor is not None:
                sensor.setdefault("streams", []).append(pose)
        components.append({"name": COLLISION_SENSOR, "type": "collision",
                           "streams": [_stream(collision_file(metric.robot))]})


def _stream(file: str) -> dict:
    return {"middleware": "text", "format": "csv", "file": file}


def _items(value: Any) -> list[dict]:
    return [item for item in value if isinstance(item, dict)] if isinstance(value, list) else []


def _name(item: dict) -> str | None:
    name = item.get("name", item.get("type"))
    return name if isinstance(name, str) else None


def _find(items: list[dict], name: str) -> dict | None:
    return next((item for item in items if _name(item) == name), None)


def _components(owner: dict):
    for component in _items(owner.get("components")):
        yield component
        yield from _components(component)


def _hint(word: str, known: list[str]) -> str:
    return did_you_mean(word, known) or (f" (there are: {', '.join(map(repr, known))})" if known else "")
