"""The metrics morsec computes after a run, from the CSV files its streams wrote (morsec.app.sweep.instrument
adds them): per robot, the final pose, the distance travelled, the contacts begun, and the simulated time it
first entered each zone. Standard library only: this runs on the workers.

Columns: `<robot>.final_x`, `.final_y`, `.final_z`, `.final_yaw`, `<robot>.distance` (m, the pose's path
in 3D), `<robot>.collisions` (each thing the robot begins to touch counts once per contact),
`<robot>.time_to.<zone>` (s, empty when it never got there)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

POSE_SENSOR = "sweep_pose"
COLLISION_SENSOR = "sweep_collision"
FOLDER = "sweep"  # inside the run's output folder


def pose_file(robot: str) -> str:
    return f"{FOLDER}/{robot}.pose.csv"


def collision_file(robot: str) -> str:
    return f"{FOLDER}/{robot}.collision.csv"


def compute(metrics: list[dict], output_dir: Path, build_dir: Path) -> dict[str, Any]:
    manifest = json.loads((Path(build_dir) / "manifest.json").read_text(encoding="utf-8"))
    zones = {z["name"]: z for z in manifest["scene"]["zones"]}
    frequency = {c["fqn"]: float(c["frequency"]) for c in manifest["components"]}
    out: dict[str, Any] = {}
    for metric in metrics:
        robot = metric["robot"]
        poses = _rows(Path(output_dir) / pose_file(robot))
        last = poses[-1] if poses else {}
        for axis in ("x", "y", "z", "yaw"):
            out[f"{robot}.final_{axis}"] = float(last[axis]) if last else None
        points = [(float(r["x"]), float(r["y"]), float(r["z"])) for r in poses]
        out[f"{robot}.distance"] = math.fsum(math.dist(a, b) for a, b in zip(points, points[1:]))
        period = 1.0 / frequency.get(f"{robot}.{COLLISION_SENSOR}", 60.0)
        out[f"{robot}.collisions"] = contacts_begun(_rows(Path(output_dir) / collision_file(robot)), period)
        for name in metric["zones"]:
            out[f"{robot}.time_to.{name}"] = first_entry(poses, points, zones[name])
    return out


def contacts_begun(rows: list[dict], period: float) -> int:
    """The collision sensor writes only while its robot touches something: a thing counts when it is in a row's
    `objects` and was not in the row a sensor period before."""
    count, before, t_before = 0, set(), -math.inf
    for row in rows:
        t = float(row["timestamp"])
        objects = {o for o in row.get("objects", "").split(",") if o}
        if t - t_before > 1.5 * period:
            before = set()
        count += len(objects - before)
        before, t_before = objects, t
    return count


def first_entry(poses: list[dict], points: list[tuple], zone: dict) -> float | None:
    centre, half = zone["translate"], [s / 2 for s in zone["size"]]
    for row, point in zip(poses, points):
        if all(abs(p - c) <= h for p, c, h in zip(point, centre, half)):
            return float(row["timestamp"])
    return None


def _rows(path: Path) -> list[dict]:
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except FileNotFoundError:
        return []
