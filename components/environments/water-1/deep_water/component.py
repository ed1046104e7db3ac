from morsec.component import Environment


class DeepWater(Environment):
    """Open deep water: a translucent water surface at z = 0 (200 m x 200 m, as MORSE's `Water` plane, which
    nothing collides with) under a sky, and no sea floor: for submarines and other robots that float
    (`NoGravity`) below or on the surface. MORSE's `water-1/deep_water`."""

    short_descr = "Open water, surface at z = 0, no sea floor (for submarines)"


COMPONENT = DeepWater
