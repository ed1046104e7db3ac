from morsec.component import Prop


class RollingChair(Prop):
    """An office chair on a five-star base, 0.60 m wide, 0.64 m deep and 0.96 m tall, facing +y (its
    backrest towards -y), a dynamic object of 1 kg whose origin is on the floor under its column. Its shape
    is the four boxes MORSE's physics used for it (base, column, seat, backrest); `color` is the seat's
    and the backrest's, `size` scales the whole chair. MORSE's `RollingChair` of props/objects.blend."""

    short_descr = "Office chair on wheels (MORSE's props/objects RollingChair)"
    builder_name = "RollingChair"
    defaults = {"size": [0.6, 0.635, 0.958], "color": [0.093, 0.808, 0.584], "dynamic": True, "mass": 1.0}


COMPONENT = RollingChair
