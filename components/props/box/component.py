from morsec.component import Prop


class Box(Prop):
    """A box whose full extents are the object's `size` [x, y, z] (MORSE's Cube)."""

    short_descr = "Box of a given size and colour"
    builder_name = "Cube"


COMPONENT = Box
