from morsec.component import Environment
from morsec.kits import land1
from morsec.kits.layout import rgba

TOP = 2.83  # m: the ground's highest point in MORSE's trees.blend
GRASS = rgba(0.36, 0.5, 0.25)
WALL = rgba(1.0, 0.993, 0.719)  # MORSE's BuildingLightMat

# MORSE's 25 trees (the Tree objects of trees.blend): where each stands
TREES = ((-2.8, -7.9), (40.3, 15.6), (8.0, -18.8), (-7.7, 18.8), (-27.5, -8.7), (-10.2, -1.6), (12.6, -6.5),
         (14.4, 19.2), (6.1, 6.4), (-9.6, -18.2), (-29.5, 4.9), (22.2, -13.0), (21.5, 4.7), (26.3, -3.3),
         (28.2, -33.3), (46.0, -4.0), (0.8, -36.1), (-40.8, -24.2), (-36.5, 23.1), (-31.8, -43.9), (-17.1, -34.7),
         (45.0, -23.9), (8.3, -54.5), (-27.0, 49.3), (15.7, 58.9))


class Land1Trees(Environment):
    """MORSE's `land-1/trees`: 121 x 148 m of rolling grass (x from -60.6 to 60.7 m, y from -74.6 to 73.6 m)
    up to 2.83 m high, flat at z = 0 along the valley through the origin; 25 trees (a trunk 2.16 m high
    and a crown 2.3 m across, where MORSE's stand) and MORSE's town block of nine buildings on the plateau
    to the north (x from -12 to 58 m, y from 25 to 55 m). Everything collides; beyond the ground, nothing."""

    short_descr = "MORSE's countryside: rolling grass, 25 trees, a town block on a plateau"
    bounds = ((-60.6, -74.6, 0.0), (60.7, 73.6, TOP))
    terrain = land1.terrain(TOP, GRASS)
    layout = (*land1.trees(TREES, TOP), *land1.buildings(land1.CITY_3, TOP, WALL))


COMPONENT = Land1Trees
