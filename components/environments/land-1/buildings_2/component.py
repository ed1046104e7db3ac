from dataclasses import replace

from morsec.component import Environment
from morsec.kits import land1
from morsec.kits.layout import rgba

TOP = 2.83  # m: the ground's highest point in MORSE's buildings_2.blend
GRASS = rgba(0.36, 0.5, 0.25)
WALL = rgba(1.0, 0.993, 0.719)
HOUSE = rgba(0.86, 0.8, 0.7)

# MORSE's 15 trees (its Tree objects)
TREES = ((2.8, -1.3), (6.2, -4.8), (8.1, -0.7), (5.4, 3.1), (-5.4, -1.3), (-10.2, -1.6), (12.6, -6.5), (20.4, -9.8),
         (2.5, 1.6), (9.8, -3.6), (-29.5, 4.9), (22.2, -13.0), (17.9, -12.4), (26.3, -3.3), (28.2, -33.3))
# its six apartment buildings (buildingA ... buildingF): where each stands (the corner of its 10.7 x 11.2 m
# floor plan, 1.7 m west and 5.6 m south of that point) and its height (2.2 m a storey, and the roof)
HOUSES = (("buildingA", (32.9, -54.9), 14.5), ("buildingB", (45.9, -48.7), 14.5), ("buildingC", (-38.6, -3.9), 14.5),
          ("buildingD", (-24.5, -2.3), 7.0), ("buildingE", (33.1, -67.6), 7.0), ("buildingF", (45.9, -30.7), 9.0))


def _houses(top: float):
    footprints = tuple(((x - 1.7, y - 5.6), (x + 9.0, y + 5.55), tall) for _, (x, y), tall in HOUSES)
    parts = land1.buildings(footprints, top, HOUSE)
    return tuple(replace(part, name=name) for (name, _, _), part in zip(HOUSES, parts))


class Land1Buildings2(Environment):
    """MORSE's `land-1/buildings_2`: the land-1 countryside (121 x 148 m, x from -60.6 to 60.7 m, y from
    -74.6 to 73.6 m, up to 2.83 m high, flat at z = 0 along the valley through the origin) with 15 trees
    around the origin, MORSE's town block of nine buildings on the northern plateau and its six apartment
    buildings (buildingA ... buildingF, 10.7 x 11.2 m, two to six storeys) to the south-east and west.
    Everything collides."""

    short_descr = "MORSE's countryside with trees, a town block and six apartment buildings"
    bounds = ((-60.6, -74.6, 0.0), (60.7, 73.6, TOP))
    terrain = land1.terrain(TOP, GRASS)
    layout = (*land1.trees(TREES, TOP),
              *land1.buildings(land1.CITY_3, TOP, WALL), *_houses(TOP))


COMPONENT = Land1Buildings2
