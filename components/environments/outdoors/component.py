from morsec.component import Environment
from morsec.kits import land1
from morsec.kits.layout import Part, blob, block, rgba

TOP = 4.15  # m: the ground's highest point in MORSE's outdoors.blend
GRASS = rgba(0.4, 0.52, 0.26)
WALL = rgba(1.0, 0.993, 0.719)
BARK = rgba(0.36, 0.25, 0.15)
LEAVES = rgba(0.45, 0.35, 0.18)  # MORSE's brown trees
ROCK = rgba(0.3, 0.28, 0.27)
CRATE = rgba(0.62, 0.5, 0.34)
FENCE = rgba(0.9, 0.9, 0.88)
BUSH = rgba(0.25, 0.42, 0.18)

# where MORSE's outdoors.blend puts its things (the objects' x, y; they stand on the ground)
BIG_TREES = ((2.8, -39.5), (37.5, 8.1), (-35.9, -28.9), (-38.2, -48.3), (-52.5, 5.7), (-28.5, -23.4), (-44.9, 12.7),
             (-6.8, 59.0), (41.3, -37.2), (33.5, 35.6), (38.0, 27.3), (10.3, -37.8), (-17.3, 63.8),
             (-48.8, -0.7), (11.7, 9.0), (17.0, 1.6))
ROCKS = ((11.4, 0.6), (32.1, -31.3), (37.1, -22.6), (33.9, -7.3), (2.9, 6.0), (0.6, 9.7), (-58.8, -43.0),
         (-30.2, -51.6), (-53.2, -36.8), (-50.7, -41.6), (-50.8, -35.6), (-54.0, -35.3), (-48.5, -39.5),
         (-58.3, -36.2))
BIG_ROCKS = ((-45.0, -47.7),)
SMALL_CRATES = ((38.1, -30.7), (37.1, -31.6), (1.5, 6.8), (0.6, 7.9), (1.8, 8.4))
FENCES = ((34.4, -34.7), (-1.4, 2.5), (-7.9, -47.4), (-10.7, -47.3), (-49.8, 26.1), (-55.1, 15.0), (-59.5, 6.4))
BUSHES = ((8.6, -0.6), (45.7, 2.5), (44.7, -5.6), (33.7, -1.7), (43.4, -15.9), (-3.7, 44.3), (38.6, -3.5),
          (36.7, -0.6), (36.2, -3.0), (37.0, 4.0))


def _ground(x: float, y: float) -> float:
    return TOP * land1.height(x, y)


def _things() -> tuple[Part, ...]:
    parts: list[Part] = []
    for i, (x, y) in enumerate(BIG_TREES):  # MORSE's brown trees: about 5 x 4 m and 8 m tall
        z = _ground(x, y)
        parts.append(block(f"tree_{i:02d}_trunk", (x - 0.3, y - 0.3, z - 0.3), (x + 0.3, y + 0.3, z + 4.0), BARK))
        parts.append(blob(f"tree_{i:02d}_crown", (x - 2.6, y - 2.1, z + 3.0), (x + 2.6, y + 2.1, z + 8.0), LEAVES))
    for i, (x, y) in enumerate(ROCKS):  # volcano_rock1: 1.9 x 2.1 x 1.3 m
        z = _ground(x, y)
        parts.append(blob(f"rock_{i:02d}", (x - 0.95, y - 1.05, z - 0.4), (x + 0.95, y + 1.05, z + 1.0), ROCK))
    for i, (x, y) in enumerate(BIG_ROCKS):  # volcano_rock2: 3.8 x 3.4 x 3.5 m
        z = _ground(x, y)
        parts.append(blob(f"big_rock_{i:02d}", (x - 1.9, y - 1.7, z - 0.8), (x + 1.9, y + 1.7, z + 2.8), ROCK))
    for i, (x, y) in enumerate(SMALL_CRATES):  # 1 m crates; MORSE stacks a second on two of them
        z = _ground(x, y)
        top = z + (2.0 if i in (0, 3) else 1.0)
        parts.append(block(f"small_crate_{i:02d}", (x - 0.5, y - 0.5, z - 0.2), (x + 0.5, y + 0.5, top), CRATE))
    x, y = 41.7, -28.7  # the large crate, 4 x 2 x 2 m
    parts.append(block("large_crate", (x - 2.0, y - 1.0, _ground(x, y) - 0.2), (x + 2.0, y + 1.0, _ground(x, y) + 2.0),
                       CRATE))
    x, y = 2.5, 2.6  # the open transport box, 2.1 x 1.3 x 0.9 m
    parts.append(block("transport_box", (x - 1.05, y - 0.65, -0.2), (x + 1.05, y + 0.65, _ground(x, y) + 0.88),
                       CRATE))
    for i, (x, y) in enumerate(FENCES):  # fence_long: 1.4 x 2.2 m, 0.86 m high
        z = _ground(x, y)
        parts.append(block(f"fence_{i:02d}", (x - 0.1, y - 1.1, z - 0.2), (x + 0.1, y + 1.1, z + 0.86), FENCE))
    for i, (x, y) in enumerate(BUSHES):  # furn_001: 3 x 3 m, 1.3 m high
        z = _ground(x, y)
        parts.append(blob(f"bush_{i:02d}", (x - 1.5, y - 1.5, z - 0.3), (x + 1.5, y + 1.5, z + 1.3), BUSH))
    return tuple(parts)


class Outdoors(Environment):
    """MORSE's `outdoors`: the land-1 countryside (121 x 148 m, x from -60.6 to 60.7 m, y from -74.6 to
    73.6 m, up to 4.15 m high, flat at z = 0 along the valley through the origin) with MORSE's town block of
    nine buildings on the northern plateau, 16 large trees, 15 rocks, crates and a transport box near the
    origin and to the south-east, fences and bushes. Everything stands on the ground and collides."""

    short_descr = "MORSE's outdoor scene: hills, a town block, trees, rocks, crates and fences"
    bounds = ((-60.6, -74.6, 0.0), (60.7, 73.6, TOP))
    terrain = land1.terrain(TOP, GRASS)
    layout = (*land1.buildings(land1.CITY_3, TOP, WALL), *_things())


COMPONENT = Outdoors
