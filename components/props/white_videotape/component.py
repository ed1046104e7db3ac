from morsec.component import Prop

# MORSE's props/objects.blend: the same cassette as BlackVideotape, light grey
VIDEOTAPE = {"size": [0.04, 0.12, 0.2], "dynamic": True, "mass": 1.0}


class WhiteVideotape(Prop):
    """A white (light grey) videotape standing on its edge, 4 x 12 x 20 cm, 1 kg, that falls and can be
    pushed (a dynamic object); its origin is at the middle of its bottom face. MORSE's `WhiteVideotape` of
    props/objects.blend."""

    short_descr = "White videotape (MORSE's props/objects WhiteVideotape)"
    builder_name = "WhiteVideotape"
    defaults = {**VIDEOTAPE, "color": [0.753, 0.753, 0.753]}


COMPONENT = WhiteVideotape
