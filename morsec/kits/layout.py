"""The static pieces of an environment, declared as data in its component.py (`Environment.layout`,
`Environment.terrain`) and written to MJCF by the compiler: walls, furniture, buildings, trees, a terrain.

Each piece is an axis-aligned shape given by the box that bounds it (its lower and upper corners, world frame,
metres), so that an environment reproducing a MORSE world is a table of the original objects' extents:

    layout = (
        block("wall_north", (-4.0, 5.96, 0.0), (4.0, 6.05, 2.5), WALL),
        column("pillar", (3.0, 1.0), 0.2, 0.0, 3.0, GREY),
        ball("crown", (10.0, 4.0, 5.0), 2.2, LEAVES),
    )

Every piece is a geom named `env/<name>` ("env/" is a prefix no scene object can take); it collides unless
`collides=False` (then it is drawn only, as a visual geom). A terrain is a MuJoCo height field whose heights
come from a function of (x, y), sampled on a regular grid.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Literal

from morsec.kits.geometry import euler_to_quat

Vec3 = tuple[float, float, float]
Rgba = tuple[float, float, float, float]
PREFIX = "env/"
FLOOR_SINK = 0.02  # m: how far a terrain's height field lies under its flat floor


def rgba(r: float, g: float, b: float, a: float = 1.0) -> Rgba:
    return (r, g, b, a)


@dataclass(frozen=True)
class Part:
    """One static shape of a world: a box, a vertical cylinder, a sphere or an ellipsoid filling the
    axis-aligned box from `lo` to `hi`, then turned by the XYZ Euler angles `euler` (rad) about its centre."""

    name: str
    shape: Literal["box", "cylinder", "sphere", "ellipsoid"]
    lo: Vec3
    hi: Vec3
    color: Rgba
    collides: bool = True
    euler: Vec3 = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        if any(h <= lo for lo, h in zip(self.lo, self.hi)):
            raise ValueError(f"layout part {self.name!r}: its upper corner {self.hi} must be above its lower corner "
                             f"{self.lo} on every axis")

    @property
    def geom_name(self) -> str:
        return PREFIX + self.name

    @property
    def centre(self) -> Vec3:
        return tuple((lo + hi) / 2 for lo, hi in zip(self.lo, self.hi))  # type: ignore[return-value]

    @property
    def extent(self) -> Vec3:
        """Full size along x, y, z."""
        return tuple(hi - lo for lo, hi in zip(self.lo, self.hi))  # type: ignore[return-value]

    @property
    def quat(self) -> tuple[float, ...] | None:
        """(w, x, y, z) of its turn, R = Rz Ry Rx of `euler` (Blender's XYZ Euler); None: not turned."""
        if self.euler == (0.0, 0.0, 0.0):
            return None
        return tuple(float(q) for q in euler_to_quat(*self.euler))

    @property
    def mjcf_size(self) -> tuple[float, ...]:
        """MuJoCo's `size` of the geom: half extents (box, ellipsoid), radius and half height (cylinder),
        radius (sphere)."""
        half = tuple(s / 2 for s in self.extent)
        if self.shape == "cylinder":
            return (min(half[0], half[1]), half[2])
        if self.shape == "sphere":
            return (min(half),)
        return half


def block(name: str, lo: Iterable[float], hi: Iterable[float], color: Rgba, collides: bool = True) -> Part:
    """A box from corner `lo` to corner `hi`."""
    return Part(name, "box", _vec(lo), _vec(hi), color, collides)


def column(name: str, xy: Iterable[float], radius: float, z0: float, z1: float, color: Rgba,
           collides: bool = True) -> Part:
    """A vertical cylinder of `radius` on (x, y), from z0 up to z1."""
    x, y = xy
    return Part(name, "cylinder", (x - radius, y - radius, z0), (x + radius, y + radius, z1), color, collides)


def ball(name: str, centre: Iterable[float], radius: float, color: Rgba, collides: bool = True) -> Part:
    x, y, z = centre
    return Part(name, "sphere", (x - radius, y - radius, z - radius), (x + radius, y + radius, z + radius), color,
                collides)


def blob(name: str, lo: Iterable[float], hi: Iterable[float], color: Rgba, collides: bool = True) -> Part:
    """An ellipsoid filling the box from `lo` to `hi` (a rock, a bush, a crown of leaves)."""
    return Part(name, "ellipsoid", _vec(lo), _vec(hi), color, collides)


def table(name: str, lo: Iterable[float], hi: Iterable[float], color: Rgba, top: float = 0.04,
          leg: float = 0.05) -> tuple[Part, ...]:
    """A table (a desk) filling the box from `lo` to `hi`: a top `top` m thick and four square legs `leg` m
    across at its corners (`<name>_top`, `<name>_leg_1` ...), so that chairs slide under it."""
    (x0, y0, z0), (x1, y1, z1) = _vec(lo), _vec(hi)
    parts = [Part(f"{name}_top", "box", (x0, y0, z1 - top), (x1, y1, z1), color)]
    for i, (x, y) in enumerate(((x0, y0), (x1 - leg, y0), (x0, y1 - leg), (x1 - leg, y1 - leg)), start=1):
        parts.append(Part(f"{name}_leg_{i}", "box", (x, y, z0), (x + leg, y + leg, z1 - top), color))
    return tuple(parts)


def segment(name: str, start: Iterable[float], end: Iterable[float], width: float, color: Rgba,
            thickness: float = 0.2) -> Part:
    """A straight strip of road or path `width` m wide from point `start` to point `end` (its top surface
    runs through both), `thickness` m deep."""
    a, b = _vec(start), _vec(end)
    dx, dy, dz = (b[0] - a[0], b[1] - a[1], b[2] - a[2])
    run = math.hypot(dx, dy)
    length = math.hypot(run, dz)
    yaw, pitch = math.atan2(dy, dx), -math.atan2(dz, run)
    # the centre sits thickness / 2 under the middle of the line, along the strip's own up axis
    up = (math.sin(pitch) * math.cos(yaw), math.sin(pitch) * math.sin(yaw), math.cos(pitch))
    centre = tuple((a[k] + b[k]) / 2 - up[k] * thickness / 2 for k in range(3))
    half = (length / 2, width / 2, thickness / 2)
    return Part(name, "box", tuple(c - h for c, h in zip(centre, half)),  # type: ignore[arg-type]
                tuple(c + h for c, h in zip(centre, half)), color, True, (0.0, pitch, yaw))  # type: ignore[arg-type]


def _vec(values: Iterable[float]) -> Vec3:
    x, y, z = (float(v) for v in values)
    return (x, y, z)


@dataclass(frozen=True)
class Terrain:
    """Uneven ground: heights `height(x, y)` (metres, world frame) over x in `x`, y in `y`, sampled every
    `step` metres, as a MuJoCo height field named `env/<name>_relief`; `depth` m of solid under its lowest
    point. Where it is at its lowest, a flat box `env/<name>` (top at that height) is the ground: MuJoCo's
    height-field contacts rock a box set down on flat parts, a box's contacts do not; the height field lies
    FLOOR_SINK m lower, so that it meets things only where the land rises."""

    name: str
    x: tuple[float, float]
    y: tuple[float, float]
    height: Callable[[float, float], float] = field(compare=False)
    color: Rgba = rgba(0.4, 0.5, 0.3)
    step: float = 1.0
    depth: float = 1.0

    @property
    def geom_name(self) -> str:
        return PREFIX + self.name

    @property
    def relief_name(self) -> str:
        return PREFIX + self.name + "_relief"

    @property
    def shape(self) -> tuple[int, int]:
        """(rows along y, columns along x)."""
        return (round((self.y[1] - self.y[0]) / self.step) + 1, round((self.x[1] - self.x[0]) / self.step) + 1)

    def grid(self) -> list[list[float]]:
        """Heights, row by row from the lowest y, each row from the lowest x."""
        rows, cols = self.shape
        dx = (self.x[1] - self.x[0]) / (cols - 1)
        dy = (self.y[1] - self.y[0]) / (rows - 1)
        return [[float(self.height(self.x[0] + i * dx, self.y[0] + j * dy)) for i in range(cols)] for j in range(rows)]

    def mjcf(self) -> dict:
        """What the compiler writes: the height field's size (MuJoCo's rx, ry, zmax, base), its elevation
        (0 at the lowest point, 1 at the highest: MuJoCo scales it by zmax), rows from the highest y down, and
        the geom's position."""
        heights = self.grid()
        low = min(min(row) for row in heights)
        high = max(max(row) for row in heights)
        top = max(high - low, 1e-3)
        rows, cols = self.shape
        half = ((self.x[1] - self.x[0]) / 2, (self.y[1] - self.y[0]) / 2)
        centre = ((self.x[0] + self.x[1]) / 2, (self.y[0] + self.y[1]) / 2)
        return {
            "name": self.relief_name, "nrow": rows, "ncol": cols,
            "size": (*half, top, self.depth),
            # MuJoCo reads the elevation's first row as the field's far side (highest y)
            "elevation": " ".join(f"{(h - low) / top:.4f}" for row in reversed(heights) for h in row),
            "pos": (*centre, low - FLOOR_SINK),
            "color": self.color,
            "floor": {"name": self.geom_name, "pos": (*centre, low - 0.05), "size": (*half, 0.05)},
        }


def smoothstep(edge0: float, edge1: float, value: float) -> float:
    """0 below edge0, 1 above edge1, a smooth S between (edge0 > edge1 reverses it)."""
    t = min(1.0, max(0.0, (value - edge0) / (edge1 - edge0)))
    return t * t * (3 - 2 * t)


def bump(x: float, y: float, cx: float, cy: float, radius: float) -> float:
    """A smooth round hill of height 1 centred on (cx, cy), 0 beyond `radius`."""
    d = math.hypot(x - cx, y - cy) / radius
    return 0.5 * (1 + math.cos(math.pi * d)) if d < 1 else 0.0


@dataclass(frozen=True)
class PropPart:
    """One shape of a prop object (`Prop.variants`): a box or an upright cylinder (x, y: its diameter) of full
    size `size` centred at `centre` from the object's origin; `rgba` None: the object's colour."""

    name: str
    centre: Vec3
    size: Vec3
    shape: Literal["box", "cylinder"] = "box"
    rgba: Rgba | None = None


def prop_object(parts: Iterable[PropPart], color: Iterable[float], mass: float = 1.0, dynamic: bool = True,
                properties: dict | None = None) -> dict:
    """A `Prop.variants` entry: the object's parts, its size (what its parts fill, around its origin: the
    full extent of their bounding box), colour, mass, whether it moves, its game properties."""
    parts = tuple(parts)
    size = [round(max(p.centre[k] + p.size[k] / 2 for p in parts) - min(p.centre[k] - p.size[k] / 2 for p in parts), 4)
            for k in range(3)]
    entry = {"size": size, "color": [float(c) for c in color], "dynamic": dynamic, "mass": mass, "parts": parts}
    if properties:
        entry["properties"] = dict(properties)
    return entry
