from morsec.component import Prop


class Sphere(Prop):
    """A sphere of diameter `size[0]` (MORSE's Sphere)."""

    short_descr = "Sphere of a given size and colour"


COMPONENT = Sphere
