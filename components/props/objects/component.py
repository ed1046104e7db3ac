from morsec.component import Prop
from morsec.kits.layout import PropPart, prop_object

BLACK = (0.05, 0.05, 0.05, 1.0)
GREY = (0.34, 0.34, 0.34, 1.0)
TAPE = (PropPart("body", (0.0, 0.0, 0.1), (0.04, 0.12, 0.2)),)  # a VHS cassette standing on its edge


def _desk(top: float, width: float, depth: float) -> tuple[PropPart, ...]:
    """MORSE's Desk collision shape: a top on four legs, tied by two low rails."""
    legs = tuple(PropPart(f"leg_{i}", (x, y, 0.31), (0.052, 0.057, 0.621))
                 for i, (x, y) in enumerate(((0.762, 0.333), (0.76, -0.383), (-0.767, -0.383), (-0.767, 0.333)), 1))
    rails = tuple(PropPart(f"rail_{i}", (x, -0.024, 0.202), (0.052, 0.722, 0.039))
                  for i, x in enumerate((-0.763, 0.76), 1))
    return (PropPart("top", (-0.001, -0.026, top), (width, depth, 0.114)), *legs, *rails)


class Objects(Prop):
    """The objects of MORSE's props/objects.blend, by their MORSE names: videotapes, toy trash bins, a box
    stand, a desk, a shelf, a rolling chair and a small table. Each has MORSE's size, mass (1 kg, a rigid body
    that falls and can be pushed; the small table stands still, as in MORSE) and origin (on the floor under
    the object: `translate` z = 0 stands it there); its shape is the boxes of MORSE's collision shape, or its
    bounding box. MORSE's file gives them no game property: `setgraspable()` or `properties:` tags them."""

    short_descr = "MORSE's props/objects: videotapes, trash bins, desk, shelf, rolling chair, small table"
    variants = {
        "BlackVideotape": prop_object(TAPE, (0.0, 0.0, 0.0)),
        "WhiteVideotape": prop_object(TAPE, (0.753, 0.753, 0.753)),
        "GreyVideotape": prop_object(TAPE, (0.8, 0.8, 0.8)),
        "BlueToyTrashbin": prop_object((PropPart("body", (0.0, 0.0, 0.139), (0.37, 0.37, 0.277), "cylinder"),),
                                       (0.063, 0.545, 0.796)),
        "PinkToyTrashbin": prop_object((PropPart("body", (0.0, 0.0, 0.089), (0.278, 0.278, 0.177), "cylinder"),),
                                       (0.76, 0.51, 0.8)),
        "BoxStand": prop_object((PropPart("body", (0.0, 0.0, 0.313), (0.267, 0.349, 0.626)),), (0.9, 0.9, 0.88)),
        "Desk": prop_object(_desk(0.671, 1.648, 0.792), (0.884, 0.884, 0.884)),
        "IKEAShelf": prop_object((PropPart("body", (0.0, 0.0, 0.394), (1.184, 1.185, 0.788)),), (0.478, 0.34, 0.094)),
        # MORSE's RollingChair: its four collision boxes, facing +y (its backrest towards -y)
        "RollingChair": prop_object((
            PropPart("base", (0.0, -0.029, 0.0355), (0.597, 0.447, 0.071), rgba=BLACK),
            PropPart("column", (0.0, 0.010, 0.226), (0.08, 0.067, 0.351), rgba=GREY),
            PropPart("seat", (0.0, 0.051, 0.441), (0.53, 0.423, 0.071)),
            PropPart("backrest", (0.0, -0.2225, 0.725), (0.542, 0.3, 0.466)),
        ), (0.093, 0.808, 0.584)),
        "SmallTable": prop_object((PropPart("body", (0.0, 0.0, 0.375), (0.65, 1.1, 0.75)),), (0.884, 0.884, 0.884),
                                  dynamic=False),
    }


COMPONENT = Objects
