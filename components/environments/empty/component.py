from morsec.component import Environment


class Empty(Environment):
    """A flat, infinite ground plane at z = 0, lit from above. MORSE's `empty` environment."""

    short_descr = "Flat ground plane"


COMPONENT = Empty
