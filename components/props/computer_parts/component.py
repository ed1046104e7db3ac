from morsec.component import Prop
from morsec.kits.layout import PropPart, prop_object

DARK = (0.08, 0.08, 0.09)
METAL = (0.7, 0.7, 0.72)


class ComputerParts(Prop):
    """The objects of MORSE's props/computer_parts.blend, by their MORSE names: a computer tower (`cpu`), a
    `keyboard`, an open `laptop` and a `monitor`, each of MORSE's size and where MORSE's file puts it from its
    origin (the box is off-centre where MORSE's object is), static as in MORSE (they stay where they are put,
    on a desk). Their shape is their bounding box. MORSE's file gives them no game property."""

    short_descr = "MORSE's props/computer_parts: computer tower, keyboard, laptop, monitor"
    variants = {
        "cpu": prop_object((PropPart("body", (-0.177, -0.007, 0.02), (0.462, 0.212, 0.482)),), DARK, dynamic=False),
        "keyboard": prop_object((PropPart("body", (0.029, 0.021, 0.02), (0.248, 0.558, 0.053)),), DARK, dynamic=False),
        "laptop": prop_object((PropPart("body", (0.0, -0.085, 0.119), (0.321, 0.391, 0.458)),), METAL, dynamic=False),
        "monitor": prop_object((PropPart("body", (-0.027, 0.0, -0.031), (0.268, 0.512, 0.447)),), METAL,
                               dynamic=False),
    }


COMPONENT = ComputerParts
