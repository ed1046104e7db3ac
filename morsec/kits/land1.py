"""MORSE's "land-1" countryside, shared by its outdoor environments (land-1/trees, land-1/buildings_1,
land-1/buildings_2, outdoors, water-1/water_scene): the same 121 x 148 m ground, scaled to a different height
in each, and the same town blocks.

What is MORSE's: the ground's extent (x from -60.6 to 60.7 m, y from -74.6 to 73.6 m), the lie of the land
(a plateau north of y = 10 m and a hill in the south-west, at the ground's full height; a valley through the
origin along the x axis, at z = 0; low rolling ground to the south and east) and each environment's height
of it; the town blocks' footprints and heights (the buildings of its City meshes). What is not: the exact
surface, here smooth hills of our own (`height`), and the buildings' shapes, here boxes.
"""

from __future__ import annotations

from morsec.kits.layout import Part, Rgba, Terrain, ball, block, bump, column, rgba, smoothstep

EXTENT_X = (-60.6, 60.7)
EXTENT_Y = (-74.6, 73.6)
GRID_STEP = 2.0  # m between the height field's samples
BARK = rgba(0.36, 0.25, 0.15)
LEAVES = rgba(0.2, 0.45, 0.15)


def height(x: float, y: float) -> float:
    """The ground's height at (x, y), 0 (the valley through the origin) to 1 (the plateau's top)."""
    # the northern plateau: up from y = 3 to y = 16, lower towards the northern edge and the western side, with
    # a shallow dip around (10, 35)
    plateau = smoothstep(3.0, 16.0, y) * smoothstep(-48.0, -28.0, x) * (1.0 - 0.7 * smoothstep(52.0, 68.0, y))
    plateau -= 0.2 * bump(x, y, 10.0, 35.0, 14.0)
    # the south-western hill
    hill = 1.0 - smoothstep(12.0, 32.0, ((x + 60.0) ** 2 + (y + 42.0) ** 2) ** 0.5)
    # rolling ground to the south and east
    rolls = max(0.35 * bump(x, y, 0.0, -33.0, 18.0), 0.45 * bump(x, y, 35.0, -30.0, 16.0),
                0.35 * bump(x, y, -10.0, -70.0, 14.0), 0.45 * bump(x, y, 30.0, -72.0, 14.0),
                0.3 * bump(x, y, -22.0, -18.0, 10.0))
    return min(1.0, max(0.0, plateau, hill, rolls))


def terrain(top: float, color: Rgba) -> Terrain:
    """The land-1 ground as a height field `top` m high at its highest (MORSE's heights: 2.83 m in land-1/trees
    and land-1/buildings_2, 4.15 m in outdoors, 11.15 m in land-1/buildings_1 and water-1/water_scene)."""
    return Terrain("ground", EXTENT_X, EXTENT_Y, lambda x, y: top * height(x, y), color, step=GRID_STEP)


# the town blocks: one box per building of MORSE's City meshes, ((x0, y0), (x1, y1), height above the ground)
CITY_3 = (
    ((-12.4, 25.2), (-3.3, 34.3), 3.0),
    ((-11.6, 41.0), (-5.6, 45.7), 8.8),
    ((-10.3, 33.8), (-4.7, 41.7), 3.3),
    ((-10.2, 46.4), (-2.8, 51.6), 3.5),
    ((9.9, 32.2), (18.6, 39.7), 2.9),
    ((30.9, 45.6), (35.7, 50.1), 5.7),
    ((35.7, 28.4), (45.1, 37.5), 5.8),
    ((38.8, 47.5), (45.9, 54.7), 3.0),
    ((49.7, 35.7), (58.0, 44.5), 11.0),
)
CITY_1_2_3 = (
    ((-58.2, -3.9), (-50.9, 3.1), 3.2),
    ((-50.4, -4.2), (-42.8, -1.0), 6.4),
    ((-50.4, 0.8), (-44.2, 4.0), 5.8),
    ((-40.3, -4.4), (-29.3, 0.7), 3.4),
    ((-29.4, -7.2), (-22.5, -1.7), 5.3),
    ((-25.7, 5.0), (-20.8, 8.2), 2.9),
    ((-20.7, 4.0), (-14.0, 8.2), 3.0),
    ((-13.6, 4.1), (-10.6, 8.1), 12.3),
    ((-12.4, 25.2), (-3.3, 34.3), 3.0),
    ((-11.6, 41.0), (-5.6, 45.7), 8.8),
    ((-10.3, 33.8), (-4.7, 41.7), 3.3),
    ((-10.2, 46.4), (-2.8, 51.6), 3.5),
    ((9.9, 32.2), (18.6, 39.7), 2.9),
    ((17.7, -47.4), (24.9, -40.1), 3.0),
    ((22.9, -68.1), (33.9, -65.1), 14.7),
    ((24.8, -65.2), (29.5, -58.8), 5.7),
    ((24.8, -58.2), (32.0, -54.6), 3.3),
    ((26.0, -41.3), (30.2, -36.5), 21.5),
    ((29.8, -65.2), (34.4, -58.7), 3.0),
    ((30.9, 45.6), (35.7, 50.1), 5.7),
    ((31.8, -56.2), (35.1, -51.0), 8.8),
    ((31.8, -29.3), (35.0, -25.5), 5.7),
    ((35.7, 28.4), (45.1, 37.5), 5.8),
    ((37.8, -54.4), (41.0, -47.6), 3.5),
    ((38.0, -45.4), (46.8, -39.2), 2.8),
    ((38.2, -32.1), (43.9, -26.9), 30.9),
    ((38.8, 47.5), (45.9, 54.7), 3.0),
    ((39.5, -65.3), (42.7, -54.3), 2.7),
    ((43.4, -51.4), (48.8, -46.9), 3.4),
    ((48.5, -32.2), (55.0, -24.9), 5.8),
    ((49.7, 35.7), (58.0, 44.5), 11.0),
)


def buildings(footprints, top: float, wall: Rgba, prefix: str = "building") -> tuple[Part, ...]:
    """The buildings standing on the land-1 ground `top` m high: each from below the ground under its
    footprint up to its own height above the ground's highest point there."""
    parts = []
    for i, ((x0, y0), (x1, y1), tall) in enumerate(footprints):
        corners = [top * height(x, y) for x in (x0, (x0 + x1) / 2, x1) for y in (y0, (y0 + y1) / 2, y1)]
        parts.append(block(f"{prefix}_{i:02d}", (x0, y0, min(corners) - 0.5), (x1, y1, max(corners) + tall), wall))
    return tuple(parts)


def trees(places, top: float) -> tuple[Part, ...]:
    """MORSE's small tree (its BB_Trunk, 0.28 m across and 2.16 m high, and its BB_Leaves, a 2.3 m ball
    centred 3.26 m up) at each place, on the ground."""
    parts: list[Part] = []
    for i, (x, y) in enumerate(places):
        z = top * height(x, y)
        parts.append(column(f"tree_{i:02d}_trunk", (x, y), 0.14, z - 0.3, z + 2.16, BARK))
        parts.append(ball(f"tree_{i:02d}_leaves", (x, y, z + 3.26), 1.15, LEAVES))
    return tuple(parts)
