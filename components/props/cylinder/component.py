from morsec.component import Prop


class Cylinder(Prop):
    """An upright cylinder: diameter `size[0]`, height `size[2]` (MORSE's Cylinder)."""

    short_descr = "Upright cylinder of a given size and colour"


COMPONENT = Cylinder
