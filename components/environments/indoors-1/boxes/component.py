from morsec.component import Environment


class IndoorsBoxes(Environment):
    """A 10 m x 10 m room centred on the origin: floor at z = 0, four 2.5 m walls (inner faces at
    x = ±5 m and y = ±5 m, 0.2 m thick), no ceiling, six static boxes of different sizes in the four
    quadrants, away from the origin and from the axes. MORSE's `indoors-1/boxes`."""

    short_descr = "Room with walls and boxes"


COMPONENT = IndoorsBoxes
