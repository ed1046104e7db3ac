from morsec.component import Prop
from morsec.kits.layout import PropPart, prop_object

WOOD = (0.62, 0.5, 0.34)


class Crates(Prop):
    """The objects of MORSE's props/crates.blend, by their MORSE names: an open large crate (4 x 2 x 2 m,
    80 kg), its lid, a closed small crate (1 m cube, 20 kg) and an open transport box (2.05 x 1.3 x 0.88 m,
    20 kg), with MORSE's masses and origins (on the floor under the crate; the lid's at its centre) and the
    walls and bottoms of MORSE's collision shape, so that things go into the open ones. Dynamic, as MORSE's
    rigid bodies. MORSE's file gives them no game property."""

    short_descr = "MORSE's props/crates: large crate and its lid, small crate, transport box"
    variants = {
        "large_crate": prop_object((
            PropPart("wall_south", (0.012, -0.957, 0.996), (4.007, 0.114, 2.0)),
            PropPart("wall_north", (0.012, 0.949, 0.996), (4.007, 0.114, 2.0)),
            PropPart("wall_west", (-1.946, -0.01, 0.996), (0.114, 1.996, 2.0)),
            PropPart("wall_east", (1.947, -0.01, 0.996), (0.114, 1.996, 2.0)),
            PropPart("bottom", (-0.003, -0.01, 0.14), (3.907, 1.996, 0.278)),
        ), WOOD, mass=80.0),
        "cap_large_crate": prop_object((PropPart("body", (0.0, 0.0, 0.0), (3.876, 1.938, 0.083)),), WOOD),
        "small_crate": prop_object((PropPart("body", (0.0, 0.0, 0.5), (1.0, 1.0, 1.0)),), WOOD, mass=20.0),
        "transport_box": prop_object((
            PropPart("wall_south", (0.0, -0.641, 0.444), (2.052, 0.032, 0.871)),
            PropPart("wall_west", (-1.037, -0.01, 0.444), (0.032, 1.298, 0.871)),
            PropPart("wall_east", (1.027, -0.01, 0.444), (0.032, 1.298, 0.871)),
            PropPart("bottom", (0.0, 0.0, 0.025), (2.052, 1.249, 0.047)),
        ), WOOD, mass=20.0),
    }


COMPONENT = Crates
