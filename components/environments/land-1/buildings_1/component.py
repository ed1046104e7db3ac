from morsec.component import Environment
from morsec.kits import land1
from morsec.kits.layout import rgba

TOP = 11.15  # m: the ground's highest point in MORSE's buildings_1.blend
GRASS = rgba(0.36, 0.5, 0.25)
WALL = rgba(1.0, 0.993, 0.719)  # MORSE's BuildingLightMat


class Land1Buildings1(Environment):
    """MORSE's `land-1/buildings_1`: the land-1 countryside at its highest (121 x 148 m, x from -60.6 to
    60.7 m, y from -74.6 to 73.6 m, hills up to 11.15 m; flat at z = 0 along the valley through the origin)
    with MORSE's three town blocks (its City.1, City.2 and City.3: 31 buildings, 3 to 31 m tall) on the
    plateau to the north, west of the origin and on the southern hills; around the ground, a plane 0.5 m
    below it (MORSE's 600 m Plane). Buildings are boxes the size of MORSE's; everything collides."""

    short_descr = "MORSE's countryside with three town blocks (31 buildings) on high hills"
    bounds = ((-60.6, -74.6, 0.0), (60.7, 73.6, TOP))
    terrain = land1.terrain(TOP, GRASS)
    layout = land1.buildings(land1.CITY_1_2_3, TOP, WALL)


COMPONENT = Land1Buildings1
