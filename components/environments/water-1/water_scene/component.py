from morsec.component import Environment
from morsec.kits import land1
from morsec.kits.layout import rgba

TOP = 11.15  # m: the ground's highest point in MORSE's water_scene.blend
WATER_LEVEL = 4.2  # m: MORSE's Water plane, 126 x 126 m
SAND = rgba(0.55, 0.5, 0.36)


class Water1WaterScene(Environment):
    """MORSE's `water-1/water_scene`: a lake over the land-1 ground. The ground (121 x 148 m, x from -60.6
    to 60.7 m, y from -74.6 to 73.6 m) rises from z = 0 along the valley through the origin to 11.15 m on
    a northern plateau and a south-western hill; the water's surface, MORSE's `Water` plane, is at
    z = 4.2 m over x and y within ±63 m, light blue and half transparent, and nothing collides with it: the
    valley and the low ground to the south and east are under water, the plateau and the hill are islands.
    For submarines (`NoGravity`) under the surface and robots on the islands."""

    short_descr = "MORSE's lake: water 4.2 m deep in a valley between hills, for submarines"
    bounds = ((-60.6, -74.6, 0.0), (60.7, 73.6, TOP))
    terrain = land1.terrain(TOP, SAND)


COMPONENT = Water1WaterScene
