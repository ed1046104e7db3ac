from morsec.component import Prop

# MORSE's props/objects.blend: a VHS cassette standing on its edge, 0.04 x 0.12 x 0.20 m, a rigid body of 1 kg,
# its origin at the bottom (a translate z of 0 stands it on the floor)
VIDEOTAPE = {"size": [0.04, 0.12, 0.2], "dynamic": True, "mass": 1.0}


class BlackVideotape(Prop):
    """A black videotape standing on its edge, 4 x 12 x 20 cm, 1 kg, that falls and can be pushed (a
    dynamic object); its origin is at the middle of its bottom face. MORSE's `BlackVideotape` of
    props/objects.blend, the object its gripper tests grab."""

    short_descr = "Black videotape (MORSE's props/objects BlackVideotape)"
    builder_name = "BlackVideotape"
    defaults = {**VIDEOTAPE, "color": [0.0, 0.0, 0.0]}


COMPONENT = BlackVideotape
